"""Where kitchen_tamp keeps what it computes once per machine: the user's cache directory.

Every cache lives under it: Lark's built parsers and parsed, grounded tasks
(``planning.grammar_cache``, ``planning.task_cache``), the models generated from
scene files (``kitchen.scene_models``) and the sphere sets covering collision
meshes (``motion.sphere_scene``). This module imports nothing heavy, so a run
served from the cache pays for neither Lark nor the ``pddl`` package.
"""

from __future__ import annotations

import os
from pathlib import Path

CACHE_DIRECTORY_NAME = "kitchen_tamp"


def cache_directory() -> Path:
    """``$XDG_CACHE_HOME/kitchen_tamp``, or ``~/.cache/kitchen_tamp`` when it is unset or relative.

    Raises ``RuntimeError`` when there is no home directory to be found.
    """
    configured = os.environ.get("XDG_CACHE_HOME", "")
    base = Path(configured) if configured and os.path.isabs(configured) else Path.home() / ".cache"
    return base / CACHE_DIRECTORY_NAME
