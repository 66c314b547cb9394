(define (problem helpful-trap) (:domain helpful-trap)
  (:init (ready))
  (:goal (done)))
