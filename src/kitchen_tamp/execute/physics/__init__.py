"""Execution under physics: the trajectory run by joint motors in a simulated kitchen with
gravity and friction, and the scene compared with the plan, as the kinematic judge read
it, after each action.

``execution`` runs and judges; ``rollout`` drives the arm and grip tick by tick and
watches contacts, tracking and slip; ``verdict`` holds the record and its bounds;
``time_law`` says when the arm should be where; ``replanning`` closes the loop in a
planning run.
"""
