; The kitchen domain: a single arm moves boxes between open surfaces and a
; drawer that has to be opened first. Object, predicate and action names are
; part of the project's contract (other problem files and the kitchen map use
; them), so change them only together with src/kitchen_tamp/kitchen.
(define (domain kitchen)
  (:requirements :strips :typing :negative-preconditions)
  (:types surface openable box)
  (:predicates
    (holding ?b - box)
    (boxOn ?b - box ?s - surface)
    (opened ?o - openable)
    (boxIn ?b - box ?o - openable)
    (surfClear ?s - surface)
    (cabClear ?o - openable)
    (armClear))

  (:action open
    :parameters (?o - openable)
    :precondition (and (armClear) (not (opened ?o)))
    :effect (opened ?o))

  (:action pickUp
    :parameters (?b - box ?s - surface)
    :precondition (and (boxOn ?b ?s) (armClear))
    :effect (and (holding ?b) (surfClear ?s)
                 (not (boxOn ?b ?s)) (not (armClear))))

  (:action cabPickUp
    :parameters (?b - box ?o - openable)
    :precondition (and (boxIn ?b ?o) (opened ?o) (armClear))
    :effect (and (holding ?b) (cabClear ?o)
                 (not (boxIn ?b ?o)) (not (armClear))))

  (:action placeOn
    :parameters (?b - box ?s - surface)
    :precondition (and (holding ?b) (surfClear ?s))
    :effect (and (boxOn ?b ?s) (armClear)
                 (not (holding ?b)) (not (surfClear ?s))))

  (:action placeIn
    :parameters (?b - box ?o - openable)
    :precondition (and (holding ?b) (opened ?o) (cabClear ?o))
    :effect (and (boxIn ?b ?o) (armClear)
                 (not (holding ?b)) (not (cabClear ?o)))))
