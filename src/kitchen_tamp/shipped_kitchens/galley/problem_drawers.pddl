; One box into each drawer: spam into the left one, sugar into the right one (6 actions).
(define (problem galley-both-drawers)
  (:domain kitchen)
  (:objects
    stove countertop table - surface
    left_drawer right_drawer - openable
    sugar spam - box)
  (:init
    (boxOn sugar stove)
    (boxOn spam countertop)
    (surfClear table)
    (cabClear left_drawer)
    (cabClear right_drawer)
    (armClear))
  (:goal (and
    (boxIn spam left_drawer)
    (boxIn sugar right_drawer))))
