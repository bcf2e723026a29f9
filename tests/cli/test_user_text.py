"""What users read cites what users have: the thesis and the repository's docs, never the team's
internal SPEC/CONTRACT files; labels say what they mean (capacity u_B(θc), units in CSV headers)."""
from __future__ import annotations

import json
import re

import pytest
from typer.testing import CliRunner

from rockdesign.cli import app
from rockdesign.paths import REPO_ROOT

runner = CliRunner()
INTERNAL = re.compile(r"\b(SPEC|CONTRACT) §")
COMMANDS = [[], ["init"], ["quantities"], ["simulate"], ["check"], ["spectrum"], ["bench"], ["records"],
            ["records", "list"], ["records", "show"], ["records", "spectrum"], ["records", "synth"]]


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: " ".join(c) or "root")
def test_help_cites_no_internal_document(command):
    r = runner.invoke(app, [*command, "--help"])
    assert r.exit_code == 0
    assert not INTERNAL.search(r.output), r.output


def test_docs_and_templates_cite_no_internal_document():
    offenders = []
    for folder in ("docs", "templates"):
        for path in (REPO_ROOT / folder).rglob("*"):
            if path.suffix in (".md", ".j2", ".toml", ".html", ".css") and INTERNAL.search(path.read_text("utf-8")):
                offenders.append(str(path.relative_to(REPO_ROOT)))
    assert not offenders


def test_model_doc_exists_and_cites_thesis_equations():
    text = (REPO_ROOT / "docs" / "model.md").read_text("utf-8")
    for eq in ("Eq 3.13", "Eq 3.14", "Eq 3.56", "Eq 4.8", "Eq 4.20", "Eq 2.8", "Eq 3.44", "Eq 6.5"):
        assert eq in text, eq
    assert "## 8. Verdict" in text and "29" in text           # the minimum suite for a 10 % bound


def test_polyakov_line_is_labelled_with_the_capacity():
    from rockdesign.planar.spectra.figures import polyakov_label
    assert polyakov_label(1.2) == "Polyakov: SD_max = u_B(θc) = 1.2 m"
    assert "2B" not in polyakov_label(None)


def test_results_csv_headers_carry_units():
    from rockdesign.planar.checks.results_csv import CSV_COLUMNS, CSV_UNITS
    from rockdesign.report.results import csv_header
    headers = [csv_header(c, CSV_UNITS) for c in CSV_COLUMNS]
    assert "pga [m/s^2]" in headers and "sd_max [m]" in headers and "uplift_time [s]" in headers
    assert "id" in headers and "impacts" in headers


def test_unit_messages_use_the_right_article(tmp_path):
    p = tmp_path / "p.toml"
    p.write_text('[project]\nname = "x"\n[column]\nheight = "3 m"\nslenderness = 0.1\nmass = "1 t"\n'
                 'mass_distribution = 0.3333\n[excitation]\ndesign_pga = "0.35 kg"\n', encoding="utf-8")
    r = runner.invoke(app, ["quantities", str(p)])
    assert r.exit_code == 2 and "a acceleration" not in r.output


def test_suite_without_records_message(tmp_path):
    manifest = tmp_path / "s.toml"
    manifest.write_text('name = "s"\n', encoding="utf-8")
    r = runner.invoke(app, ["records", "list", "--suite", str(manifest)])
    assert r.exit_code == 2 and "NoneType" not in r.output and "no 'records' key" in " ".join(r.output.split())


@pytest.mark.slow
def test_mostly_missing_suite_is_named_and_refused(tmp_path):
    """thesis-table-4.1 without records_dir: 9 of 13 records missing.  The 4 found are two components each of two
    stations (A7/A8 = p695-nfp/6, A9/A10 = p695-ff/11): 2 ground motions, fewer than the 11 the acceptance rule
    needs: refused before any analysis (exit 2), naming the missing records."""
    p = tmp_path / "p.toml"
    p.write_text('[project]\nname = "stocky"\n[column]\nheight = "3 m"\nslenderness = 0.3\nmass = "1 t"\n'
                 'mass_distribution = 0.3333\n[excitation]\nsuites = ["thesis-table-4.1"]\n'
                 'scale = { method = "pga", target = "0.1 g" }\n', encoding="utf-8")
    out = tmp_path / "out"
    r = runner.invoke(app, ["check", str(p), "-o", str(out), "--no-pdf", "--no-margins"])
    assert r.exit_code == 2, r.output
    flat = " ".join(r.output.split())
    assert "thesis-table-4.1: 2 ground motion(s) from 4 record(s); 9 record(s) not found" in flat
    assert "at least 11 independent ground motions" in flat and not (out / "results.json").exists()


def test_templates_state_the_documented_defaults():
    """`init podium` wrote `rtol = 1e-10 # (default 1e-10)` while the documented default is 1e-8."""
    import re

    import rockdesign as rd
    from rockdesign.templates import template_names, template_text
    default = rd.parse_project('[project]\nname = "x"\n[column]\nheight = "3 m"\nwidth = "0.5 m"\nmass = "1 t"\n'
                               'mass_distribution = 0.333\n', name="x").analysis.rtol
    for kind in template_names():
        stated = [float(m.group(1)) for line in template_text(kind).splitlines() if line.startswith("rtol")
                  for m in [re.search(r"\(default ([0-9.e+-]+)[;:)]", line)] if m]
        assert stated == [default], (kind, stated)


COMMANDS = [[], ["init"], ["quantities"], ["simulate"], ["check"], ["spectrum"], ["bench"], ["calibrate"],
            ["validate"], ["ensemble"], ["design"], ["records"], ["records", "list"], ["records", "show"],
            ["records", "spectrum"], ["records", "synth"], ["records", "scale-model"]]


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: " ".join(c) or "rockdesign")
def test_help_fits_80_columns_without_cutting_words(command):
    """`spectrum --help` cut its defaults at 80 columns ("omega_p/p:0.5:12…")."""
    import os
    import subprocess
    import sys
    env = {**os.environ, "COLUMNS": "80", "TERMINAL_WIDTH": "80"}
    out = subprocess.run([sys.executable, "-m", "rockdesign.cli", *command, "--help"], capture_output=True,
                         text=True, env=env, timeout=60)
    assert out.returncode == 0, out.stderr
    assert "…" not in out.stdout, [ln for ln in out.stdout.splitlines() if "…" in ln]


def test_top_level_and_check_help_name_every_exit_code_and_command():
    import os
    import subprocess
    import sys
    env = {**os.environ, "COLUMNS": "200"}

    def help_of(*args):
        return " ".join(subprocess.run([sys.executable, "-m", "rockdesign.cli", *args, "--help"], capture_output=True,
                                       text=True, env=env, timeout=60).stdout.split())
    top = help_of()
    for code in ("0 =", "1 =", "2 = input error", "3 = internal error", "4 = not decided", "130 = interrupted"):
        assert code in top, code
    assert "scale-model" in top
    check = help_of("check")
    assert "3 = internal error" in check and "4 = not decided" in check
    assert "scale-model" in help_of("records")


def test_one_form_of_units_for_a_reader():
    """Units were printed m/s^2 beside m/s²: the console and the report write m/s², JSON keeps m/s^2."""
    from typer.testing import CliRunner

    from rockdesign.cli import app
    from rockdesign.display import readable_units
    from rockdesign.paths import REPO_ROOT
    from rockdesign.report.render import symbols
    assert readable_units("median PGA 8.785 m/s^2 over 2.5 t/m^3") == "median PGA 8.785 m/s² over 2.5 t/m³"
    assert symbols("PGA 8.785 m/s^2") == "PGA 8.785 m/s²"
    res = CliRunner().invoke(app, ["quantities", str(REPO_ROOT / "examples" / "podium_flat.toml")])
    assert res.exit_code == 0 and "m/s²" in res.stdout and "m/s^2" not in res.stdout
    res = CliRunner().invoke(app, ["quantities", str(REPO_ROOT / "examples" / "podium_flat.toml"), "--json"])
    assert '"m/s^2"' in res.stdout


def test_documentation_references_carry_the_reports_name(monkeypatch):
    """The console cited docs/model.md §7 where the report says Appendix M4: it now gives both."""
    from typer.testing import CliRunner

    import importlib

    from rockdesign.cli import app
    from rockdesign.console import make_console
    from rockdesign.paths import REPO_ROOT
    # a wide table, whatever COLUMNS was when the command line was imported (the module's console read it then)
    monkeypatch.setattr(importlib.import_module("rockdesign.cli.app"), "console", make_console(width=250))
    res = CliRunner().invoke(app, ["quantities", str(REPO_ROOT / "examples" / "podium_curved.toml")])
    text = " ".join(res.stdout.split())
    assert res.exit_code == 0
    assert "docs/model.md §7 (report: Appendix M4)" in text
    assert text.count("docs/model.md") == text.count("(report: Appendix")
