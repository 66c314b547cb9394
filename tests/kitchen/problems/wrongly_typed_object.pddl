; Calls the sugar a surface, which is a box in the default kitchen.
(define (problem kitchen-wrongly-typed-object)
  (:domain kitchen)
  (:objects
    stove countertop sugar - surface
    drawer - openable
    spam - box)
  (:init
    (boxOn spam countertop)
    (surfClear stove)
    (surfClear sugar)
    (cabClear drawer)
    (armClear))
  (:goal (and (boxOn spam stove))))
