"""The sweep's progress bar on stderr: done, failed and remaining tasks, and an ETA."""

from __future__ import annotations

import sys

from tqdm import tqdm


class SweepProgress:
    """A ``tqdm`` bar over the tasks still to run; tasks resumed from an earlier run count as done."""

    def __init__(self, total: int, already_done: int, already_failed: int) -> None:
        self.failed = already_failed
        self._bar = tqdm(
            total=total, initial=already_done, unit="task", file=sys.stderr, dynamic_ncols=True,
            mininterval=1.0, smoothing=0.1,
        )
        self._show(refresh=True)

    def _show(self, refresh: bool) -> None:
        remaining = (self._bar.total or 0) - self._bar.n
        self._bar.set_postfix_str(f"failed {self.failed}, remaining {remaining}", refresh=refresh)

    def task_done(self, solved: bool) -> None:
        if not solved:
            self.failed += 1
        self._bar.n += 1
        self._show(refresh=False)
        self._bar.update(0)

    def close(self) -> None:
        self._bar.close()
