"""Tolerance study of the superstructure demand: at which rtol its suite statistics converge.

For every example podium with an elastic superstructure the design-level suite is analysed with the 2DOF
podium model (exact equations) at rtol = 1e-7 … 1e-11 (atol as the project's), and the statistics the check
reports (``summary.superstructure``: median, 84th percentile and maximum of the shear coefficient |f_s|/g
and of the force ratio over the records that did not overturn) are tabulated, with the number of records
whose peak moves by more than 2 % from the previous tolerance.  Writes
``benchmarks/results/demand_tolerances.json`` and the "Superstructure demand" section of
``docs/tolerances.md`` (``bench_tolerances.py`` keeps that section when it rewrites the page).

    .venv/bin/python benchmarks/bench_demand_tolerances.py [--projects examples/podium_flat.toml ...]
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from rockdesign.bench.timing import machine_info  # noqa: E402
from rockdesign.planar.checks.check import check_records  # noqa: E402
from rockdesign.planar.checks.demand import DEMAND_RTOL, fixed_base_damping, record_demand, stats_of  # noqa: E402
from rockdesign.planar.checks.runner import run_jobs  # noqa: E402
from rockdesign.planar.dynamics.model import ModelChoice  # noqa: E402
from rockdesign.jsonable import json_ready  # noqa: E402
from rockdesign.library import load_project  # noqa: E402

RTOLS = (1e-7, 1e-8, 1e-9, 1e-10, 1e-11)
SECTION = "## Superstructure demand"
PROJECTS = ("examples/podium_flat.toml", "examples/podium_curved.toml")


def study_project(path: str, rtols) -> dict:
    """Demand statistics of one project's design-level suite at each rtol (2DOF podium, exact equations)."""
    p = load_project(ROOT / path)
    a = p.analysis
    motions = [r.motion for r in check_records(p).records]
    zeta = fixed_base_damping(p.system)
    rows, previous = [], None
    for rtol in rtols:
        t0 = time.perf_counter()
        runs = run_jobs(p.system, ModelChoice("podium-2dof", "exact"), motions, [1.0] * len(motions), rtol=rtol,
                        atol=a.atol, free_vibration=a.free_vibration, criterion=a.overturn,
                        rest_velocity=a.rest_velocity)
        seconds = time.perf_counter() - t0
        per = [record_demand(r, m, p.system, zeta) for r, m in zip(runs, motions)]
        ok = [i for i, r in enumerate(runs) if not r.overturned]
        peaks = np.array([d["shear_coefficient_max"] for d in per])
        moved = None if previous is None else np.abs(peaks / previous - 1.0)
        rows.append({"rtol": rtol, "seconds": seconds, "n_records": len(ok),
                     "shear_coefficient": stats_of([per[i]["shear_coefficient_max"] for i in ok]),
                     "force_ratio": stats_of([per[i]["force_ratio"] for i in ok]),
                     "n_moved_over_2pc": None if moved is None else int(np.sum(moved > 0.02)),
                     "largest_move": None if moved is None else float(moved.max())})
        previous = peaks
        print(f"{path} rtol={rtol:.0e}: {rows[-1]['shear_coefficient']} {rows[-1]['force_ratio']} "
              f"({seconds:.1f} s)", flush=True)
    return {"project": path, "rows": rows}


def _e(x: float) -> str:
    """1e-08 → 1e-8."""
    return f"{x:.0e}".replace("e-0", "e-")


def section(study: dict) -> str:
    """The "Superstructure demand" section of docs/tolerances.md."""
    def trio(s):
        return " / ".join(f"{s[k]:.4f}" for k in ("median", "p84", "max"))
    lines = [SECTION, "",
             "The superstructure's peak absolute acceleration |f_s| (docs/model.md §10) is more sensitive to the "
             "tolerance than θ_max: a rest decision at the rest velocity can flip between tolerances and move one "
             "record's peak by several percent while θ_max does not move. Its **suite statistics** are what the check "
             "reports, so they are converged on their own: each example podium's design-level suite, 2DOF model, "
             "exact equations (`benchmarks/bench_demand_tolerances.py`):", "",
             "| example | rtol | shear coefficient median / p84 / max | force ratio median / p84 / max | records moving > 2 % vs the previous rtol |",
             "|---|---|---|---|---|"]
    for proj in study["projects"]:
        name = Path(proj["project"]).stem
        for r in proj["rows"]:
            moved = "—" if r["n_moved_over_2pc"] is None else f"{r['n_moved_over_2pc']} (largest {100 * r['largest_move']:.2g} %)"
            lines.append(f"| {name} | {_e(r['rtol'])} | {trio(r['shear_coefficient'])} | {trio(r['force_ratio'])} | {moved} |")
    lines += ["",
              "From rtol 1e-8 on, every statistic stays within 0.3 % of its value at 1e-11; single records keep "
              "moving by about 1 % below 1e-8 (rest decisions and the peak's sampling), so a per-record demand is "
              f"quoted to 2 %. The check reads the demand at rtol ≤ {_e(DEMAND_RTOL)} "
              "(`rockdesign.planar.checks.demand.DEMAND_RTOL`): the default rtol already is 1e-8, so the demand costs no "
              "extra analysis; a project with a looser `[analysis] rtol` gets a separate 2DOF run at 1e-8 for the "
              "demand, and the report's note says so.", ""]
    return "\n".join(lines)


def replace_section(page: str, text: str) -> str:
    """``page`` with its "Superstructure demand" section (to the end of the page) replaced by ``text``."""
    head = page.split(SECTION)[0].rstrip("\n")
    return head + "\n\n" + text


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--projects", nargs="*", default=list(PROJECTS))
    ap.add_argument("--rtols", nargs="*", type=float, default=list(RTOLS))
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "demand_tolerances.json"))
    ap.add_argument("--docs", default=str(ROOT / "docs" / "tolerances.md"))
    args = ap.parse_args(argv)
    info = machine_info()
    study = {"benchmark": "demand_tolerances", "date": info["date"], "machine": info,
             "projects": [study_project(p, sorted(args.rtols, reverse=True)) for p in args.projects]}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(json_ready(study), indent=1) + "\n", encoding="utf-8")
    docs = Path(args.docs)
    docs.write_text(replace_section(docs.read_text(encoding="utf-8"), section(study)), encoding="utf-8")
    print(f"wrote {args.out} and the demand section of {args.docs}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
