(define (problem achievers) (:domain achievers)
  (:init (start))
  (:goal (goal)))
