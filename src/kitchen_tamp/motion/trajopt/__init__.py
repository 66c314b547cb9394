"""Trajectory optimisation with Drake, as build -> solve -> reconstruct.

`build_trajectory_program` (``program``) writes a MathematicalProgram over N
joint waypoints with a clearance constraint; ``solver`` solves it with a
nonlinear solver and reconstructs the path (`optimize_trajectory` does all
three). Those two modules load Drake; ``settings`` (what a program is asked for)
does not, and this package imports none of them, so that a run which never
optimises never loads Drake for it.
"""
