"""The CLI starts without the numerical libraries: ``rockdesign --help`` and ``init`` answer in ≈ 0.2 s
(they took ≈ 0.65 s when mounting the records commands loaded numba, pint and the spectra kernels)."""
from __future__ import annotations

import subprocess
import sys

import pytest

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


# --- a mistake in a project file is reported before the engine loads (issue 50) -------------------------------
ENGINE = ("numba", "matplotlib", "weasyprint", "rockdesign.motions.excitation", "rockdesign.planar.dynamics.engine",
          "rockdesign.cylinder.kernel", "rockdesign.planar.checks.check", "rockdesign.cylinder.check",
          "rockdesign.report.render")
"""What reading and validating a project needs none of: numba, the engines, the checks, figures and the report."""
VERSION_QUIET = 0.2
"""``rockdesign --version`` on a quiet 2-core machine [s] (0.16–0.2 s measured); slower means a loaded machine."""
HEADROOM = 1.5
"""The ratio's allowance for the noise of a shared machine (both commands are timed in the same run)."""


def _misspelled(tmp_path, table: str, key: str, wrong: str):
    from rockdesign.paths import REPO_ROOT
    text = (REPO_ROOT / "examples" / "podium_flat.toml").read_text(encoding="utf-8")
    start = text.index(f"[{table}]")
    at = text.index(f"\n{key} =", start) + 1
    path = tmp_path / f"typo_{table}.toml"
    path.write_text(text[:at] + wrong + text[at + len(key):], encoding="utf-8")
    return path


def _seconds(*args: str) -> tuple[float, subprocess.CompletedProcess]:
    import time
    started = time.perf_counter()
    done = subprocess.run([sys.executable, "-m", "rockdesign.cli", *args], capture_output=True, text=True)
    return time.perf_counter() - started, done


@pytest.mark.parametrize("table, key, wrong", [("podium", "height", "heigth"), ("superstructure", "damping", "dampng"),
                                                ("analysis", "overturn", "overturning")])
def test_a_misspelled_key_is_reported_before_the_engine_loads(tmp_path, table, key, wrong):
    """`rockdesign check` of a project with a misspelled key exits 2 naming the file and the key, having loaded no
    numba, engine, check or report module (it loaded them all before it read the file: 2.2 s against 0.16 s for
    --version on a quiet machine).  The structure's tables are read first; ``[excitation]`` last, by the
    ground-motion modules, which load numba under them (its timing is the next test's)."""
    path = _misspelled(tmp_path, table, key, wrong)
    code = ("import sys; from typer.testing import CliRunner; from rockdesign.cli import app; "
            f"r = CliRunner().invoke(app, ['check', {str(path)!r}, '-o', {str(tmp_path / 'out')!r}]); "
            "print(r.exit_code); print(r.output.replace(chr(10), ' ')); "
            f"print(','.join(m for m in {ENGINE!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.splitlines()
    assert out[0] == "2" and f"{table}.{wrong}" in out[1] and path.name in out[1], out
    assert out[2] == "", f"loaded before the mistake was reported: {out[2]}"
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("table, key, wrong", [("podium", "height", "heigth"), ("excitation", "suites", "suite")])
def test_a_misspelled_key_answers_within_three_times_version_and_0_6_s(tmp_path, table, key, wrong):
    """The whole command, timed against `rockdesign --version` in the same run (best of three each): at most
    3 × version + 0.6 s, the 0.6 s scaled by how much slower than quiet this machine runs --version now."""
    path = _misspelled(tmp_path, table, key, wrong)
    version = min(_seconds("--version")[0] for _ in range(3))
    runs = [_seconds("check", str(path), "-o", str(tmp_path / "out")) for _ in range(3)]
    assert all(done.returncode == 2 and f"{table}.{wrong}" in done.stderr + done.stdout for _, done in runs)
    typo = min(seconds for seconds, _ in runs)
    load = max(1.0, version / VERSION_QUIET)
    limit = HEADROOM * (3.0 * version + 0.6 * load)
    assert typo <= limit, f"misspelled key {typo:.2f} s against --version {version:.2f} s (limit {limit:.2f} s)"
