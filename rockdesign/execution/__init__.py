"""Running many independent analyses: the executor protocol every kind's check accepts (run a batch, count its
analyses: :data:`.executor.EXECUTOR_METHODS`, :mod:`.counting`), a chunked executor, local (in-process or a process
pool) or dask.distributed (:mod:`.executor`), the design grid's pool that merges the batches of many checks
(:mod:`.batch_pool`), with fingerprints and resumable chunk files (:mod:`.store`).

It knows nothing of rocking: it calls functions on chunks of tasks.  The spectra, the planar checks
(:func:`rockdesign.planar.checks.runner.run_jobs`) and the cylinder's (:mod:`rockdesign.cylinder.batch`) all
run on it.
"""
