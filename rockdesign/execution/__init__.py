"""Running many independent analyses: a chunked executor, local (in-process or a process pool) or
dask.distributed (:mod:`.executor`), with fingerprints and resumable chunk files (:mod:`.store`).

It knows nothing of rocking: it calls functions on chunks of tasks.  The spectra
(:mod:`rockdesign.planar.spectra`) and the checks (:func:`rockdesign.planar.dynamics.parallel.run_motions`) both
run on it.
"""
