(define (problem tempting)
  (:domain trap)
  (:init (token))
  (:goal (and (a) (b))))
