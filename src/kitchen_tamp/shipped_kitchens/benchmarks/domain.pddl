; The kitchen with regions: a surface, a region on it (a plate, a tray, a sink, a burner) or a
; drawer holds as many items as fit, and items stack on items. Which of them fit where, and what
; is in the way, is geometry's to say (the skills fail with "full" or name the obstructing items),
; not this domain's: it has no capacity predicates. Ψ derives every atom from the simulated
; scene (domain.binding.toml beside this file says how); clean and cooked are conditions the
; scene keeps, set by wash and cook.
(define (domain kitchen-regions)
  (:requirements :strips :typing :negative-preconditions)
  (:types
    support drawer - object
    region item - support
    sink burner - region)
  (:predicates
    (on ?o - item ?s - support)
    (in ?o - item ?d - drawer)
    (clear ?o - item)
    (holding ?o - item)
    (handempty)
    (opened ?d - drawer)
    (clean ?o - item)
    (cooked ?o - item))

  (:action open
    :parameters (?d - drawer)
    :precondition (and (handempty) (not (opened ?d)))
    :effect (opened ?d))

  (:action pick
    :parameters (?o - item ?r - region)
    :precondition (and (on ?o ?r) (clear ?o) (handempty))
    :effect (and (holding ?o) (not (on ?o ?r)) (not (clear ?o)) (not (handempty))))

  (:action take-out
    :parameters (?o - item ?d - drawer)
    :precondition (and (in ?o ?d) (opened ?d) (clear ?o) (handempty))
    :effect (and (holding ?o) (not (in ?o ?d)) (not (clear ?o)) (not (handempty))))

  (:action unstack
    :parameters (?o - item ?b - item)
    :precondition (and (on ?o ?b) (clear ?o) (handempty))
    :effect (and (holding ?o) (clear ?b) (not (on ?o ?b)) (not (clear ?o)) (not (handempty))))

  (:action place
    :parameters (?o - item ?r - region)
    :precondition (holding ?o)
    :effect (and (on ?o ?r) (clear ?o) (handempty) (not (holding ?o))))

  (:action put-in
    :parameters (?o - item ?d - drawer)
    :precondition (and (holding ?o) (opened ?d))
    :effect (and (in ?o ?d) (clear ?o) (handempty) (not (holding ?o))))

  (:action stack
    :parameters (?o - item ?b - item)
    :precondition (and (holding ?o) (clear ?b))
    :effect (and (on ?o ?b) (clear ?o) (handempty) (not (holding ?o)) (not (clear ?b))))

  (:action wash
    :parameters (?o - item ?r - sink)
    :precondition (on ?o ?r)
    :effect (clean ?o))

  (:action cook
    :parameters (?o - item ?r - burner)
    :precondition (and (on ?o ?r) (clean ?o))
    :effect (cooked ?o)))
