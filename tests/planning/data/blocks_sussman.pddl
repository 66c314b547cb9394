; The Sussman anomaly: C on A, goal A on B on C. Optimal length 6.
(define (problem sussman)
  (:domain blocks)
  (:objects a b c)
  (:init (on c a) (ontable a) (ontable b) (clear c) (clear b) (handempty))
  (:goal (and (on a b) (on b c))))
