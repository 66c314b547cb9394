"""Where kitchen_tamp keeps what it computes once per machine: the user's cache directory.

Every cache lives under it: Lark's built parsers and parsed, grounded tasks
(``planning.grammar_cache``, ``planning.task_cache``), the models generated from
scene files (``kitchen.scene_models``) and the sphere sets covering collision
meshes (``motion.sphere_scene``). This module imports nothing heavy (not even
``pathlib`` until a ``Path`` is asked for), so a run served from the cache pays
for neither Lark nor the ``pddl`` package.
"""

from __future__ import annotations

import os

TYPE_CHECKING = False  # not typing.TYPE_CHECKING: importing typing costs every planner start
if TYPE_CHECKING:
    from pathlib import Path

CACHE_DIRECTORY_NAME = "kitchen_tamp"


def cache_folder() -> str:
    """``cache_directory()`` as a plain string (for start-up code that does without ``pathlib``)."""
    configured = os.environ.get("XDG_CACHE_HOME", "")
    if configured and os.path.isabs(configured):
        return os.path.join(configured, CACHE_DIRECTORY_NAME)
    home = os.path.expanduser("~")
    if home.startswith("~"):  # as Path.home(): no HOME and no password entry
        raise RuntimeError("Could not determine home directory.")
    return os.path.join(home, ".cache", CACHE_DIRECTORY_NAME)


def cache_directory() -> Path:
    """``$XDG_CACHE_HOME/kitchen_tamp``, or ``~/.cache/kitchen_tamp`` when it is unset or relative.

    Raises ``RuntimeError`` when there is no home directory to be found.
    """
    from pathlib import Path

    return Path(cache_folder())
