#!/usr/bin/env python3
"""Kitchen TAMP for a Franka Panda: ``python final_project.py {rrt,optimizes,replay} --help``."""

import time

_STARTED = time.perf_counter()

import sys  # noqa: E402

from kitchen_tamp.cli.final_project import main  # noqa: E402

if __name__ == "__main__":
    sys.exit(main(started=_STARTED))
