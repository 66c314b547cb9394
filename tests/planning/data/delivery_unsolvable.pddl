; A parcel cannot be in two places at once. Every goal atom is reachable on its
; own, so grounding cannot tell; only exhausting the reachable states proves it.
(define (problem two-places)
  (:domain delivery)
  (:objects north - place vw - van p1 - parcel)
  (:init (road depot north) (road north depot) (at vw depot) (at p1 north))
  (:goal (and (at p1 depot) (at p1 north))))
