"""kitchen_tamp: task and motion planning for a Franka Panda in a simulated kitchen.

Packages, from the bottom up (imports only go down this list's dependencies,
see DESIGN.md): ``planning`` (PDDL to STRIPS, search), ``bilevel`` (generic
bilevel planning), ``motion`` (configuration-space planners), ``world`` (the
only PyBullet code), ``kitchen`` (what the symbols mean here), ``execute``
(replay, verify, report) and ``cli``.
"""

__version__ = "0.1.0"
