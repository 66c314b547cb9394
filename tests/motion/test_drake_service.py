"""Drake's models asked in a process of their own give the verdicts of models built here, the hand
empty and holding a box; a scene Drake cannot load is an error in the asking process; a planning
run with the sphere model never loads Drake in its own process."""

from __future__ import annotations

import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from kitchen_tamp.kitchen import KitchenScene
from kitchen_tamp.motion.geometry.drake import DrakeCollisionChecker
from kitchen_tamp.motion.geometry.drake_service import DrakeService, DrakeServiceError
from kitchen_tamp.world.scene_description import describe_collision_checker
from tests.motion.conftest import holding_spam_pair

REPO = Path(__file__).resolve().parents[2]


def test_the_service_gives_the_verdicts_of_a_model_built_here(kitchen: KitchenScene) -> None:
    free = kitchen.collision_checker(margin=0.003)
    holding = holding_spam_pair(kitchen, DrakeCollisionChecker).pybullet
    rng = np.random.default_rng(7)
    service = DrakeService()
    try:
        for checker in (free, holding):
            description = describe_collision_checker(checker)
            here = DrakeCollisionChecker(description, margin=checker.margin)
            there = service.model(description, checker.margin)
            qs = rng.uniform(here.lower, here.upper, size=(400, len(here.lower)))
            verdicts = here.is_valid(qs)
            assert 0 < verdicts.sum() < len(qs)  # both kinds asked
            assert np.array_equal(there.is_valid(qs), verdicts)
            assert np.array_equal(there.is_valid(qs[3]), verdicts[3:4])  # one configuration
    finally:
        service.close()


def test_a_scene_drake_cannot_load_is_an_error_where_it_is_asked(kitchen: KitchenScene) -> None:
    description = describe_collision_checker(kitchen.collision_checker())
    broken = replace(description, bodies=(replace(description.bodies[0], urdf_path="/nowhere/gone.urdf"),
                                          *description.bodies[1:]))
    service = DrakeService()
    try:
        model = service.model(broken, 0.0)
        with pytest.raises(DrakeServiceError, match=r"gone\.urdf"):
            model.is_valid(np.zeros((1, len(description.arm_lower))))
        good = service.model(description, 0.0)  # the service still answers
        assert good.is_valid(kitchen.home[None]).shape == (1,)
    finally:
        service.close()


@pytest.mark.slow
def test_a_planning_run_with_spheres_never_loads_drake_itself(tmp_path: Path) -> None:
    script = (
        "import sys\n"
        "from kitchen_tamp.cli.final_project import main\n"
        f"code = main(['rrt', '--no-video', '--no-physics', '--out', {str(tmp_path / 'run')!r}])\n"
        "print('drake loaded' if 'pydrake' in sys.modules else 'drake not loaded', code)\n"
    )
    done = subprocess.run([sys.executable, "-c", script], cwd=REPO, capture_output=True, text=True,
                          check=True)
    assert done.stdout.strip().splitlines()[-1] == "drake not loaded 0"
