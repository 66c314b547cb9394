"""Skills: what turns a grounded action into motion targets, computed from geometry.

``registry`` maps each action to its skill (``pick``, ``place``, ``open_drawer``);
a skill samples ``grasps`` and ``placements``, solves ``straight_moves`` by IK and
hands `SkillTargets` (``targets``) to motion planning; ``parameters`` holds the
skills' distances and budgets (never joint angles).
"""
