"""Skills: what turns a grounded action into motion targets, computed from geometry.

``registry`` finds an action's skill in the kitchen's binding (``pick``, ``place``,
``place_in``, ``stack``, ``open``, ``process``) and checks its arguments; each
sampling skill is a problem for the one loop of ``sampling_loop`` (draw a candidate,
build its segments, hand out targets, or fail saying why and what obstructed it); a
skill samples ``grasps`` and ``placements``, solves ``straight_moves`` by IK and
hands `SkillTargets` (``targets``) to motion planning; ``parameters`` holds the
skills' distances and budgets (never joint angles).
"""
