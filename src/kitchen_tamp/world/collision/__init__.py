"""Collision checking in PyBullet: which link pairs are checked and how deep each may touch
(``checked_pairs``), the checker of arm configurations in a snapshot of a scene (``checker``,
which moves what the hand carries with ``carried_placement``), and the judge's scan for a run's
closest approach (``clearance_scan``)."""
