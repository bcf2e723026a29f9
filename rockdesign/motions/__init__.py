"""Ground motions: records, suites, scaling, spectra, pulses (SPEC §4–§5).

The modules with numba kernels (``excitation``, ``measures``, ``spectra``) refresh stale cached kernels
when they are imported (:func:`rockdesign.kernel_cache.refresh_stale_caches`); the package itself
does not, so that the command line can read the SD_max defaults (``motions.defaults``) without
importing numba (tests/cli/test_startup.py).
"""
