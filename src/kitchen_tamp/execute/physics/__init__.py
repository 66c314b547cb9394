"""Execution under physics: the trajectory run by joint motors in a simulated kitchen with
gravity and friction, and the scene compared with what the plan says after each action.

``execution`` runs and judges; ``plan`` says what the scene should look like;
``time_law`` says when the arm should be where; ``replanning`` closes the loop in
a planning run.
"""
