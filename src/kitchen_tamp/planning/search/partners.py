"""The searches that take turns with a long greedy search: a portfolio inside one process.

Greedy best-first search is fast when its heuristics lead it and lost when they
do not: which of the landmark count and the novel queue misleads it differs
from problem to problem, and a search that has gone wrong seldom comes back.
So a lazy search that has not ended after ``PARTNERS_AFTER_WORK`` is joined by
``PARTNERS``, searches of the same task from its root with other choices of
heuristics and queues, and they take turns of ``PARTNER_TURN_EVALUATIONS``
evaluations until one of them finds a plan or proves there is none (every one
of them is complete). A problem the main search solves before then is
untouched; one it would solve later takes at most about three times as long
from then on; one a partner solves takes about three times the partner's time.
Fast Downward's portfolios (Stone Soup) run configurations one after another
in fixed time slices; here they share the time from the moment the partners
join, so that none is cut off. The turns are counted in evaluations, not
seconds, so the same task gets the same plan on any machine.

The searches take turns in C (``greedy_search.c``'s ``greedy_portfolio``),
where each keeps its own state between turns. Without a C compiler the lazy
search hands over to numba's kernel, which runs the main search alone.
"""

from __future__ import annotations

from typing import NamedTuple


class Partner(NamedTuple):
    """A search that takes turns with the main one: which heuristics and queues it has."""

    landmarks: bool
    landmark_preferred: bool
    novelty: bool


PARTNERS = (
    Partner(landmarks=False, landmark_preferred=False, novelty=False),
    Partner(landmarks=True, landmark_preferred=True, novelty=False),
)
"""The searches that take turns with a long lazy search in C: h_FF alone (Fast Downward's ``lazy_greedy``
with preferred operators), and h_FF with the landmark count without the novel queue. h_FF alone solves
pegsol-30 of the IPC in 1.8 s (the main search does not in a minute), the landmark count without the
novel queue depot-20 in 3.4 s (the same). A third partner, h_FF with the novel queue, would take
freecell-19 from 20 s to 11 s, but four searches give each a quarter of the time, and sokoban-28, which
every choice solves alone in 12-30 s, then takes over a minute (50 s with these two); see
docs/planner.md, "Searches taking turns"."""

PARTNERS_AFTER_WORK = 1_500_000_000
"""Evaluations times ``LandmarkEvaluator.work_per_evaluation`` after which the partners join: about 3-7 s
of the C search's CPU, beyond every problem of ``benchmarks/ipc`` (pegsol-28, the longest, is about a third
of it). A count, not a clock, so that the same task always gets the same plan."""

PARTNER_TURN_EVALUATIONS = 1000
"""Evaluations each search makes in its turn once the partners have joined."""


class Turns(NamedTuple):
    """Who takes turns with a search, and when: it goes alone for ``alone`` evaluations, then each
    search in turn for ``turn`` evaluations."""

    partners: tuple[Partner, ...]
    alone: int
    turn: int


def turns_after_work(work_per_evaluation: int) -> Turns:
    """``PARTNERS`` joining a search once its evaluations of ``work_per_evaluation`` each have made
    ``PARTNERS_AFTER_WORK``."""
    return Turns(PARTNERS, -(-PARTNERS_AFTER_WORK // max(1, work_per_evaluation)), PARTNER_TURN_EVALUATIONS)
