; A trap for helpful actions. From the start the relaxed plan is (commit) then
; (finish-committed): commit is the only helpful action, but it deletes (ready),
; which finish-committed also needs, so it leads to a dead end. Enforced hill
; climbing must then retry with every action and find (prepare) (finish-prepared).
(define (domain helpful-trap)
  (:requirements :strips)
  (:predicates (ready) (committed) (prepared) (done))
  (:action finish-committed :parameters ()
    :precondition (and (committed) (ready)) :effect (done))
  (:action commit :parameters ()
    :precondition (ready) :effect (and (committed) (not (ready))))
  (:action prepare :parameters ()
    :precondition (ready) :effect (prepared))
  (:action finish-prepared :parameters ()
    :precondition (prepared) :effect (done)))
