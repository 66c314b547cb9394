; Reverse a tower of three: a on b on c becomes c on b on a (6 actions); every block is moved,
; the bottom one only after the two above it are set down somewhere.
(define (problem towers-reversal)
  (:domain kitchen-regions)
  (:objects
    table - region
    a b c - item)
  (:init
    (on c table)
    (on b c)
    (on a b)
    (clear a)
    (handempty))
  (:goal (and
    (on c b)
    (on b a))))
