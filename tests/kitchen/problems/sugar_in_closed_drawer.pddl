; The sugar starts in the closed drawer and must go onto the stove.
(define (problem kitchen-sugar-from-drawer)
  (:domain kitchen)
  (:objects
    stove countertop - surface
    drawer - openable
    sugar spam - box)
  (:init
    (boxIn sugar drawer)
    (boxOn spam countertop)
    (surfClear stove)
    (armClear))
  (:goal (and (boxOn sugar stove) (boxOn spam countertop))))
