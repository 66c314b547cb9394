"""Where kitchen_tamp keeps what it computes once per machine: the user's cache directory.

Every cache lives under it: Lark's built parsers and parsed, grounded tasks
(``planning.reading.grammar_cache``, ``planning.reading.task_cache``), the models
generated from scene files (``kitchen.scene.models``) and the sphere sets covering
collision meshes (``motion.geometry.spheres``).
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
    if configured and os.path.isabs(configured):
        return Path(configured, CACHE_DIRECTORY_NAME)
    return Path.home() / ".cache" / CACHE_DIRECTORY_NAME
