; Each box onto the plate of its colour. The shortest plan (4 actions) picks each box where it
; stands; the blocker in front of it must be moved first (6-8 actions).
(define (problem nonmonotonic-swap)
  (:domain kitchen-regions)
  (:objects
    table red_plate blue_plate - region
    red_box blue_box red_blocker blue_blocker - item)
  (:init
    (on red_box table)
    (on blue_box table)
    (on red_blocker table)
    (on blue_blocker table)
    (clear red_box)
    (clear blue_box)
    (clear red_blocker)
    (clear blue_blocker)
    (handempty))
  (:goal (and
    (on red_box red_plate)
    (on blue_box blue_plate))))
