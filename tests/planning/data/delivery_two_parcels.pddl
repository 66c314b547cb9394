; Two parcels to move with a van (the truck is broken). The van must refuel
; at the depot first. Optimal length 9 (found by BFS and A*).
(define (problem two-parcels)
  (:domain delivery)
  (:objects north south - place
            lorry - truck
            vw - van
            p1 p2 - parcel)
  (:init (road depot north) (road north depot) (road north south) (road south north)
         (at vw depot) (at lorry north) (broken lorry)
         (at p1 north) (at p2 south))
  (:goal (and (at p1 south) (at p2 depot) (not (in p1 vw)))))
