; Reverse a tower of four blocks: d on c on b on a  ->  a on b on c on d.
(define (problem reverse-tower)
  (:domain blocks)
  (:objects a b c d)
  (:init (ontable a) (on b a) (on c b) (on d c) (clear d) (handempty))
  (:goal (and (on a b) (on b c) (on c d))))
