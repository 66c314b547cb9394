"""What a run's forked children share: whether the platform forks at all, and how a child waits for
its parent.

A child waits for the next item its parent put on a queue (a queue pickles in a thread of its
own, so the parent never waits for the child to read) or sent on a pipe, checking now and then
that the parent still runs: the child holds a copy of the sending end, so it would otherwise
wait for ever after the parent died.
"""

from __future__ import annotations

import multiprocessing
import multiprocessing.queues
import queue
from multiprocessing.connection import Connection
from typing import Final, TypeVar

PARENT_CHECK_S: Final = 1.0
"""How often (s) a child waiting for its parent checks that the parent still runs."""

Item = TypeVar("Item")


def can_fork() -> bool:
    """Whether this platform forks (the children are forked; without it, work stays in the process)."""
    return "fork" in multiprocessing.get_all_start_methods()


def _parent_gone() -> bool:
    parent = multiprocessing.parent_process()
    return parent is not None and not parent.is_alive()


def next_from_parent(items: multiprocessing.queues.Queue[Item]) -> Item:
    """The next item on ``items``; raises EOFError when the parent process is gone."""
    while True:
        try:
            return items.get(timeout=PARENT_CHECK_S)
        except queue.Empty:
            if _parent_gone():
                raise EOFError("the parent process ended") from None


def received_from_parent(connection: Connection) -> object:
    """The next object sent on ``connection``; raises EOFError when the parent process is gone."""
    while not connection.poll(PARENT_CHECK_S):
        if _parent_gone():
            raise EOFError("the parent process ended")
    return connection.recv()
