"""The solver stability study: where each method fails or degrades, with evidence (stability.md).

Each case (:mod:`rockdesign.bench.stability_cases`) provokes one failure condition with a small,
fast problem, runs our engine and the scipy methods, and returns a :class:`StabilityCase`: one
:class:`Outcome` per method (verdict ``ok`` | ``degrades`` | ``fails`` with the measured detail),
the diagnosed result of our engine (status and counters), what our engine does, and the data of its
evidence plot.  :func:`run_stability` runs them all; :func:`stability_markdown` writes the table.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

ALL_METHODS = ("rockdesign", "scipy RK45", "scipy DOP853", "scipy LSODA", "scipy Radau")
VERDICTS = ("ok", "degrades", "fails")


@dataclass
class Outcome:
    """How one method fares in one case.

    Attributes:
        method: method name (:data:`ALL_METHODS`).
        verdict: ``ok`` | ``degrades`` (right answer at a higher cost or lower accuracy than asked)
            | ``fails`` (wrong answer, crash, hang guard tripped) | ``n/a``.
        detail: the measured evidence in one sentence.
        data: the numbers behind it.
    """

    method: str
    verdict: str
    detail: str
    data: dict = field(default_factory=dict)


@dataclass
class StabilityCase:
    """One failure condition of the study.

    Attributes:
        key: short identifier (file names).
        condition: the failure condition (table row title).
        setup: how it is provoked (system, excitation, tolerances).
        outcomes: one :class:`Outcome` per method run.
        engine: diagnosed result of our engine (status, counters, the run it comes from).
        engine_behaviour: what our engine does in this case (mechanism and measured effect).
        plot: callable returning the evidence figure (``plot(case)``), or None.
        data: arrays and numbers for the plot.
        seconds: wall time of the case [s].
    """

    key: str
    condition: str
    setup: str
    outcomes: list[Outcome]
    engine: dict
    engine_behaviour: str
    plot: Callable | None = None
    data: dict = field(default_factory=dict)
    seconds: float = 0.0

    def outcome(self, method: str) -> Outcome | None:
        return next((o for o in self.outcomes if o.method == method), None)

    @property
    def diagnosed(self) -> bool:
        """True when our engine's result carries a status and its counters."""
        return bool(self.engine) and "status" in self.engine

    def as_json(self) -> dict:
        return {"key": self.key, "condition": self.condition, "setup": self.setup,
                "outcomes": [{"method": o.method, "verdict": o.verdict, "detail": o.detail} for o in self.outcomes],
                "engine": self.engine, "engine_behaviour": self.engine_behaviour, "seconds": self.seconds}


def case_functions() -> dict[str, Callable]:
    """key → case function ``f(quick=False, methods=ALL_METHODS) -> StabilityCase``."""
    from . import stability_cases as c
    return {"missed-events": c.missed_events, "zeno": c.zeno, "stiff-superstructure": c.stiff_superstructure,
            "overturning-threshold": c.overturning_threshold, "long-record-drift": c.long_record_drift,
            "coarse-sampling": c.coarse_sampling, "event-location-crash": c.event_location_crash}


def run_stability(quick: bool = False, methods=ALL_METHODS, keys=None,
                  progress: Callable[[str], None] | None = None) -> list[StabilityCase]:
    """Run the stability cases (all, or ``keys``) for ``methods``; quick: fewer tolerances/shorter runs."""
    say = progress or (lambda s: None)
    out = []
    for key, fn in case_functions().items():
        if keys and key not in keys:
            continue
        t0 = time.perf_counter()
        case = fn(quick=quick, methods=tuple(methods))
        case.seconds = time.perf_counter() - t0
        say(f"stability {key}: " + ", ".join(f"{o.method} {o.verdict}" for o in case.outcomes)
            + f" ({case.seconds:.1f} s)")
        out.append(case)
    return out


def write_stability_figures(cases: list[StabilityCase], out_dir: Path) -> dict[str, list[Path]]:
    """Evidence plots (PNG + SVG) of the cases into ``out_dir``; key → written paths."""
    from .figures import save_both
    written = {}
    for case in cases:
        if case.plot is not None:
            written[case.key] = save_both(case.plot(case), Path(out_dir), f"stability_{case.key}")
    return written


_MARK = {"ok": "ok", "degrades": "degrades", "fails": "**fails**", "n/a": "n/a"}


def stability_markdown(cases, figures: dict | None = None, figure_prefix: str = "",
                       machine: dict | None = None) -> str:
    """The stability study as Markdown: summary table, then one section per case with its evidence.

    Args:
        cases: :class:`StabilityCase` objects or their ``as_json()`` dicts (as stored in bench.json).
        figures: key → figure paths (the PNG is linked); default ``stability_<key>.png``.
        figure_prefix: path prefix of the figure links (relative to the Markdown file).
        machine: machine description (date, uname, nproc) printed under the title.
    """
    cases = [c.as_json() if isinstance(c, StabilityCase) else c for c in cases]
    figures = figures or {}
    methods = list(dict.fromkeys(o["method"] for c in cases for o in c["outcomes"]))
    lines = ["# Solver stability study", ""]
    if machine:
        lines += [f"Measured {machine.get('date', '')} on `{machine.get('uname', '')}` "
                  f"({machine.get('cpu', '')}, {machine.get('nproc', '')} cores); scipy "
                  f"{machine.get('scipy', '')}, numba {machine.get('numba', '')}.", ""]
    lines += ["Each row provokes one condition under which numerical methods for rocking fail or degrade, "
              "with a small problem. scipy methods run `solve_ivp` with the same equations and events, "
              "restarted at every impact and record sample (`rockdesign.reference`). Verdicts: **fails** = "
              "wrong answer, crash or hang guard tripped; degrades = right answer but at a much higher cost "
              "or a lower accuracy than the tolerance asks; ok. Generated by `rockdesign bench`.", ""]
    head = "| condition | " + " | ".join(methods) + " | what rockdesign does |"
    lines += [head, "|" + "---|" * (len(methods) + 2)]
    for c in cases:
        verdicts = {o["method"]: o["verdict"] for o in c["outcomes"]}
        cells = [_MARK.get(verdicts[m], verdicts[m]) if m in verdicts else "–" for m in methods]
        summary = c["engine_behaviour"].split(". ")[0].rstrip(".") + "."
        lines.append(f"| {c['condition']} [↓](#{c['key']}) | " + " | ".join(cells) + f" | {summary} |")
    lines.append("")
    for c in cases:
        lines += [f"<a id=\"{c['key']}\"></a>", f"## {c['condition']}", "", f"*Setup.* {c['setup']}", ""]
        for o in c["outcomes"]:
            lines.append(f"- **{o['method']}** — {o['verdict']}: {o['detail']}")
        lines += ["", f"*What rockdesign does.* {c['engine_behaviour']}", "",
                  "*Engine diagnostics.* " + ", ".join(f"{k} = {v}" for k, v in c["engine"].items()), ""]
        paths = figures.get(c["key"])
        png = (next((p for p in paths if str(p).endswith(".png")), paths[0]) if paths
               else f"stability_{c['key']}.png")
        lines += [f"![{c['condition']}]({figure_prefix}{Path(png).name})", ""]
        lines += [f"({c.get('seconds', 0.0):.1f} s)", ""]
    return "\n".join(lines)
