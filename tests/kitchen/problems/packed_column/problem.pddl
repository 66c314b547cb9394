; The fifth block onto the plate, where only the free column has room.
(define (problem packed-column)
  (:domain kitchen-regions)
  (:objects table plate - region block1 block2 block3 block4 block5 - item)
  (:init
    (on block1 plate) (on block2 plate) (on block3 plate) (on block4 plate) (on block5 table)
    (clear block1) (clear block2) (clear block3) (clear block4) (clear block5) (handempty))
  (:goal (on block5 plate)))
