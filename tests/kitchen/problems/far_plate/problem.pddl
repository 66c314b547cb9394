; The green block onto the near plate; the far plate is out of reach.
(define (problem far)
  (:domain kitchen-regions)
  (:objects table plate far_plate - region green - item)
  (:init (on green table) (clear green) (handempty))
  (:goal (on green plate)))
