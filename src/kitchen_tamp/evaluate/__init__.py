"""Sweeps of kitchen runs over problems x modes x seeds, on this machine or a Ray cluster.

``python -m kitchen_tamp.evaluate --problems problem.pddl --modes rrt --seeds 0-19``
expands the grid (``grid``), runs each task as ``final_project.py`` in its own
process with a timeout (``task_run``) on a local pool or on Ray (``backends``),
streams one CSV row per finished task (``results_table``), and ends with
``summary.md`` and plots (``summary``, ``plots``). ``random_problems`` writes
random kitchen problems to sweep over. Importing this package imports neither
Ray nor matplotlib.
"""

from kitchen_tamp.evaluate.grid import TaskSpec, expand_grid, parse_seeds

__all__ = ["TaskSpec", "expand_grid", "parse_seeds"]
