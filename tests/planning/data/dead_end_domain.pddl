; A trap for enforced hill climbing. Taking (a) looks like progress (h_FF drops
; from 3 to 2) but uses up the only token, and getting (b) afterwards costs (a)
; again: a dead end that the delete relaxation cannot see. The only real plan
; is the four-step detour l1..l4.
(define (domain trap)
  (:requirements :strips)
  (:predicates (token) (a) (b) (key) (s1) (s2) (s3))
  (:action take-a :parameters () :precondition (token) :effect (and (a) (not (token))))
  (:action get-key :parameters () :precondition (a) :effect (and (key) (not (a))))
  (:action use-key :parameters () :precondition (key) :effect (b))
  (:action l1 :parameters () :precondition (token) :effect (s1))
  (:action l2 :parameters () :precondition (s1) :effect (s2))
  (:action l3 :parameters () :precondition (s2) :effect (s3))
  (:action l4 :parameters () :precondition (s3) :effect (and (a) (b))))
