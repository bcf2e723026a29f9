"""Measurement: the distance to the flip of a check (its λ_count and Ŝ_CT/S_MT) against a brute-force scan of the
design-level suite on a 1 % grid of amplitude factors — how much the scans' resolution (ratio 1.2, the first
rise bisected to margin_precision) misses of a chaotic response's narrow overturning bands.

The suite: 11 far-field ground motions (p695-ff/1a … 11a at 0.4 g) on the 20-column podium of
tests/checks/test_flip_margin.py (rigid superstructure, 2.5 m columns), at the column widths given.  For each
width: the check's values, the fine grid's (201 factors 0.45 … 3.3 × design, every record at every factor) and
each record's first overturning factor by both.  The tests assert what must hold (the fine grid never lies above
the check by more than the two grids' resolution); this script prints what was measured for docs/design.md.

    .venv/bin/python benchmarks/flip_resolution.py [--widths 0.6,0.65] [--out benchmarks/results/flip_resolution.json]
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))


def order(values, k):
    found = sorted(v for v in values if v is not None)
    return found[k - 1] if len(found) >= k else None


def main(argv=None) -> int:
    import rockdesign as rd
    from support import brute_first_factors, stocky_podium_toml
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--widths", default="0.6,0.65")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "flip_resolution.json"))
    args = ap.parse_args(argv)
    base = stocky_podium_toml(records=[f"p695-ff/{k}a" for k in range(1, 12)], pga="0.4 g", analysis="",
                              height="2.5 m")
    factors = [float(f) for f in 0.45 * 1.01 ** np.arange(201)]
    rows = []
    for w in args.widths.split(","):
        t0 = time.perf_counter()
        project = rd.parse_project(base.replace('width = "0.6 m"', f'width = "{w} m"'))
        result = rd.check(project)
        check = [1.0 if o.run.overturned and (o.margin.overturn_scale is None or o.margin.overturn_scale > 1.0)
                 else o.margin.overturn_scale for o in result.records]
        fine = brute_first_factors(project, result, lambda i: factors)
        acc = result.acceptance
        row = {"width_m": float(w), "verdict": result.verdict, "flip_margin": acc["flip_margin"],
               "flip_governing": acc["flip"]["governing"],
               "count_scan": order(check, 2), "count_fine": order(fine, 2),
               "acmr_scan": acc["acmr"], "acmr_fine": order(fine, 6), "acmr_required": acc["acmr_required"],
               "records": {o.id: {"scan": c, "fine": f} for o, c, f in zip(result.records, check, fine)},
               "records_lower_on_fine_grid": sum(1 for c, f in zip(check, fine)
                                                  if f is not None and (c is None or f < c / 1.02)),
               "seconds": time.perf_counter() - t0}
        rows.append(row)
        print(f"2B = {w} m: {row['verdict']}, flip margin {row['flip_margin']:.3g} ({row['flip_governing']}); "
              f"λ_count scan {row['count_scan']:.3g} vs 1 % grid {row['count_fine']:.3g}; Ŝ_CT/S_MT scan "
              f"{row['acmr_scan']:.3g} vs 1 % grid {row['acmr_fine']:.3g}; {row['records_lower_on_fine_grid']} of "
              f"{len(check)} records overturn first more than 2 % lower on the fine grid")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps({"date": datetime.now(timezone.utc).isoformat(timespec="seconds"),
                                          "factors": {"from": factors[0], "ratio": 1.01, "n": len(factors)},
                                          "rows": rows}, indent=1) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
