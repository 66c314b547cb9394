; Put the tea from the side table away into the right drawer and set the jam from the
; stove on the table (5 actions).
(define (problem galley-tidy)
  (:domain kitchen)
  (:objects
    stove countertop table - surface
    left_drawer right_drawer - openable
    sugar tea jam - box)
  (:init
    (boxOn jam stove)
    (boxOn sugar countertop)
    (boxOn tea table)
    (cabClear left_drawer)
    (cabClear right_drawer)
    (armClear))
  (:goal (and
    (boxIn tea right_drawer)
    (boxOn jam table))))
