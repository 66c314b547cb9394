; Blue targets to the blue region, red ones to the red region (10 actions if nothing were in
; the way; the clutter around them has to be moved first).
(define (problem sort-clutter)
  (:domain kitchen-regions)
  (:objects
    table blue_region red_region - region
    blue1 red1 blue2 red2 blue3 clutter1 clutter2 clutter3 clutter4 - item)
  (:init
    (on blue1 table)
    (on red1 table)
    (on blue2 table)
    (on red2 table)
    (on blue3 table)
    (on clutter1 table)
    (on clutter2 table)
    (on clutter3 table)
    (on clutter4 table)
    (clear blue1)
    (clear red1)
    (clear blue2)
    (clear red2)
    (clear blue3)
    (clear clutter1)
    (clear clutter2)
    (clear clutter3)
    (clear clutter4)
    (handempty))
  (:goal (and
    (on blue1 blue_region)
    (on blue2 blue_region)
    (on blue3 blue_region)
    (on red1 red_region)
    (on red2 red_region))))
