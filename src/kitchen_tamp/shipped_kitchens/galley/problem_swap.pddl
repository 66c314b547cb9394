; Swap sugar (stove) and spam (countertop) in the galley. The side table holds the tea and
; the right drawer the jam, so the only free place is the left drawer: it has to be opened
; and used as a temporary place (7 actions).
(define (problem galley-swap)
  (:domain kitchen)
  (:objects
    stove countertop table - surface
    left_drawer right_drawer - openable
    sugar spam tea jam - box)
  (:init
    (boxOn sugar stove)
    (boxOn spam countertop)
    (boxOn tea table)
    (boxIn jam right_drawer)
    (cabClear left_drawer)
    (armClear))
  (:goal (and
    (boxOn sugar countertop)
    (boxOn spam stove))))
