"""Which problem, domain and kitchen a command line means: ``--scene`` and ``--domain`` as given,
else the files beside the problem, else the shipped default kitchen and domain."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from kitchen_tamp.kitchen.scene.kitchen_map import KitchenMap, default_kitchen_map, load_kitchen_map
from kitchen_tamp.shipped_kitchens import (
    default_domain_path,
    default_scene_path,
    domain_for,
    find_problem,
    scene_for,
)


@dataclass(frozen=True)
class SceneChoice:
    """The files of one run."""

    problem: Path
    domain: Path
    scene: Path

    def kitchen_map(self) -> KitchenMap:
        """The kitchen of ``scene`` bound to ``domain`` (raises ``SceneFileError`` for a bad
        scene file, ``BindingFileError`` for a domain without a good binding)."""
        default_domain = self.domain.resolve() == default_domain_path().resolve()
        if default_domain and self.scene.resolve() == default_scene_path().resolve():
            return default_kitchen_map()
        return load_kitchen_map(self.scene, self.domain)


def choose_scene(problem: str | Path, scene: Path | None = None, domain: Path | None = None) -> SceneChoice:
    """Resolve a (possibly bare) problem name and the scene and domain that go with it."""
    problem_path = find_problem(problem, scene)
    return SceneChoice(
        problem_path,
        domain if domain is not None else domain_for(problem_path),
        scene if scene is not None else scene_for(problem_path),
    )
