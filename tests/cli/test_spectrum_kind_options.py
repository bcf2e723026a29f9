"""``rockdesign spectrum`` takes each kind's options from the kind (``StructureKind.spectrum_cli``): a kind with an
option of its own needs no edit of ``rockdesign/cli/spectrum.py``; the built-in kinds' flags are the same as before
they moved out of the command (a user contract); and mounting the commands still imports no kind."""
from __future__ import annotations

import json
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import pytest
import typer
from typer.testing import CliRunner

import rockdesign
from rockdesign.cli import app
from rockdesign.errors import RockdesignError
from rockdesign.kinds import register, registered, unregister
from rockdesign.kinds.base import StructureKind, unavailable
from rockdesign.kinds.options import CliOption, OptionConflict, merged_options
from rockdesign.paths import REPO_ROOT
from rockdesign.project_tables import Project, parse_analysis

runner = CliRunner()
WIDE = {"COLUMNS": "240", "TERMINAL_WIDTH": "240"}
"""One option per line of ``--help`` (rich wraps at the terminal's width)."""
PIER = str(REPO_ROOT / "examples" / "bridge_pier.toml")
PROJECT = """
[project]
name = "friction test block"
[friction_test_block]
"""


@dataclass
class FrictionSpectrum:
    """What the test kind's spectrum returns: the options it was given."""

    out_dir: Path
    given: dict
    title: str = "friction test spectrum"

    def as_json(self) -> dict:
        return {"given": {k: v if isinstance(v, (bool, int, float, str)) else str(v) for k, v in self.given.items()}}

    def summary_rows(self) -> list:
        return [(name, str(value)) for name, value in self.given.items()]


class FrictionBlock(StructureKind):
    """A kind of structure written in this test: a block whose spectrum takes a friction angle, an option no other
    kind has.  Its spectrum records what it is given; it offers nothing else."""

    name = "friction_test_block"
    systems = ("friction_test_block",)
    spectrum_options = ("friction_angle", "out_dir", "figures")
    spectrum_cli = (CliOption("friction_angle", float, "Interface friction angle in degrees (default: 30).",
                              metavar="DEG", applies_to="friction test blocks"),)

    def __init__(self):
        self.seen: list[dict] = []

    def claims(self, raw):
        return "friction_test_block" in raw

    def parse(self, raw, *, file, text):
        analysis = parse_analysis(raw.get("analysis", {}), file)
        return Project(path=file, name=raw["project"]["name"], system=SimpleNamespace(kind=self.systems[0]),
                       analysis=analysis, raw=raw, source_text=text)

    def quantities(self, project):
        raise unavailable("design quantities", self.name, "project")

    def simulation_request(self, project, motion, *, model, t_end, rtol, records_dir):
        raise unavailable("a time-history analysis", self.name, "project")

    def run_simulation(self, request):
        raise unavailable("a time-history analysis", self.name, "project")

    def check(self, project, *, progress, records_dir, margins, executor):
        raise unavailable("a design check", self.name, "project")

    def report(self, result):
        raise unavailable("a report", self.name, "project")

    def spectrum(self, project, request):
        given = request.accepted(self.spectrum_options, "the spectrum of a friction test block", "friction_angle")
        angle = given.get("friction_angle", 30.0)
        if not 0.0 < angle < 90.0:
            raise RockdesignError("out of range", key="friction_angle", expected="an angle in (0, 90) degrees",
                                  found=repr(angle))
        self.seen.append(given)
        return FrictionSpectrum(out_dir=Path(given.get("out_dir") or "friction-spectrum"), given=given)


@pytest.fixture
def friction_kind():
    """The test kind, registered for one test; the registry as it was afterwards."""
    before = [k.name for k in registered()]
    kind = register(FrictionBlock())
    yield kind
    unregister(kind.name)
    assert [k.name for k in registered()] == before


@pytest.fixture
def friction_project(tmp_path):
    path = tmp_path / "friction.toml"
    path.write_text(PROJECT, encoding="utf-8")
    return path


def _help() -> str:
    r = runner.invoke(app, ["spectrum", "--help"], env=WIDE)
    assert r.exit_code == 0, r.output
    return r.output


def _has_flag(text: str, flag: str) -> bool:
    return re.search(rf"(?<![\w-]){re.escape(flag)}(?![\w-])", text) is not None


def _spectrum_command():
    return typer.main.get_command(app).commands["spectrum"]


# --- (a) a kind's own option, with no edit of the command ------------------------------------------------------
def test_a_new_kinds_option_is_in_the_help_and_gone_with_the_kind(friction_kind):
    text = _help()
    line = next(ln for ln in text.splitlines() if _has_flag(ln, "--friction-angle"))
    assert "DEG" in line and "Friction test blocks: Interface friction angle in degrees" in line, line
    assert _has_flag(text, "--pulse") and _has_flag(text, "--record")      # the built-in kinds' options stay
    unregister(friction_kind.name)                                           # the command follows the registry
    assert not _has_flag(_help(), "--friction-angle")
    register(friction_kind)
    assert _has_flag(_help(), "--friction-angle")


def test_a_new_kinds_option_reaches_its_spectrum(friction_kind, friction_project, tmp_path):
    out = tmp_path / "out"
    r = runner.invoke(app, ["spectrum", str(friction_project), "--friction-angle", "32.5", "-o", str(out), "--json"])
    assert r.exit_code == 0, r.output
    assert friction_kind.seen == [{"friction_angle": 32.5, "out_dir": out, "figures": True}]
    assert json.loads(r.stdout)["given"]["friction_angle"] == 32.5
    r = runner.invoke(app, ["spectrum", str(friction_project), "--no-figures"])     # left out: not passed
    assert r.exit_code == 0, r.output
    assert friction_kind.seen[-1] == {"figures": False}


def test_a_new_kinds_errors_name_its_flag(friction_kind, friction_project):
    r = runner.invoke(app, ["spectrum", str(friction_project), "--friction-angle", "95"])
    assert r.exit_code == 2 and "Traceback" not in r.output
    assert "key '--friction-angle'" in r.stderr and "found 95.0" in r.stderr, r.stderr
    r = runner.invoke(app, ["spectrum", str(friction_project), "--friction-angle", "abc"])   # typer's own check
    assert r.exit_code == 2 and "--friction-angle" in r.output
    r = runner.invoke(app, ["spectrum", str(friction_project), "--pulse", "sine"])     # another kind's option
    assert r.exit_code == 2 and "key '--pulse'" in r.stderr and "friction test block" in r.stderr, r.stderr


def test_the_command_names_no_kind():
    """The command module names no kind's option (each kind declares its own) and no kind."""
    source = (REPO_ROOT / "rockdesign" / "cli" / "spectrum.py").read_text(encoding="utf-8")
    flags = [f"--{option.name.replace('_', '-')}" for kind in (*registered(), FrictionBlock())
             for option in kind.spectrum_cli]
    assert len(flags) > 10 and [f for f in flags if _has_flag(source, f)] == []
    assert not re.search(r"pulse|record|cylinder|planar|polyakov|friction", source, re.IGNORECASE)


# --- (b) the built-in kinds' flags, as before -----------------------------------------------------------------------
FLAGS = ("--pulse -p --record --x --y --relative --dask -o --out --model --structure --overturn --t-free --rtol "
         "--tm-ratio --chunk-rows --resume --no-resume --keep-chunks --energy-stop --no-energy-stop --stop-at-capacity "
         "--polyakov --no-polyakov --equivalent-at --figures --no-figures --json --quiet -q").split()


def test_every_flag_of_the_command_is_still_there():
    text = _help()
    assert [f for f in FLAGS if not _has_flag(text, f)] == []
    command = _spectrum_command()
    flags = {f for p in command.params for f in [*p.opts, *p.secondary_opts] if f.startswith("-")}
    assert flags == set(FLAGS)
    params = {p.name: p for p in command.params}
    assert params["equivalent_at"].multiple and params["equivalent_at"].metavar == "Y"
    assert params["resume"].is_flag and params["resume"].secondary_opts == ["--no-resume"]
    assert params["keep_chunks"].is_flag and not params["keep_chunks"].secondary_opts
    assert all(params[name].default is None for name in ("pulse", "x", "chunk_rows", "resume", "keep_chunks"))


def test_an_axis_declared_by_two_kinds_is_one_option_with_both_helps():
    x = next(ln for ln in _help().splitlines() if _has_flag(ln, "--x"))
    assert x.count("--x") == 1 and "Planar structures: x axis" in x and "cylinders: R in m" in x, x


def test_the_values_reach_rd_spectrum_unchanged(monkeypatch):
    seen = []

    def spectrum(project, **options):
        seen.append(options)
        raise RockdesignError("stop here", key="project", expected="nothing", found="the test")

    monkeypatch.setattr(rockdesign, "spectrum", spectrum)
    runner.invoke(app, ["spectrum", PIER, "-p", "sine", "--chunk-rows", "3", "--t-free", "5", "--no-resume",
                        "--keep-chunks", "--equivalent-at", "1", "--equivalent-at", "2.5", "--dask", "local:2"])
    runner.invoke(app, ["spectrum", PIER])
    given, left_out = seen
    assert {k: given[k] for k in ("pulse", "chunk_rows", "t_free", "resume", "keep_chunks", "equivalent_at",
                                  "executor", "polyakov", "record")} == {
        "pulse": "sine", "chunk_rows": 3, "t_free": 5.0, "resume": False, "keep_chunks": True,
        "equivalent_at": [1.0, 2.5], "executor": "local:2", "polyakov": None, "record": None}
    assert {k for k, v in left_out.items() if v is not None} - {"progress", "say"} == {"figures"}


# --- declarations that cannot make one command -------------------------------------------------------------------
def _kind(name, options, takes=None):
    return SimpleNamespace(name=name, spectrum_cli=options, spectrum_options=takes or tuple(o.name for o in options))


def test_two_kinds_declaring_one_option_differently_is_a_programming_error():
    with pytest.raises(OptionConflict, match="'a' and 'b' declare the spectrum option 'x' differently"):
        merged_options([_kind("a", (CliOption("x", help="1"),)), _kind("b", (CliOption("x", float, "2"),))])
    with pytest.raises(OptionConflict, match="does not take"):
        merged_options([_kind("a", (CliOption("x"),), takes=("y",))])
    with pytest.raises(OptionConflict, match="only a bool option"):
        CliOption("x", float, negatable=True)
    merged = merged_options([_kind("a", (CliOption("x", help="one", applies_to="as"),)),
                             _kind("b", (CliOption("x", help="two"),))])
    assert merged == (CliOption("x", help="As: one; b: two"),)


def test_a_kind_option_taking_a_flag_of_the_command_or_of_another_kind_is_refused():
    class Loud(FrictionBlock):
        name = "loud_test_block"
        spectrum_options = ("quiet",)
        spectrum_cli = (CliOption("quiet", bool, "Say nothing."),)
    class Short(FrictionBlock):
        name = "short_test_block"
        spectrum_options = ("pressure",)
        spectrum_cli = (CliOption("pressure", float, "Pore pressure in Pa.", short="p"),)   # -p is --pulse's

    for kind, name in ((Loud(), "'quiet'"), (Short(), "'pulse'")):
        register(kind)
        try:
            r = runner.invoke(app, ["spectrum", "--help"])
            assert isinstance(r.exception, TypeError) and name in str(r.exception), r.exception
        finally:
            unregister(kind.name)
    assert _has_flag(_help(), "--quiet") and _has_flag(_help(), "-p")


# --- (c) mounting the commands imports no kind ------------------------------------------------------------------
def test_the_command_line_starts_without_the_kinds():
    kinds = ("rockdesign.kinds", "rockdesign.planar.kind", "rockdesign.cylinder.kind", "scipy", "pint")
    code = ("import sys; from typer.testing import CliRunner; import rockdesign.cli as cli; "
            f"loaded = lambda: [m for m in {kinds!r} if m in sys.modules]; print(loaded()); "
            "[CliRunner().invoke(cli.app, args) for args in (['--version'], ['--help'], ['check', '--help'])]; "
            "print(loaded()); CliRunner().invoke(cli.app, ['spectrum', '--help']); print(loaded())")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.splitlines()
    assert out[:2] == ["[]", "[]"], out
    assert "'rockdesign.planar.kind'" in out[2]          # the spectrum's help reads the kinds' declarations
    assert "'pint'" not in out[2] and "'scipy'" not in out[2]    # … without the units or the engines (0.26 s, not 0.66)
