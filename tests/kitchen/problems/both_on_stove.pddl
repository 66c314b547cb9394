; Both boxes share the stove; the drawer is closed and empty.
(define (problem kitchen-both-on-stove)
  (:domain kitchen)
  (:objects
    stove countertop - surface
    drawer - openable
    sugar spam - box)
  (:init
    (boxOn sugar stove)
    (boxOn spam stove)
    (surfClear countertop)
    (cabClear drawer)
    (armClear))
  (:goal (and (boxOn spam countertop) (boxIn sugar drawer))))
