; A small typed logistics-like domain with a type hierarchy, a domain constant
; (the depot), equality, negative preconditions and a static road map.
(define (domain delivery)
  (:requirements :strips :typing :equality :negative-preconditions)
  (:types place - object
          vehicle parcel - locatable
          truck van - vehicle
          locatable - object)
  (:constants depot - place)
  (:predicates (at ?l - locatable ?p - place)
               (in ?x - parcel ?v - vehicle)
               (road ?from ?to - place)
               (broken ?v - vehicle)
               (fuelled ?v - vehicle))
  (:action drive
    :parameters (?v - vehicle ?from ?to - place)
    :precondition (and (at ?v ?from) (road ?from ?to) (not (= ?from ?to)) (not (broken ?v)))
    :effect (and (not (at ?v ?from)) (at ?v ?to)))
  (:action refuel
    :parameters (?v - vehicle)
    :precondition (and (at ?v depot) (not (fuelled ?v)))
    :effect (fuelled ?v))
  (:action load
    :parameters (?x - parcel ?v - vehicle ?p - place)
    :precondition (and (at ?x ?p) (at ?v ?p) (fuelled ?v))
    :effect (and (not (at ?x ?p)) (in ?x ?v)))
  (:action unload
    :parameters (?x - parcel ?v - vehicle ?p - place)
    :precondition (and (in ?x ?v) (at ?v ?p))
    :effect (and (not (in ?x ?v)) (at ?x ?p))))
