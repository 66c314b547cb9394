; A baguette in a long box (6 x 6 x 50 cm) goes from the countertop into the drawer.
; It is longer than the drawer's diagonal, so it only fits standing up, and then the
; hand must hold it near its upper end to stay above the drawer's walls. A grasp near
; the other end is collision-free to pick but leaves no way to put the box in the
; drawer: greedy refinement, which never revisits the pick, fails; backtracking
; re-grasps and succeeds. (tests/refinement/test_geometric_backtracking.py)
(define (problem kitchen-baguette-into-drawer)
  (:domain kitchen)
  (:objects
    stove countertop - surface
    drawer - openable
    baguette - box)
  (:init
    (boxOn baguette countertop)
    (surfClear stove)
    (cabClear drawer)
    (armClear))
  (:goal (and (boxIn baguette drawer))))
