"""What a forked child of a run waits for from its parent: the next item its parent put on a queue.

The parent puts (a queue pickles in a thread of its own, so the parent never waits
for the child to read); the child waits, checking now and then that the parent
still runs: the child holds a copy of the queue's sending end, so it would
otherwise wait for ever after the parent died.
"""

from __future__ import annotations

import multiprocessing
import multiprocessing.queues
import queue
from typing import Final, TypeVar

PARENT_CHECK_S: Final = 1.0
"""How often (s) a child waiting for its parent checks that the parent still runs."""

Item = TypeVar("Item")


def next_from_parent(items: multiprocessing.queues.Queue[Item]) -> Item:
    """The next item on ``items``; raises EOFError when the parent process is gone."""
    parent = multiprocessing.parent_process()
    while True:
        try:
            return items.get(timeout=PARENT_CHECK_S)
        except queue.Empty:
            if parent is not None and not parent.is_alive():
                raise EOFError("the parent process ended") from None
