; The class project's task: put the sugar on the countertop and the spam in
; the drawer. The spam stands where the sugar must go, and the drawer starts
; closed, so the shortest plan opens the drawer, moves the spam into it and
; then the sugar onto the countertop (5 actions).
(define (problem kitchen-put-away)
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
    (boxIn spam drawer))))
