"""The cylinder's 3D analyses on an executor (the shared protocol of rockdesign.execution.executor): every stage
of the check — the design-level suite, each round of the incremental scans, the perturbation ensemble — is one
batch of independent analyses, so the check is the same wherever and in whatever order they run.

Compared whole (results.json's records, acceptance, summary and ensemble, exactly) against the check in this
process: an executor that runs each batch backwards (order), and a pool of two worker processes (place)."""
from __future__ import annotations

import pytest

from rockdesign.cylinder import pairs
from rockdesign.cylinder.check import run_cylinder_check
from rockdesign.execution.counting import Counted
from rockdesign.execution.executor import LocalExecutor, is_executor
from rockdesign.library import load_project

SUITE = "test-three-pairs"
TOML = ('[project]\nname = "executor cylinder"\n[cylinder]\nheight = "3 m"\nslenderness = 0.2\nmass = "2 t"\n'
        f'[excitation]\nsuites = ["{SUITE}"]\nscale = {{ method = "resultant_pga", target = "0.45 g" }}\n'
        '[analysis]\nacceptance = "binomial"\noverturn_probability_limit = 0.8\nensemble_size = 2\n')


class Backwards(Counted):
    """An executor (start, map, close, describe, count) that runs each batch in this process, last task first, and
    keeps the size of every batch it was given."""

    slots = 10 ** 6            # as many as there are analyses: one task per analysis (a pool chunks them)

    def __init__(self):
        self.batches: list[int] = []

    def start(self):
        pass

    def map(self, func, common, tasks):
        self.batches.append(len(tasks))
        for i in reversed(list(tasks)):
            yield i, func(*common, *tasks[i])

    def close(self):
        pass

    def describe(self):
        return {"executor": "backwards"}


@pytest.fixture
def project(tmp_path, monkeypatch):
    monkeypatch.setitem(pairs.PAIR_SUITES, SUITE, ("p695-ff", range(1, 4)))
    path = tmp_path / "cyl.toml"
    path.write_text(TOML)
    return load_project(path)


def _essence(result) -> dict:
    data = result.as_json()
    return {k: data[k] for k in ("records", "acceptance", "summary", "ensemble", "verdict", "verdict_reason",
                                 "collapse_margin")}


def test_batches_in_any_order_give_the_same_check(project):
    local = LocalExecutor()
    here = run_cylinder_check(project, executor=local)
    n_here = local.analyses
    executor = Backwards()
    assert is_executor(executor)
    there = run_cylinder_check(project, executor=executor)
    assert executor.analyses == n_here          # counted on the executor the check ran through
    assert _essence(there) == _essence(here)
    # the design level (3 pairs) and the ensemble (2 × 3) are one batch each; the scans a batch per round; every
    # 3D analysis ran on the executor (the planar runs along the components, 2 per pair, in this process)
    assert executor.batches[0] == 3 and 6 in executor.batches and sum(executor.batches) == n_here - 2 * 3
    assert any(o.margin is not None and o.margin.runs for o in here.records)   # the scans ran (and were batched)


def test_a_pool_of_processes_gives_the_same_check(project):
    here = run_cylinder_check(project)
    with LocalExecutor(processes=2) as pool:
        there = run_cylinder_check(project, executor=pool)
    assert _essence(there) == _essence(here)


@pytest.mark.slow          # a local dask cluster starts (≈ 10 s)
def test_rockdesign_check_dask_runs_the_cylinder_there(project, tmp_path):
    """``rockdesign check CYL --dask local:2`` (a cylinder refused --dask before): results.json equals the run in
    this process."""
    pytest.importorskip("distributed")
    import json

    from typer.testing import CliRunner

    from rockdesign.cli import app
    runs = {}
    for name, extra in (("here", []), ("dask", ["--dask", "local:2"])):
        r = CliRunner().invoke(app, ["check", project.path, "--no-pdf", "-o", str(tmp_path / name), *extra])
        assert r.exit_code in (0, 1), r.output
        data = json.loads((tmp_path / name / "results.json").read_text())
        runs[name] = {k: data[k] for k in ("records", "acceptance", "summary", "ensemble", "verdict")}
    assert runs["dask"] == runs["here"]
