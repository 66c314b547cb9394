; Names a box the kitchen does not have.
(define (problem kitchen-unknown-object)
  (:domain kitchen)
  (:objects
    stove countertop - surface
    drawer - openable
    sugar spam soup - box)
  (:init
    (boxOn sugar stove)
    (boxOn spam countertop)
    (boxOn soup countertop)
    (cabClear drawer)
    (armClear))
  (:goal (and (boxOn soup stove))))
