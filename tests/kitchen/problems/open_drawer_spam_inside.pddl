; The drawer starts open with the spam inside; swap it with the sugar.
(define (problem kitchen-open-drawer)
  (:domain kitchen)
  (:objects
    stove countertop - surface
    drawer - openable
    sugar spam - box)
  (:init
    (opened drawer)
    (boxIn spam drawer)
    (boxOn sugar countertop)
    (surfClear stove)
    (armClear))
  (:goal (and (boxIn sugar drawer) (boxOn spam stove))))
