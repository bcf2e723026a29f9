"""The CLI starts without the numerical libraries: ``rockdesign --help`` and ``init`` answer in ≈ 0.2 s
(they took ≈ 0.65 s when mounting the records commands loaded numba, pint and the spectra kernels)."""
from __future__ import annotations

import subprocess
import sys

HEAVY = ("numpy", "numba", "pint", "scipy", "matplotlib", "weasyprint")


def test_mounting_the_commands_loads_no_numerical_library():
    code = ("import sys, rockdesign.cli; "
            f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "", f"imported when the CLI starts: {out.stdout.strip()}"


def test_the_records_commands_still_show_the_spectrum_defaults():
    from typer.testing import CliRunner

    from rockdesign.cli import app
    from rockdesign.motions.spectra import DEFAULT_BAND, DEFAULT_DAMPING, DEFAULT_N_PERIODS
    result = CliRunner().invoke(app, ["records", "spectrum", "--help"], env={"COLUMNS": "200"})
    assert result.exit_code == 0
    assert f"{DEFAULT_BAND[0]:g}:{DEFAULT_BAND[1]:g}" in result.output
    assert str(DEFAULT_DAMPING) in result.output and str(DEFAULT_N_PERIODS) in result.output
