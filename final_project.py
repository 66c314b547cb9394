#!/usr/bin/env python3
"""Kitchen TAMP for a Franka Panda: ``python final_project.py {rrt,optimizes,replay} --help``."""

import sys

from kitchen_tamp.cli.run_clock import exit_now, process_start
from kitchen_tamp.cli.run_profile import profile_if_asked

if __name__ == "__main__":
    STARTED = process_start()
    profile_if_asked(sys.argv)  # before the package's modules load, so start-up is profiled too

    from kitchen_tamp.cli.final_project import main

    exit_now(main(started=STARTED))
