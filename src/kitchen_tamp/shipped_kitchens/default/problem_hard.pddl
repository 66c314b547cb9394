; Swap the two boxes: sugar from the stove to the countertop and spam from the
; countertop to the stove. Each surface holds one box, so one of them has to
; wait in the drawer, which must be opened first.
(define (problem kitchen-swap)
  (:domain kitchen)
  (:objects
    stove countertop - surface
    drawer - openable
    sugar spam - box)
  (:init
    (boxOn sugar stove)
    (boxOn spam countertop)
    (cabClear drawer)
    (armClear))
  (:goal (and
    (boxOn sugar countertop)
    (boxOn spam stove))))
