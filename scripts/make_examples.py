"""Write the example inputs of ``rockdesign calibrate`` and ``rockdesign validate`` into examples/.

    .venv/bin/python scripts/make_examples.py

- ``examples/free_vibration.csv``: a free-rocking test of the thesis specimen F02 without its feet
  (2H = 500 mm, 2B = 50 mm, λ = 0.543), made by the model itself (rockdesign.planar.experiments.synthetic):
  released from 0.7 α, c_r = 0.93 on the right and 0.9765 on the left, 500 Hz, seeded Gaussian noise
  of 0.5 % α and a sensor offset of 0.004 rad.  ``calibrate`` recovers these values.
- ``examples/validation_analyses.csv``: the model's θ_max/α of F02 under the FEMA P695 far-field suite
  at half its recorded amplitude (``rockdesign ensemble``, theoretical c_r).
- ``examples/validation_tests.csv``: a stand-in for shake-table results on the same motions: the
  model with a 5 % lower c_r and a seeded lognormal scatter of 10 % on θ_max/α.  Not measurements.

Deterministic: the seeds are fixed, so the files are the same on every run.
"""
from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SUITE, SCALE = "p695-farfield", 0.35
SPECIMEN = """\
[project]
name = "Free-rocking specimen 2H = 500 mm, 2B = 50 mm"

[column]
height = "500 mm"
width = "50 mm"
mass = "0.329 kg"
mass_distribution = 0.543

[analysis]
g = "9.807 m/s^2"
"""


def free_vibration() -> None:
    from rockdesign.planar.experiments.synthetic import free_rocking_history
    from rockdesign.planar.system import block
    alpha = math.atan(0.1)
    system = block(0.25, 0.025, 0.329, 0.543, g=9.807)
    t, theta = free_rocking_history(system, 0.7 * alpha, c_r_left=0.93 * 1.05, c_r_right=0.93, duration=15.0,
                                    rate=200.0, noise=0.005 * alpha, offset=0.004, seed=7)
    path = EXAMPLES / "free_vibration.csv"
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("# Free-rocking test of a column 2H = 500 mm, 2B = 50 mm, m = 0.329 kg, lambda = 0.543\n"
                 "# (examples/specimens/free_rocking_block.toml). NOT A MEASUREMENT: made by rockdesign's own model\n"
                 "# (scripts/make_examples.py): released at rest from 0.7 alpha, c_r = 0.93 at right-side\n"
                 "# impacts and 0.9765 at left-side ones, 200 Hz, seeded Gaussian noise of 0.5 % alpha,\n"
                 "# sensor offset 0.004 rad. 'rockdesign calibrate' should recover these values.\n")
        fh.write("t,theta\n")
        for a, b in zip(t, theta):
            fh.write(f"{a:.4f},{b:.6f}\n")
    (EXAMPLES / "specimens").mkdir(exist_ok=True)
    (EXAMPLES / "specimens" / "free_rocking_block.toml").write_text(
        "# The specimen of examples/free_vibration.csv (rockdesign calibrate\n"
        "# examples/specimens/free_rocking_block.toml --free-vibration examples/free_vibration.csv).\n"
        + SPECIMEN, encoding="utf-8")


def validation() -> None:
    import rockdesign as rd
    from rockdesign.planar.experiments.ensemble import run_ensemble, write_analyses_csv
    project = rd.load_project(EXAMPLES / "shake_table_F02.toml")
    analyses = EXAMPLES / "validation_analyses.csv"
    write_analyses_csv(run_ensemble(project, SUITE, scale=SCALE), analyses)
    from rockdesign.planar.design.quantities import coefficient_of_restitution
    c_r = coefficient_of_restitution(project.system)[0]
    weaker = run_ensemble(project, SUITE, scale=SCALE, restitution=0.95 * c_r)
    rng = np.random.default_rng(11)
    rows = weaker.rows()
    with open(EXAMPLES / "validation_tests.csv", "w", newline="", encoding="utf-8") as fh:
        fh.write(f"# Stand-in for shake-table results of specimen F02 (examples/shake_table_F02.toml) under the\n"
                 f"# FEMA P695 far-field records at {SCALE:g} x their recorded amplitude. NOT MEASUREMENTS: made by\n"
                 f"# rockdesign's own model (scripts/make_examples.py) with c_r 5 % below the theoretical\n"
                 f"# {c_r:.4f} and a seeded lognormal scatter of 10 % on theta_max/alpha.\n")
        w = csv.writer(fh)
        w.writerow(["id", "theta_max_over_alpha", "overturned"])
        for row in rows:
            over = bool(row["overturned"])
            value = "inf" if over else f"{row['theta_max_over_alpha'] * math.exp(0.1 * rng.standard_normal()):.4f}"
            w.writerow([row["id"], value, str(over).lower()])
    text = analyses.read_text(encoding="utf-8")
    analyses.write_text(f"# The model's results for specimen F02 (examples/shake_table_F02.toml) under the FEMA P695\n"
                        f"# far-field records at {SCALE:g} x their recorded amplitude, theoretical c_r: written by\n"
                        f"# rockdesign ensemble examples/shake_table_F02.toml --suite {SUITE} --scale {SCALE:g}"
                        f" -o examples/validation_analyses.csv\n" + text, encoding="utf-8")


if __name__ == "__main__":
    free_vibration()
    validation()
