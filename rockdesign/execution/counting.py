"""How many analyses ran: one counter shared by every kind's check (the design grid reports what each variant
ran and what shared work saved; variants that share batches count theirs on their
:class:`~rockdesign.execution.batch_pool.PoolMember`)."""
from __future__ import annotations

import threading


class AnalysisCount:
    """Analyses run in this process (``total``): record × scale jobs of the planar check's runs, and the
    cylinder check's (one per record pair run in 3D or per component in the plane)."""

    total = 0
    _lock = threading.Lock()

    @classmethod
    def add(cls, n: int) -> None:
        """Count ``n`` analyses."""
        with cls._lock:
            cls.total += n
