"""How many analyses ran, counted on the executor they ran through (the executor protocol's ``count``).

Every executor (:class:`~rockdesign.execution.executor.LocalExecutor`, :class:`~rockdesign.execution.executor.DaskExecutor`,
the design grid's :class:`~rockdesign.execution.batch_pool.PoolMember`) is :class:`Counted`: a kind's check calls
``executor.count(n)`` for the analyses it hands to it, so whoever passed the executor reads what its work cost
(the design grid: each variant's ``analyses``) — no count shared by the whole process.
"""
from __future__ import annotations

import threading


class Counted:
    """``analyses``: the analyses counted on this object (:meth:`count`; thread-safe)."""

    analyses: int = 0

    def count(self, n: int) -> None:
        """Count ``n`` analyses run through this executor."""
        lock = self.__dict__.get("_count_lock")
        if lock is None:
            lock = self.__dict__.setdefault("_count_lock", threading.Lock())
        with lock:
            self.analyses = self.analyses + int(n)


__all__ = ["Counted"]
