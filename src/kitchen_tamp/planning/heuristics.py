"""Delete-relaxation heuristics: h_max, h_add and h_FF, and h_FF's helpful actions.

All three explore the relaxed task (delete effects and negative preconditions
ignored). With unit costs, h_max and h_FF need only the relaxed planning graph:
layer by layer, every action whose preconditions are all reached fires at once,
which is a handful of bitset operations per action and layer. h_max is the
index of the first layer holding the whole goal.

h_FF extracts a relaxed plan backwards from the goal as Hoffmann and Nebel's FF
does: each subgoal is placed at the layer where it first appears; its achiever
comes from the layer before, and among several the one with the lowest
difficulty (the sum of its preconditions' first layers) wins, ties going to the
first in task order; the achiever's add effects count as true at its layer and
the one below, and its preconditions become subgoals unless already so marked.
h_FF is the number of actions. The relaxed plan's actions that are applicable
in the state are its *helpful actions* (preferred operators), which the greedy
searches try first. (FF's own definition takes every applicable action that
adds a subgoal of layer 1; that larger set guides blocks world ten times worse,
and Fast Downward and pyperplan also use the relaxed plan's own actions.)

h_add needs real sums, so it runs a generalised Dijkstra over atoms (with
integer costs, a list of buckets) in which an action becomes usable once its
last precondition is settled. Its best supporters give the other relaxed plan,
the one Fast Downward's ``ff()`` and GBFS use (``supporters="hadd"``): FF's
graph always takes the goal at its first layer, so where a short route is a
wide one (mystery: a vehicle near the goal that must first load and fetch)
it never counts the narrow route that is fewer actions.

Only actions relevant to the goal (adding a goal or a precondition of a
relevant action, transitively) take part in the layers: the others cannot
change any of these values. h_max is admissible (A* with it returns optimal
plans); h_add and h_FF are not, but guide greedy search much better.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Literal

from kitchen_tamp.planning.task import State, Task, bits, mask_of

INFINITY = float("inf")

UNSETTLED = 1 << 40
"""In ``additive_costs``, the weight of one unsettled precondition, which must exceed every sum of costs.

If some cost reaches ``UNSETTLED`` divided by the most preconditions of an
action (only in contrived tasks), the exploration is repeated with its square."""

HeuristicName = Literal["hmax", "hadd", "hff", "lmcut"]

RelaxedPlanSupporters = Literal["hadd", "ff"]
"""Where h_FF's relaxed plan takes its achievers from: h_add's best supporters or FF's planning graph."""

Heuristic = Callable[[State], float]
HelpfulHeuristic = Callable[[State], tuple[float, int]]
"""h_FF with helpful actions: (h, bitset over action indices of the helpful actions)."""


def _relevant_actions(task: Task) -> list[int]:
    """Indices of the actions that can contribute to the goal in the relaxation, in task order."""
    needed = task.goal
    relevant: set[int] = set()
    changed = True
    while changed:
        changed = False
        for index, action in enumerate(task.actions):
            if index not in relevant and action.add & needed:
                relevant.add(index)
                if action.pre & ~needed:
                    needed |= action.pre
                    changed = True
    return sorted(relevant)


Entry = tuple[int, int, int]
"""A relevant action in the relaxed exploration: (precondition mask, add mask, action index)."""


KeyedEntries = tuple[int, dict[int, tuple[Entry, ...]], tuple[Entry, ...]]
"""Entries grouped by key atom: (mask of the key atoms, groups by key bit, entries without preconditions)."""


def _entries_by_key(task: Task, entries: list[Entry]) -> KeyedEntries:
    """The entries grouped by their action's key atom (``Task.key_atoms``).

    An action cannot fire before its key atom is reached, so a relaxed
    exploration only tests the groups whose key it has reached. Returns the
    mask of key atoms, the groups by key bit, and the actions without
    preconditions.
    """
    keys = task.key_atoms
    keyed: dict[int, list[Entry]] = {}
    unkeyed: list[Entry] = []
    for entry in entries:
        key = keys[entry[2]]
        if key >= 0:
            keyed.setdefault(1 << key, []).append(entry)
        else:
            unkeyed.append(entry)
    return mask_of(k.bit_length() - 1 for k in keyed), {k: tuple(v) for k, v in keyed.items()}, tuple(unkeyed)


BUCKET_LEVELS = 4096
"""Costs the compiled explorations (``relaxed_kernel``, ``search/greedy_search.c``) keep in buckets
(first-in first-out lists); dearer offers go to a heap, in the same order."""


class RelaxedExploration:
    """Precomputed structure for fast relaxed explorations of one task."""

    def __init__(self, task: Task, supporters: RelaxedPlanSupporters = "ff") -> None:
        self.task = task
        self.supporters = supporters
        n_atoms = len(task.atoms)
        self.preconditions_of = [a.pre_ids for a in task.actions]
        self.adds_of = [a.add_ids for a in task.actions]
        self.goal_ids = tuple(bits(task.goal))
        self.n_atoms = n_atoms
        self.pre_masks = [a.pre for a in task.actions]
        self.add_masks = [a.add for a in task.actions]
        relevant = _relevant_actions(task)
        self.entries = [(self.pre_masks[i], self.add_masks[i], i) for i in relevant]
        self.key_mask, self.entries_by_key, self.unkeyed_entries = _entries_by_key(task, self.entries)
        achievers: list[list[int]] = [[] for _ in range(n_atoms)]
        for index in relevant:
            for atom in self.adds_of[index]:
                achievers[atom].append(index)
        self.achievers = [tuple(a) for a in achievers]
        # For h_add: the relevant actions using each atom, and per action the preconditions left to settle.
        users: list[list[int]] = [[] for _ in range(n_atoms)]
        for index in relevant:
            for atom in self.preconditions_of[index]:
                users[atom].append(index)
        self.relevant_users = [tuple(u) for u in users]
        self.relevant_precondition_count = [len(p) for p in self.preconditions_of]
        self.most_preconditions = max(self.relevant_precondition_count, default=1) or 1
        self.relevant_pending = [count * UNSETTLED for count in self.relevant_precondition_count]
        self.relevant_free_actions = [i for i in relevant if not self.preconditions_of[i]]
        self.unsolvable = task.trivially_unsolvable

    def additive_costs(self, state: State,
                       unsettled: int = UNSETTLED) -> tuple[list[float], list[int]] | None:
        """h_add cost of the atoms from ``state`` and each one's best supporter (-1: none).

        A generalised Dijkstra over atoms with unit action costs, so the queue
        is a list of buckets by integer cost: an action's cost is 1 plus the sum
        of its preconditions' costs, known when the last of them is settled,
        and it offers that cost to its add effects. Atoms are settled cost by
        cost, each bucket in the order its atoms were offered, and a cost is
        taken only if strictly lower, so the first action to offer the lowest
        cost is the supporter. Only relevant actions take part, and it stops
        when every goal atom is settled (atoms settled later keep their
        offers, unsettled ones infinity). None if some goal atom is
        relaxed-unreachable. ``unsettled`` (at least 2): see ``UNSETTLED``.
        """
        cost: list[float] = [INFINITY] * self.n_atoms
        supporter = [-1] * self.n_atoms
        # Per action, (preconditions not yet settled) * UNSETTLED + (sum of the settled ones' costs):
        # one number to update per settled precondition; below UNSETTLED, all are settled.
        pending = (self.relevant_pending.copy() if unsettled == UNSETTLED
                   else [count * unsettled for count in self.relevant_precondition_count])
        cost_limit = unsettled // self.most_preconditions
        too_dear = False
        users, adds_of = self.relevant_users, self.adds_of
        settled_now: list[int] = []
        for atom in bits(state):
            cost[atom] = 0
            settled_now.append(atom)
        buckets = [settled_now, []]
        for action in self.relevant_free_actions:
            for atom in adds_of[action]:
                if cost[atom] > 1:
                    cost[atom] = 1
                    supporter[atom] = action
                    buckets[1].append(atom)
        open_goals = [g for g in self.goal_ids if not state >> g & 1]
        level = 0
        while open_goals:
            if level == len(buckets):
                return self.additive_costs(state, unsettled * unsettled) if too_dear else None
            step = level - unsettled
            for atom in buckets[level]:
                if cost[atom] != level:
                    continue  # offered again at a lower cost, and settled then
                for action in users[atom]:
                    total = pending[action] + step
                    pending[action] = total
                    if total < unsettled:
                        offer = total + 1
                        if offer >= cost_limit:
                            too_dear = True
                        for added in adds_of[action]:
                            if offer < cost[added]:
                                cost[added] = offer
                                supporter[added] = action
                                try:
                                    buckets[offer].append(added)
                                except IndexError:
                                    buckets.extend([] for _ in range(offer + 1 - len(buckets)))
                                    buckets[offer].append(added)
            open_goals = [g for g in open_goals if cost[g] > level]
            level += 1
        if too_dear:
            return self.additive_costs(state, unsettled * unsettled)
        return cost, supporter

    def atom_layers(self, state: State) -> list[int] | None:
        """The atoms new in each layer of the relaxed planning graph (layer 0 is ``state``).

        Stops at the first layer holding the whole goal; None if the goal is
        relaxed-unreachable. This loop is where h_max and h_FF spend their time:
        one mask test per pending action and layer; an action leaves the
        pending list once it has fired, and joins it only once its key atom
        (its least used precondition, see ``_entries_by_key``) is reached, so
        actions that never come near applicable cost nothing.
        """
        goal = self.task.goal
        reached = state
        new_atoms = [state]
        pending = self._activate(state, list(self.unkeyed_entries))
        while reached & goal != goal:
            waiting: list[Entry] = []
            added = 0
            for entry in pending:
                pre = entry[0]
                if pre & reached == pre:
                    added |= entry[1]
                else:
                    waiting.append(entry)
            added &= ~reached
            if not added:
                return None
            new_atoms.append(added)
            reached |= added
            pending = self._activate(added, waiting)
        return new_atoms

    def _activate(self, atoms: int, pending: list[Entry]) -> list[Entry]:
        """``pending`` plus the actions keyed by one of ``atoms`` (which have just been reached)."""
        keys = atoms & self.key_mask
        by_key = self.entries_by_key
        while keys:
            low = keys & -keys
            keys ^= low
            pending.extend(by_key[low])
        return pending

    def h_max(self, state: State) -> float:
        if self.unsolvable:
            return INFINITY
        new_atoms = self.atom_layers(state)
        return INFINITY if new_atoms is None else float(len(new_atoms) - 1)

    def h_add(self, state: State) -> float:
        if self.unsolvable:
            return INFINITY
        explored = self.additive_costs(state)
        return INFINITY if explored is None else float(sum(explored[0][g] for g in self.goal_ids))

    def _extract(self, new_atoms: list[int]) -> list[int]:
        """FF's relaxed plan in the graph with these atom layers, as action indices."""
        top = len(new_atoms) - 1
        reached_at = new_atoms.copy()
        for level in range(1, top + 1):
            reached_at[level] |= reached_at[level - 1]
        unreached_at = [~atoms for atoms in reached_at]
        goal = self.task.goal
        goals_at = [goal & atoms for atoms in new_atoms]
        true_at = [0] * (top + 1)
        pre, add, achievers = self.pre_masks, self.add_masks, self.achievers
        plan: list[int] = []
        for level in range(top, 0, -1):
            open_goals = goals_at[level] & ~true_at[level]
            below = reached_at[level - 1]
            while open_goals:
                goal_bit = open_goals & -open_goals
                # The achievers first applicable in the layer below; all fire there.
                achiever = best = -1
                for candidate in achievers[goal_bit.bit_length() - 1]:
                    needs = pre[candidate]
                    if needs & below == needs:
                        if achiever < 0:
                            achiever = candidate
                            continue
                        if best < 0:
                            best = self._difficulty(pre[achiever], unreached_at, level)
                        difficulty = self._difficulty(needs, unreached_at, level)
                        if difficulty < best:
                            achiever, best = candidate, difficulty
                plan.append(achiever)
                needs = pre[achiever] & ~true_at[level - 1]
                for lower in range(1, level):
                    goals_at[lower] |= needs & new_atoms[lower]
                true_at[level] |= add[achiever]
                true_at[level - 1] |= add[achiever]
                open_goals &= ~add[achiever]
        return plan

    @staticmethod
    def _difficulty(needs: int, unreached_at: list[int], level: int) -> int:
        """FF's difficulty of an action of layer ``level - 1``: the sum of its preconditions' first layers."""
        difficulty = 0
        for layer in range(level - 1):
            difficulty += (needs & unreached_at[layer]).bit_count()
        return difficulty

    def relaxed_plan(self, state: State) -> list[int] | None:
        """Indices of the actions of the relaxed plan from ``state``, or None if there is none.

        From FF's planning graph (``supporters == "ff"``, the default) or from
        h_add's best supporters (``"hadd"``, see ``plan_from_supporters``).
        """
        if self.unsolvable:
            return None
        if self.supporters == "hadd":
            return self.plan_from_supporters(state)
        new_atoms = self.atom_layers(state)
        return None if new_atoms is None else self._extract(new_atoms)

    def plan_from_supporters(self, state: State) -> list[int] | None:
        """The relaxed plan of h_add's best supporters, as Fast Downward's ``ff()`` builds it.

        Each goal atom not in ``state`` is achieved by its best supporter (the
        action that first gave it its lowest h_add cost), whose preconditions
        are achieved the same way, each action counted once. Against FF's
        planning graph, this prefers achievers whose preconditions are cheap in
        total rather than early. GBFS uses it; it costs 1.5-3x more per
        state than FF's graph (a Dijkstra over the relevant actions against
        bitset layers), which lazy evaluation more than pays back. FF's graph
        stays the default here, for enforced hill climbing (as in FF).
        """
        explored = self.additive_costs(state)
        if explored is None:
            return None
        return self.supported_plan(*explored, self.goal_ids)

    def supported_plan(self, cost: list[float], supporter: list[int], targets: Iterable[int]) -> list[int]:
        """The best supporters' relaxed plan for ``targets`` from ``additive_costs``' answer."""
        chosen: dict[int, None] = {}
        marked = bytearray(self.n_atoms)
        open_atoms = list(targets)
        preconditions_of = self.preconditions_of
        while open_atoms:
            atom = open_atoms.pop()
            if marked[atom] or not cost[atom]:
                continue  # handled already, or true in the state
            marked[atom] = 1
            action = supporter[atom]
            if action not in chosen:
                chosen[action] = None
                open_atoms.extend(preconditions_of[action])
        return list(chosen)

    def h_ff(self, state: State) -> float:
        plan = self.relaxed_plan(state)
        return INFINITY if plan is None else float(len(plan))

    def h_ff_helpful(self, state: State) -> tuple[float, int]:
        """h_FF and the helpful actions: the relaxed plan's actions applicable in ``state``.

        The helpful actions come as a bitset over action indices (bit ``i``:
        ``task.actions[i]``); it is 0 at goal states and dead ends.
        """
        plan = self.relaxed_plan(state)
        if plan is None:
            return INFINITY, 0
        helpful = 0
        pre = self.pre_masks
        for action in plan:
            if pre[action] & state == pre[action]:
                helpful |= 1 << action
        return float(len(plan)), helpful


def make_heuristic(task: Task, name: HeuristicName) -> Heuristic:
    """The named heuristic bound to ``task``."""
    exploration = RelaxedExploration(task)
    if name == "lmcut":
        from kitchen_tamp.planning.landmark_cut import LandmarkCut  # it builds on this module

        return LandmarkCut(exploration)
    heuristics: dict[str, Heuristic] = {
        "hmax": exploration.h_max,
        "hadd": exploration.h_add,
        "hff": exploration.h_ff,
    }
    try:
        return heuristics[name]
    except KeyError:
        choices = [*sorted(heuristics), "lmcut"]
        raise ValueError(f"unknown heuristic {name!r}; choose from {choices}") from None
