"""How many analyses ran: one counter shared by every kind's check (the design grid reports what each variant
ran and what shared work saved)."""
from __future__ import annotations

import threading


class AnalysisCount:
    """Analyses run in this process (``total``) and in the calling thread (:meth:`mine`): record × scale jobs
    of :func:`run_jobs`, and the cylinder check's (one per record pair run in 3D or per component in the
    plane).  The design grid, which checks its variants in threads of their own, reads the calling thread's
    count around a variant to report what it ran and what its shared work saved."""

    total = 0
    _lock = threading.Lock()
    _local = threading.local()

    @classmethod
    def add(cls, n: int) -> None:
        """Count ``n`` analyses run for the calling thread."""
        with cls._lock:
            cls.total += n
        cls._local.n = cls.mine() + n

    @classmethod
    def mine(cls) -> int:
        """The analyses counted for the calling thread."""
        return getattr(cls._local, "n", 0)
