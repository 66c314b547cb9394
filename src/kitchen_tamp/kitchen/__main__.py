"""``python -m kitchen_tamp.kitchen show``: render the kitchen for a problem, headless.

Exit codes: 0 picture written, 1 a skill found no targets or the problem has no
plan, 2 bad input (unreadable problem, unknown object, unsupported or
mismatching :init), 3 internal error.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

from kitchen_tamp.kitchen.errors import (
    InitialStateMismatchError,
    SkillFailure,
    UnknownActionError,
    UnknownObjectError,
    UnsupportedInitialStateError,
)
from kitchen_tamp.kitchen.scene.choice import SceneChoice, choose_scene
from kitchen_tamp.kitchen.scene.layout import build_kitchen_for_task
from kitchen_tamp.kitchen.scene.spec_reader import SceneFileError
from kitchen_tamp.kitchen.show import render_scene, render_skill_frames
from kitchen_tamp.planning import PlanningInputError, load_task, plan
from kitchen_tamp.shipped_kitchens import DEFAULT_PROBLEM
from kitchen_tamp.world import tile, write_png


def parse_arguments(argv: Sequence[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(
        prog="python -m kitchen_tamp.kitchen", description=__doc__.splitlines()[0]
    )
    commands = parser.add_subparsers(dest="command", required=True)
    show = commands.add_parser("show", help="render the kitchen scene for a problem")
    show.add_argument("--problem", default=DEFAULT_PROBLEM,
                      help="PDDL problem file; a bare name is looked up in the working directory, then "
                           "beside the scene file, then in the shipped kitchens (default: %(default)s)")
    show.add_argument("--scene", type=Path, default=None,
                      help="kitchen scene file (default: scene.toml beside the problem, else the default "
                           "kitchen)")
    show.add_argument("--domain", type=Path, default=None,
                      help="domain file (default: domain.pddl beside the problem, else the shipped one)")
    show.add_argument("--out", type=Path, default=Path("out/scene.png"), help="PNG to write")
    show.add_argument("--skills", action="store_true", help="also render the arm at each plan step's targets")
    show.add_argument("--seed", type=int, default=0, help="seed of the skills' sampling")
    show.add_argument("--gui", action="store_true", help="open the PyBullet window (needs a display)")
    return parser.parse_args(argv)


def show(arguments: argparse.Namespace) -> int:
    """Write the scene picture (and with ``--skills`` a sheet of skill frames beside it)."""
    choice: SceneChoice = choose_scene(arguments.problem, arguments.scene, arguments.domain)
    task = load_task(choice.problem, choice.domain)
    with build_kitchen_for_task(task, gui=arguments.gui, kitchen_map=choice.kitchen_map()) as kitchen:
        path = write_png(render_scene(kitchen), arguments.out)
        print(f"wrote {path}")
        if arguments.skills:
            result = plan(task, "bfs")
            if result.plan is None:
                print(f"error: {arguments.problem} has no plan", file=sys.stderr)
                return 1
            frames = render_skill_frames(kitchen, list(result.plan), arguments.seed)
            sheet = tile([f.image for f in frames], columns=4)
            path = write_png(sheet, arguments.out.with_name(f"{arguments.out.stem}_skills.png"))
            print(f"wrote {path}: " + " ".join(f.action for f in frames))
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    arguments = parse_arguments(argv)
    try:
        return show(arguments)
    except (
        PlanningInputError,
        SceneFileError,
        UnknownObjectError,
        UnknownActionError,
        UnsupportedInitialStateError,
        InitialStateMismatchError,
        OSError,
    ) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    except SkillFailure as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    except Exception as error:  # the CLI's last line of defence: one line, exit code 3
        print(f"internal error: {type(error).__name__}: {error}", file=sys.stderr)
        return 3


if __name__ == "__main__":
    sys.exit(main())
