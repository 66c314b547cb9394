"""The command line of ``final_project.py``: modes ``rrt``, ``optimizes`` and ``replay``, and
their options. A mistake on the command line is one line naming the option (exit 2); the
usage stays in ``--help``."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path

from kitchen_tamp.cli import CommandLineParser
from kitchen_tamp.motion import MOTION_PLANNERS, planner_options
from kitchen_tamp.refinement.kitchen_sesame import KITCHEN_BUDGETS
from kitchen_tamp.refinement.optimizing_settings import DEFAULT_SETTINGS
from kitchen_tamp.refinement.planning_checkers import COLLISION_MODELS, DEFAULT_COLLISION_MODEL
from kitchen_tamp.shipped_kitchens import DEFAULT_PROBLEM


def _integer_at_least(minimum: int) -> Callable[[str], int]:
    """An argparse type: an integer no smaller than ``minimum``."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"not an integer: {text!r}") from None
        if value < minimum:
            raise argparse.ArgumentTypeError(f"must be at least {minimum}, got {value}")
        return value

    return parse


def _add_viewing_options(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--out", type=Path, metavar="DIR", help="output folder")
    parser.add_argument("--no-video", action="store_true", help="do not render replay.gif and replay.html")
    parser.add_argument("--meshcat", action="store_true",
                        help="serve a live 3D viewer (Meshcat) on this machine while the program runs")
    parser.add_argument("--gui", action="store_true", help="also play the run in a PyBullet window")
    parser.add_argument("--step", action="store_true", help="wait for Enter before each action of the replay")
    parser.add_argument("--no-physics", action="store_true", help="skip execution under physics")
    parser.add_argument("--profile", action="store_true",
                        help="write profile.prof and profile.txt, a profile of the whole run, beside "
                             "the report")


def _add_planning_options(sub: argparse.ArgumentParser, mode: str) -> None:
    sub.add_argument("--problem", default=DEFAULT_PROBLEM,
                     help="problem file; a bare name is looked up in the working directory, beside "
                          "the scene file, then in the shipped kitchens (default: %(default)s)")
    sub.add_argument("--domain", help="domain file (default: domain.pddl beside the problem, else "
                                      "the shipped kitchen domain)")
    sub.add_argument("--scene", type=Path, metavar="FILE",
                     help="kitchen scene file (default: scene.toml beside the problem, else the "
                          "default kitchen)")
    sub.add_argument("--seed", type=_integer_at_least(0), default=0, help="random seed (default 0)")
    budgets = KITCHEN_BUDGETS
    sub.add_argument("--max-plans", type=_integer_at_least(1), default=budgets.max_plans, metavar="N",
                     help="abstract plans SeSamE may try, shortest first; a plan dropped for a fact "
                          "its failure taught does not count (default %(default)s)")
    sub.add_argument("--samples-per-step", type=_integer_at_least(1), default=budgets.samples_per_step,
                     metavar="N", help="samples of an action (targets + motion) before SeSamE "
                                       "steps back (default %(default)s)")
    sub.add_argument("--max-samples", type=_integer_at_least(1), default=KITCHEN_BUDGETS.max_samples,
                     metavar="N", help="samples over the whole run (default %(default)s)")
    sub.add_argument("--no-feedback", action="store_true",
                     help="skill failures do not teach the abstract search (no learned obstructions, "
                          "no pruned places); for comparison")
    sub.add_argument("--collision-model", choices=sorted(COLLISION_MODELS), default=DEFAULT_COLLISION_MODEL,
                     help="collision model for planning (default %(default)s; PyBullet always verifies)")
    if mode == "optimizes":
        sub.add_argument("--waypoints", type=_integer_at_least(2), default=DEFAULT_SETTINGS.num_waypoints,
                         metavar="N", help="joint waypoints per move (default %(default)s)")
    if mode == "rrt":
        options = planner_options()
        sub.add_argument("--rrt", choices=list(options), default=next(iter(options)),
                         help="; ".join(f"{option}: {MOTION_PLANNERS[name].summary}"
                                        for option, name in options.items()) + " (default %(default)s)")


def build_parser() -> argparse.ArgumentParser:
    parser = CommandLineParser(
        prog="final_project.py",
        description="Kitchen task-and-motion planning for a Franka Panda: symbolic plan, skills, "
                    "motion planning per step, headless replay, verification.")
    modes = parser.add_subparsers(dest="mode", required=True, metavar="MODE")
    helps = {
        "rrt": "solve each step with a joint-space RRT (RRT-Connect by default) and shortcutting",
        "optimizes": "solve each step with Drake trajectory optimisation",
    }
    for mode, text in helps.items():
        sub = modes.add_parser(mode, help=text, description=text)
        _add_planning_options(sub, mode)
        _add_viewing_options(sub)
    replay = modes.add_parser(
        "replay", help="re-verify and re-render a saved run without planning",
        description="Judge a saved run again (both judges, no planning) against the files it "
                    "recorded, or against the ones named here.")
    replay.add_argument("run_dir", type=Path, metavar="RUN_DIR", help="folder with trajectory.json")
    replay.add_argument("--problem", type=Path, metavar="FILE",
                        help="judge against this problem file (default: the one the run recorded)")
    replay.add_argument("--domain", type=Path, metavar="FILE",
                        help="judge against this domain file (default: the one the run recorded)")
    replay.add_argument("--scene", type=Path, metavar="FILE",
                        help="judge in this kitchen scene file (default: the one the run recorded)")
    _add_viewing_options(replay)
    return parser
