#!/usr/bin/env python3
"""Plan a PDDL problem: ``python pddl/activity_planning.py [PROBLEM] [--planner ...]``.

A thin entry script; the work is in ``kitchen_tamp.planning`` and
``kitchen_tamp.cli.activity_planning``. Run ``--help`` for the options.
"""

import sys

from kitchen_tamp.cli.activity_planning import main

if __name__ == "__main__":
    sys.exit(main())
