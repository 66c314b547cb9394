; Leaves out (surfClear countertop) although nothing stands on the countertop.
(define (problem kitchen-mismatched-init)
  (:domain kitchen)
  (:objects
    stove countertop - surface
    drawer - openable
    sugar spam - box)
  (:init
    (boxOn sugar stove)
    (boxOn spam stove)
    (cabClear drawer)
    (armClear))
  (:goal (and (boxOn sugar countertop))))
