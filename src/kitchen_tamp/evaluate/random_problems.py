"""Random kitchen problems: random valid starts of the kitchen's objects and random goals over them.

The objects come from the kitchen map (the default kitchen's map, with the domain's
binding: its surfaces, openables and boxes), and the types and predicates a problem is
written with from the domain's binding (``Vocabulary``: the predicate of each relation a
start or goal needs), so a kitchen with other objects gets other problems and a domain
bound otherwise (the seed's kitchen domain, the regions domain) gets problems in its own
words. A start puts some of the boxes, one per place and leaving a place free, on
surfaces or in openables, each openable open or closed; a goal asks for some of them in
other places. A start is kept only if the kitchen lays it
out (``build_kitchen`` checks Ψ of the built scene against ``:init``); every
kept problem is also planned symbolically, and whether it has a plan is
recorded: generality is measured over all of them, not only the easy ones.
Problem ``i`` of ``--problem-seed S`` is the same file on every machine.
"""

from __future__ import annotations

import shutil
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from kitchen_tamp.atomic_files import write_atomically
from kitchen_tamp.kitchen import DomainBinding, KitchenError, KitchenMap, build_kitchen, load_kitchen_map
from kitchen_tamp.kitchen.binding_reader import binding_path_for
from kitchen_tamp.planning import Atom, atom_text, load_task, plan
from kitchen_tamp.planning.loading import domain_model
from kitchen_tamp.shipped_kitchens import default_scene_path

KITCHEN_KINDS = ("surface", "openable", "box")
MAX_LAYOUT_ATTEMPTS = 50
"""Random starts drawn for one problem before giving up on the kitchen laying any of them out."""
SYMBOLIC_PLANNER = "bfs"
SYMBOLIC_TIME_BUDGET_S = 30.0
PROBLEM_PREFIX = "random-"
RANDOM_PROBLEMS_DIR = "problems"
"""A sweep writes its random problems (and the domain) into this sub-folder."""


class RandomProblemError(Exception):
    """The domain or the kitchen cannot give random problems (missing predicate or type, no layout)."""


@dataclass(frozen=True)
class Vocabulary:
    """The words a random problem is written in, from the domain's binding: the predicate of each
    relation (``None``: the domain has none, and the problem goes without it) and the type of
    each kind."""

    on_surface: str
    in_drawer: str
    opened: str
    hand_empty: str
    surface_clear: str | None
    drawer_clear: str | None
    box_clear: str | None
    types: dict[str, str]

    @staticmethod
    def of(binding: DomainBinding, domain: Path) -> Vocabulary:
        """The vocabulary of ``binding``; ``RandomProblemError`` naming what a start needs and
        the binding lacks."""

        def predicate(relation: str) -> str | None:
            names = binding.predicates_for(relation)
            return names[0] if names else None

        required = {relation: predicate(relation) for relation in ("on_surface", "in_drawer", "opened",
                                                                    "hand_empty")}
        for relation, name in required.items():
            if name is None:
                raise RandomProblemError(f"{domain}: random problems need a predicate for the relation "
                                         f"{relation!r} (the domain's binding has none)")
        types = {kind: binding.types.get(kind) for kind in KITCHEN_KINDS}
        for kind, type_name in types.items():
            if type_name is None:
                raise RandomProblemError(f"{domain}: the domain has no type for the kitchen's {kind}s")
        return Vocabulary(
            on_surface=str(required["on_surface"]), in_drawer=str(required["in_drawer"]),
            opened=str(required["opened"]), hand_empty=str(required["hand_empty"]),
            surface_clear=predicate("surface_clear"), drawer_clear=predicate("drawer_clear"),
            box_clear=predicate("box_clear"), types={kind: str(name) for kind, name in types.items()},
        )


@dataclass(frozen=True)
class KitchenObjects:
    """The kitchen's objects by PDDL type, as the kitchen map has them."""

    surfaces: tuple[str, ...]
    openables: tuple[str, ...]
    boxes: tuple[str, ...]
    words: Vocabulary
    kitchen_map: KitchenMap

    @property
    def places(self) -> tuple[str, ...]:
        return self.surfaces + self.openables

    def type_of(self, name: str) -> str:
        kind = "surface" if name in self.surfaces else "openable" if name in self.openables else "box"
        return self.words.types[kind]


@dataclass(frozen=True)
class RandomProblem:
    """One generated problem and what was found out about it."""

    name: str
    path: Path
    layout_attempts: int
    """Random starts drawn until the kitchen laid one out (1 = the first)."""
    solvable: bool
    plan_length: int | None


def kitchen_objects(domain: Path, kitchen_map: KitchenMap | None = None) -> KitchenObjects:
    """The map's objects (the default kitchen's, bound to ``domain``, if None) and the words of
    the domain's binding."""
    if kitchen_map is None:
        try:
            kitchen_map = load_kitchen_map(default_scene_path(), domain)
        except KitchenError as error:
            raise RandomProblemError(str(error)) from None
    words = Vocabulary.of(kitchen_map.binding, domain)
    objects = KitchenObjects(
        surfaces=tuple(sorted(kitchen_map.surfaces)),
        openables=tuple(sorted(kitchen_map.openables)),
        boxes=tuple(sorted(kitchen_map.boxes)),
        words=words,
        kitchen_map=kitchen_map,
    )
    if not objects.boxes or len(objects.places) < 2:
        raise RandomProblemError("random problems need a box and two places for it in the kitchen map")
    return objects


def _location_atom(box: str, place: str, objects: KitchenObjects) -> Atom:
    words = objects.words
    return (words.on_surface if place in objects.surfaces else words.in_drawer, box, place)


def _draw_start(rng: np.random.Generator, objects: KitchenObjects) -> tuple[dict[str, str], frozenset[Atom]]:
    """Boxes -> places (one box per place at most, one place left free) and the ``:init`` atoms.

    With every place taken and the hand empty, a box can only be put back where it was, so
    such starts are not drawn.
    """
    count = int(rng.integers(1, min(len(objects.boxes), len(objects.places) - 1) + 1))
    boxes = [str(b) for b in rng.choice(objects.boxes, size=count, replace=False)]
    places = [str(p) for p in rng.choice(objects.places, size=count, replace=False)]
    where = dict(zip(sorted(boxes), places, strict=True))
    words = objects.words
    init: set[Atom] = {(words.hand_empty,)}
    init.update(_location_atom(box, place, objects) for box, place in where.items())
    occupied = set(where.values())
    if words.surface_clear is not None:
        init.update((words.surface_clear, s) for s in objects.surfaces if s not in occupied)
    if words.drawer_clear is not None:
        init.update((words.drawer_clear, o) for o in objects.openables if o not in occupied)
    if words.box_clear is not None:
        init.update((words.box_clear, box) for box in where)
    init.update((words.opened, o) for o in objects.openables if rng.random() < 0.5)
    return where, frozenset(init)


def _draw_goal(rng: np.random.Generator, where: dict[str, str], objects: KitchenObjects) -> frozenset[Atom]:
    """Some of the boxes in places of their own, at least one of them not where it starts."""
    boxes = sorted(where)
    while True:
        count = int(rng.integers(1, len(boxes) + 1))
        chosen = sorted(str(b) for b in rng.choice(boxes, size=count, replace=False))
        places = [str(p) for p in rng.choice(objects.places, size=count, replace=False)]
        if any(where[box] != place for box, place in zip(chosen, places, strict=True)):
            return frozenset(_location_atom(b, p, objects) for b, p in zip(chosen, places, strict=True))


def _lays_out(objects: KitchenObjects, boxes: Sequence[str], init: frozenset[Atom]) -> bool:
    typed = {name: objects.type_of(name) for name in (*objects.places, *boxes)}
    try:
        with build_kitchen(typed, init, kitchen_map=objects.kitchen_map):
            return True
    except KitchenError:
        return False


def problem_text(
    name: str, domain_name: str, objects: KitchenObjects, boxes: Sequence[str], init: frozenset[Atom],
    goal: frozenset[Atom], comment: str,
) -> str:
    """The PDDL text of a problem over all places of the kitchen and the given boxes."""
    types = objects.words.types
    groups = [(objects.surfaces, types["surface"]), (objects.openables, types["openable"]),
              (tuple(sorted(boxes)), types["box"])]
    declared = "\n".join(f"    {' '.join(names)} - {type_name}" for names, type_name in groups if names)
    facts = "\n".join(f"    {atom_text(a)}" for a in sorted(init))
    wanted = "\n".join(f"    {atom_text(a)}" for a in sorted(goal))
    return (
        f"; {comment}\n(define (problem {name})\n  (:domain {domain_name})\n  (:objects\n{declared})\n"
        f"  (:init\n{facts})\n  (:goal (and\n{wanted})))\n"
    )


def generate_problems(
    count: int, problem_seed: int, folder: Path, domain: Path, kitchen_map: KitchenMap | None = None
) -> list[RandomProblem]:
    """Write ``count`` problems (and the domain with its binding beside them) into ``folder``; what
    each turned out to be."""
    objects = kitchen_objects(domain, kitchen_map)
    domain_name = domain_model(domain).name
    folder.mkdir(parents=True, exist_ok=True)
    local_domain = folder / "domain.pddl"
    if local_domain.resolve() != domain.resolve():
        shutil.copyfile(domain, local_domain)
        binding = binding_path_for(domain)
        if binding.is_file():  # the kitchen reads the domain's binding beside it
            shutil.copyfile(binding, binding_path_for(local_domain))
    problems = []
    for index in range(count):
        rng = np.random.default_rng([problem_seed, index])
        for attempts in range(1, MAX_LAYOUT_ATTEMPTS + 1):  # noqa: B007 (kept: how many it took)
            where, init = _draw_start(rng, objects)
            if _lays_out(objects, list(where), init):
                break
        else:
            raise RandomProblemError(f"the kitchen laid out none of {MAX_LAYOUT_ATTEMPTS} random starts")
        goal = _draw_goal(rng, where, objects)
        name = f"{PROBLEM_PREFIX}{index:03d}"
        comment = f"random kitchen problem {index} of --problem-seed {problem_seed} (kitchen_tamp.evaluate)"
        text = problem_text(
            f"kitchen-{name}-seed{problem_seed}", domain_name, objects, list(where), init, goal, comment
        )
        path = folder / f"{name}.pddl"
        if path.exists() and path.read_text(encoding="utf-8") != text:
            raise RandomProblemError(
                f"{path} exists with other content (another --problem-seed?): rows of this folder "
                "may refer to it, so it is not replaced; choose another --out"
            )
        write_atomically(path, text)
        result = plan(load_task(path, local_domain), SYMBOLIC_PLANNER, time_budget=SYMBOLIC_TIME_BUDGET_S)
        length = len(result.plan) if result.plan is not None else None
        problems.append(RandomProblem(name, path, attempts, result.solved, length))
    return problems


MANIFEST_FILE = "random_problems.csv"
MANIFEST_COLUMNS = ("problem", "path", "layout_attempts", "symbolically_solvable", "plan_length")


def write_manifest(folder: Path, problems: Sequence[RandomProblem]) -> Path:
    """``random_problems.csv`` beside the problems: what the generator found out about each."""
    lines = [",".join(MANIFEST_COLUMNS)]
    lines += [
        f"{p.name},{p.path},{p.layout_attempts},{str(p.solvable).lower()},"
        f"{'' if p.plan_length is None else p.plan_length}"
        for p in problems
    ]
    return write_atomically(folder / MANIFEST_FILE, "\n".join(lines) + "\n")
