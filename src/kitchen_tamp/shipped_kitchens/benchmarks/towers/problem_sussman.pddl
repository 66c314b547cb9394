; The Sussman anomaly: c stands on a, b on the table; build the tower a on b on c. Achieving
; the two goals one after the other undoes the first: c must come off a, b go onto c, then a
; onto b (6 actions).
(define (problem towers-sussman)
  (:domain kitchen-regions)
  (:objects
    table - region
    a b c - item)
  (:init
    (on a table)
    (on b table)
    (on c a)
    (clear b)
    (clear c)
    (handempty))
  (:goal (and
    (on a b)
    (on b c))))
