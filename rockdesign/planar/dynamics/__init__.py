"""Equations of motion and the event-driven integrator (SPEC §3); see docs/engine.md."""
from ...kernel_cache import refresh_stale_caches

refresh_stale_caches()
