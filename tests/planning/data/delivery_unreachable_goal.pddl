; A goal on a static predicate that is false: unsolvable before any search.
(define (problem no-road)
  (:domain delivery)
  (:objects north - place vw - van p1 - parcel)
  (:init (at vw depot) (at p1 north))
  (:goal (and (road north depot) (at p1 depot))))
