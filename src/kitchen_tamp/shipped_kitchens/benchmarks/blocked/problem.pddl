; The green block onto the plate. The shortest plan (2 actions) picks it where it stands, which
; no grasp can: the blocker in the nook's opening has to be moved first (4 actions).
(define (problem blocked-green)
  (:domain kitchen-regions)
  (:objects
    table plate - region
    green blocker - item)
  (:init
    (on green table)
    (on blocker table)
    (clear green)
    (clear blocker)
    (handempty))
  (:goal (on green plate)))
