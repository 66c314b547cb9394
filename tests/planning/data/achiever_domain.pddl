; Two achievers of (goal) first fire in the same relaxed layer; the one listed
; first needs two facts of layer 1, the other one. FF picks the easier one by
; difficulty (sum of the preconditions' first layers): a relaxed plan of 2.
(define (domain achievers)
  (:requirements :strips)
  (:predicates (start) (c) (e) (goal))
  (:action make-c :parameters () :precondition (start) :effect (c))
  (:action make-e :parameters () :precondition (start) :effect (e))
  (:action hard-way :parameters () :precondition (and (c) (e)) :effect (goal))
  (:action easy-way :parameters () :precondition (c) :effect (goal)))
