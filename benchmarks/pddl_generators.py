"""Benchmark PDDL problems: seeded generators (blocks world, gripper, a scaled kitchen) and real IPC files.

Each returns (domain text, problem text). The generated domains are plain
STRIPS with typing so that every peer planner parses them; the IPC problems
(``benchmarks/ipc/``, sources in its README) are STRIPS with typing too.
"""

from __future__ import annotations

import itertools
from pathlib import Path

import numpy as np

IPC_DIR = Path(__file__).resolve().parent / "ipc"
KITCHEN_PROBLEMS = Path(__file__).resolve().parents[1] / "pddl"

BLOCKS_DOMAIN = """(define (domain blocks)
  (:requirements :strips)
  (:predicates (on ?x ?y) (ontable ?x) (clear ?x) (handempty) (holding ?x))
  (:action pick-up :parameters (?x)
    :precondition (and (clear ?x) (ontable ?x) (handempty))
    :effect (and (not (ontable ?x)) (not (clear ?x)) (not (handempty)) (holding ?x)))
  (:action put-down :parameters (?x)
    :precondition (holding ?x)
    :effect (and (not (holding ?x)) (clear ?x) (handempty) (ontable ?x)))
  (:action stack :parameters (?x ?y)
    :precondition (and (holding ?x) (clear ?y))
    :effect (and (not (holding ?x)) (not (clear ?y)) (clear ?x) (handempty) (on ?x ?y)))
  (:action unstack :parameters (?x ?y)
    :precondition (and (on ?x ?y) (clear ?x) (handempty))
    :effect (and (holding ?x) (clear ?y) (not (clear ?x)) (not (handempty)) (not (on ?x ?y)))))
"""

GRIPPER_DOMAIN = """(define (domain gripper)
  (:requirements :strips :typing)
  (:types room ball gripper)
  (:predicates (at-robby ?r - room) (at ?b - ball ?r - room) (free ?g - gripper)
               (carry ?b - ball ?g - gripper))
  (:action move :parameters (?from ?to - room)
    :precondition (at-robby ?from)
    :effect (and (at-robby ?to) (not (at-robby ?from))))
  (:action pick :parameters (?b - ball ?r - room ?g - gripper)
    :precondition (and (at ?b ?r) (at-robby ?r) (free ?g))
    :effect (and (carry ?b ?g) (not (at ?b ?r)) (not (free ?g))))
  (:action drop :parameters (?b - ball ?r - room ?g - gripper)
    :precondition (and (carry ?b ?g) (at-robby ?r))
    :effect (and (at ?b ?r) (free ?g) (not (carry ?b ?g)))))
"""

KITCHEN_STRIPS_DOMAIN = """(define (domain kitchen)
  (:requirements :strips :typing)
  (:types surface openable box)
  (:predicates (holding ?b - box) (boxOn ?b - box ?s - surface) (opened ?o - openable)
               (boxIn ?b - box ?o - openable) (surfClear ?s - surface)
               (cabClear ?o - openable) (armClear))
  (:action open :parameters (?o - openable)
    :precondition (armClear) :effect (opened ?o))
  (:action pickUp :parameters (?b - box ?s - surface)
    :precondition (and (boxOn ?b ?s) (armClear))
    :effect (and (holding ?b) (surfClear ?s) (not (boxOn ?b ?s)) (not (armClear))))
  (:action cabPickUp :parameters (?b - box ?o - openable)
    :precondition (and (boxIn ?b ?o) (opened ?o) (armClear))
    :effect (and (holding ?b) (cabClear ?o) (not (boxIn ?b ?o)) (not (armClear))))
  (:action placeOn :parameters (?b - box ?s - surface)
    :precondition (and (holding ?b) (surfClear ?s))
    :effect (and (boxOn ?b ?s) (armClear) (not (holding ?b)) (not (surfClear ?s))))
  (:action placeIn :parameters (?b - box ?o - openable)
    :precondition (and (holding ?b) (opened ?o) (cabClear ?o))
    :effect (and (boxIn ?b ?o) (armClear) (not (holding ?b)) (not (cabClear ?o)))))
"""
"""The kitchen domain without ``open``'s negative precondition, which pyperplan cannot parse."""


def kitchen_problem(problem: str) -> tuple[str, str]:
    """A shipped kitchen problem with ``KITCHEN_STRIPS_DOMAIN``: pyperplan's parser has no negative
    preconditions, so every planner gets the domain without open's ``(not (opened ?o))`` (same plans)."""
    return KITCHEN_STRIPS_DOMAIN, (KITCHEN_PROBLEMS / problem).read_text()


def _towers(blocks: list[str], rng: np.random.Generator) -> list[list[str]]:
    order = [blocks[i] for i in rng.permutation(len(blocks))]
    towers: list[list[str]] = []
    for block in order:
        if towers and rng.random() < 0.7:
            towers[int(rng.integers(len(towers)))].append(block)
        else:
            towers.append([block])
    return towers


def _tower_atoms(towers: list[list[str]]) -> list[str]:
    atoms = []
    for tower in towers:
        atoms.append(f"(ontable {tower[0]})")
        atoms += [f"(on {upper} {lower})" for lower, upper in itertools.pairwise(tower)]
        atoms.append(f"(clear {tower[-1]})")
    return atoms


def blocks_world(n: int, seed: int) -> tuple[str, str]:
    rng = np.random.default_rng(seed)
    blocks = [f"b{i}" for i in range(n)]
    init = [*_tower_atoms(_towers(blocks, rng)), "(handempty)"]
    goal = [a for a in _tower_atoms(_towers(blocks, rng)) if a.startswith("(on ")]
    problem = (f"(define (problem blocks-{n}-{seed}) (:domain blocks)\n"
               f"  (:objects {' '.join(blocks)})\n  (:init {' '.join(init)})\n"
               f"  (:goal (and {' '.join(goal)})))\n")
    return BLOCKS_DOMAIN, problem


def gripper(n: int) -> tuple[str, str]:
    balls = [f"ball{i}" for i in range(n)]
    init = ["(at-robby rooma)", "(free left)", "(free right)"] + [f"(at {b} rooma)" for b in balls]
    goal = [f"(at {b} roomb)" for b in balls]
    problem = (f"(define (problem gripper-{n}) (:domain gripper)\n"
               f"  (:objects rooma roomb - room left right - gripper {' '.join(balls)} - ball)\n"
               f"  (:init {' '.join(init)})\n  (:goal (and {' '.join(goal)})))\n")
    return GRIPPER_DOMAIN, problem


def scaled_kitchen(boxes: int, surfaces: int, drawers: int, seed: int) -> tuple[str, str]:
    """Boxes on surfaces (one per surface), goal: a random derangement of their places."""
    if boxes > surfaces:
        raise ValueError("every box needs a surface to start on")
    rng = np.random.default_rng(seed)
    box_names = [f"box{i}" for i in range(boxes)]
    surface_names = [f"surface{i}" for i in range(surfaces)]
    drawer_names = [f"drawer{i}" for i in range(drawers)]
    start = list(rng.permutation(surfaces)[:boxes])
    goal = list(start)
    while any(g == s for g, s in zip(goal, start, strict=True)):
        goal = list(rng.permutation(start))
    init = ["(armClear)"] + [f"(cabClear {d})" for d in drawer_names]
    init += [f"(boxOn {b} {surface_names[s]})" for b, s in zip(box_names, start, strict=True)]
    init += [f"(surfClear {surface_names[s]})" for s in range(surfaces) if s not in start]
    goal_atoms = [f"(boxOn {b} {surface_names[s]})" for b, s in zip(box_names, goal, strict=True)]
    problem = (f"(define (problem kitchen-{boxes}-{surfaces}-{drawers}-{seed}) (:domain kitchen)\n"
               f"  (:objects {' '.join(surface_names)} - surface {' '.join(drawer_names)} - openable"
               f" {' '.join(box_names)} - box)\n"
               f"  (:init {' '.join(init)})\n  (:goal (and {' '.join(goal_atoms)})))\n")
    return KITCHEN_STRIPS_DOMAIN, problem


def ipc_problem(domain: str, problem: str, domain_file: str = "domain.pddl") -> tuple[str, str]:
    """An IPC problem kept in ``benchmarks/ipc/DOMAIN/`` (see the README there for its source).

    Most folders hold one ``domain.pddl``; where the competition gave each problem its own domain
    file (openstacks), ``domain_file`` names it."""
    folder = IPC_DIR / domain
    return (folder / domain_file).read_text(), (folder / problem).read_text()
