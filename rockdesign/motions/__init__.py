"""Ground motions: records, suites, scaling, spectra, pulses (SPEC §4–§5).

The package itself imports no module with a numba kernel (``excitation``, ``measures``, ``spectra``), so
that the command line can read the SD_max defaults (``motions.defaults``) without importing numba
(tests/cli/test_startup.py).
"""
