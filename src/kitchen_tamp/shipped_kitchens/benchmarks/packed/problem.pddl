; All five blocks onto the small plate (10 actions). Each placement must leave room for the
; blocks still to come: sampled poses that ignore the rest fill the plate after three or four.
(define (problem packed-five)
  (:domain kitchen-regions)
  (:objects
    table plate - region
    block1 block2 block3 block4 block5 - item)
  (:init
    (on block1 table)
    (on block2 table)
    (on block3 table)
    (on block4 table)
    (on block5 table)
    (clear block1)
    (clear block2)
    (clear block3)
    (clear block4)
    (clear block5)
    (handempty))
  (:goal (and
    (on block1 plate)
    (on block2 plate)
    (on block3 plate)
    (on block4 plate)
    (on block5 plate))))
