"""Ground motions: records, suites, scaling, spectra, pulses (SPEC §4–§5)."""
from ..kernel_cache import refresh_stale_caches

refresh_stale_caches()
