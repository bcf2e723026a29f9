"""A kind of structure that lives outside rockdesign: Newmark's rigid block sliding on a rigid-plastic
interface (Newmark 1965, "Effects of earthquakes on dams and embankments", Géotechnique 15(2)).

It exists to prove the registry (docs/architecture.md, "Adding a kind of structure"): this package is
registered from a test with :func:`rockdesign.kinds.register` — no file of ``rockdesign/`` names it — and
``rockdesign check`` runs it through the library's front door to results.json and a PDF report, judged by
the shared acceptance (ASCE 7-22 §16.4.1.1 count per ground motion) and rendered by the shared report layer.

Physics (per unit mass, one direction of sliding allowed both ways): the block sticks while
|ü_g| ≤ a_c = μ g; while it slides, the relative velocity v obeys v̇ = −ü_g − sign(v) a_c until v returns
to zero.  Integrated exactly for a record that is linear between samples (v is piecewise quadratic), with
the stop found as the root of that quadratic.  Unacceptable response: a sliding displacement over the
allowance.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockdesign.acceptance.criteria import AnalysesCompleted, decide, evaluate_criteria
from rockdesign.acceptance.criterion_base import CheckContext
from rockdesign.acceptance.overturning_criteria import UnacceptableResponses
from rockdesign.acceptance.rule import ground_motion_table
from rockdesign.errors import ProjectError, RockdesignError
from rockdesign.kinds.base import StructureKind
from rockdesign.motions.grouping import ground_motion_id
from rockdesign.motions.library import load_record
from rockdesign.motions.motion import GroundMotion
from rockdesign.motions.suites import load_suite
from rockdesign.project_tables import Project, TableReader, parse_analysis, project_info
from rockdesign.quantity import Quantity
from rockdesign.report.document import ReportParts
from rockdesign.report.render import stylesheet, svg_image
from rockdesign.report.svg import svg


@dataclass(frozen=True)
class Block:
    """The sliding block in SI: friction coefficient μ [-], allowed sliding [m], gravity [m/s²]."""

    kind = "sliding_block"
    friction: float
    allowed: float
    g: float
    design_pga: float

    @property
    def critical_acceleration(self) -> float:
        return self.friction * self.g


def sliding_displacement(accel: np.ndarray, dt: float, a_c: float) -> tuple[float, np.ndarray]:
    """(peak |u| [m], u at the samples [m]) of Newmark's rigid-plastic block under ``accel`` [m/s²] sampled
    every ``dt`` [s] and linear between samples, sliding both ways at |ü_g| > ``a_c`` [m/s²]."""
    u = v = 0.0
    out = np.zeros(len(accel))
    peak = 0.0
    for i in range(len(accel) - 1):
        a0, a1 = float(accel[i]), float(accel[i + 1])
        t, slope = 0.0, (a1 - a0) / dt
        while t < dt:
            ag = a0 + slope * t
            if v == 0.0:
                # stuck: slides once |ü_g| exceeds a_c within the rest of the segment
                if abs(ag) <= a_c:
                    ends = [(s * a_c - a0) / slope for s in (1.0, -1.0) if slope != 0.0]
                    starts = [x for x in ends if t < x < dt and abs(a0 + slope * (x + 1e-12 * dt)) > a_c]
                    if not starts:
                        break
                    t = min(starts)
                    continue
                direction = -math.copysign(1.0, ag)      # the block slides against the ground's acceleration
            else:
                direction = math.copysign(1.0, v)
            # v̇ = −(a0 + slope τ) − direction a_c: v(τ) = v + c1 τ + c2 τ² with τ from t
            c1, c2 = -(ag + direction * a_c), -0.5 * slope
            roots = sorted(x for x in _roots(c2, c1, v) if x > 1e-15)
            stop = roots[0] if roots and t + roots[0] < dt else None
            tau = stop if stop is not None else dt - t
            u += v * tau + 0.5 * c1 * tau ** 2 + c2 * tau ** 3 / 3.0
            v = 0.0 if stop is not None else v + c1 * tau + c2 * tau ** 2
            peak = max(peak, abs(u))
            t += tau
        out[i + 1] = u
    return peak, out


def _roots(a: float, b: float, c: float) -> list[float]:
    """Real roots of a x² + b x + c."""
    if abs(a) < 1e-300:
        return [] if b == 0.0 else [-c / b]
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return []
    r = math.sqrt(disc)
    return [(-b - r) / (2.0 * a), (-b + r) / (2.0 * a)]


@dataclass(frozen=True)
class Run:
    """One analysis in the terms the shared criteria read."""

    displacement: float
    allowed: float
    failed: bool = False
    status: str = "completed"

    @property
    def overturned(self) -> bool:          # the unacceptable response of this kind
        return self.displacement > self.allowed

    @property
    def response_ratio(self) -> float:      # the peak response over the capacity (rockdesign.acceptance.outcome.Run)
        return self.displacement / self.allowed


@dataclass(frozen=True)
class Outcome:
    id: str
    ground_motion: str
    run: Run


@dataclass
class SlidingCheck:
    project: Project
    records: list
    checks: list
    verdict: str
    verdict_reason: str
    allowed_unacceptable: int = 1

    def as_json(self) -> dict:
        return {"project": {"name": self.project.name}, "verdict": self.verdict,
                "verdict_reason": self.verdict_reason,
                "records": [{"id": o.id, "ground_motion": o.ground_motion,
                             "displacement_max": o.run.displacement, "unacceptable": o.run.overturned}
                            for o in self.records],
                "checks": [c.as_json() for c in self.checks], "failed_records": []}


@dataclass(frozen=True)
class Excitation:
    suite: str              # the record suite, scaled to the block's design_pga


@dataclass(frozen=True)
class Request:
    project: Project
    motion: GroundMotion
    text: str


@dataclass(frozen=True)
class Simulation:
    project: Project
    motion_text: str
    t: np.ndarray
    u: np.ndarray
    displacement_max: float
    failed: bool = False
    warnings: tuple = ()

    def as_json(self) -> dict:
        return {"motion": self.motion_text, "displacement_max": self.displacement_max}

    def write_csv(self, path) -> None:
        np.savetxt(path, np.column_stack([self.t, self.u]), delimiter=",", header="t_s,u_m", comments="")

    def write_figure(self, path) -> None:
        raise RockdesignError("no figure", key="plot", expected="--csv", found=str(path))

    def summary_rows(self):
        return [("max sliding |u|", f"{self.displacement_max:.6g}", "m")]


class SlidingBlock(StructureKind):
    """Newmark's sliding block: ``[sliding_block] friction, allowed_displacement, design_pga``."""

    name = "sliding_block"
    systems = ("sliding_block",)

    def claims(self, raw):
        return "sliding_block" in raw

    def parse(self, raw, *, file, text):
        analysis = parse_analysis(raw.get("analysis", {}), file)
        info = project_info(raw, file, analysis.g, example="dam block")
        unknown = set(raw) - {"project", "analysis", "sliding_block", "excitation"}
        if unknown:
            raise ProjectError("unknown table", file=file, key=sorted(unknown)[0], expected="[sliding_block]",
                               found=sorted(unknown)[0])
        t = TableReader(raw["sliding_block"], "sliding_block", ("friction", "allowed_displacement", "design_pga"),
                        file, analysis.g)
        block = Block(friction=t.number("friction", low=0.0, high=2.0, default=None) if t.has("friction") else
                      _missing(file, "friction"),
                      allowed=t.quantity("allowed_displacement", "length", required=True),
                      g=analysis.g, design_pga=t.quantity("design_pga", "acceleration", required=True))
        suite = TableReader(raw.get("excitation", {}), "excitation", ("suite",), file, analysis.g)
        excitation = Excitation(suite.choice("suite", ("p695-farfield", "p695-nearfield"), "p695-farfield"))
        return Project(path=file, name=info["name"], system=block, analysis=analysis, info=info, raw=raw,
                       source_text=text, excitation_raw=raw.get("excitation"), excitation=excitation)

    def quantities(self, project):
        b = project.system
        return {"critical_acceleration": Quantity(
            "critical_acceleration", "a_c", "acceleration at which the block starts to slide",
            b.critical_acceleration, "m/s^2", "Newmark (1965) Eq 1", "a_c = μ g",
            f"{b.friction:g} · {b.g:g} m/s²")}

    def simulation_request(self, project, motion, *, model, t_end, rtol, records_dir):
        if isinstance(motion, GroundMotion):
            return Request(project, motion, motion.name)
        if not (isinstance(motion, str) and motion.startswith("record:")):
            raise RockdesignError("unknown motion", key="motion", expected="record:ID", found=repr(motion))
        return Request(project, load_record(motion.split(":", 1)[1], gravity=project.system.g), motion)

    def run_simulation(self, request):
        project, motion, text = request.project, request.motion, request.text
        accel = motion.samples * motion.scale
        peak, u = sliding_displacement(accel, motion.dt, project.system.critical_acceleration)
        return Simulation(project, text, motion.dt * np.arange(len(u)), u, peak)

    def check(self, project, *, progress, records_dir, margins, executor):
        return self.grid_check(project, records=self.grid_records(project, records_dir), records_dir=records_dir,
                               executor=executor, progress=progress)

    # --- the design grid (rockdesign design): what a kind adds to be charted, nothing of another kind's ----------
    design_columns = (("critical_acceleration", "a_c", "m/s^2"),)
    design_response = ("u_max/u_allowed", "the peak sliding displacement over the allowed displacement")
    design_material = ("material", "a block carries no superstructure")
    design_draws = "the amplitude × (1 ± 0.1 %)"

    def grid_records_key(self, project):
        return project.excitation.suite

    def grid_records(self, project, records_dir):
        return load_suite(project.excitation.suite, gravity=project.system.g).records

    def grid_check(self, project, *, records, records_dir, executor, progress, amplitude=1.0):
        b = project.system
        outcomes = []
        for rid, motion, meta in records:
            accel = motion.samples * (amplitude * b.design_pga / float(np.max(np.abs(motion.samples))))
            peak, _ = sliding_displacement(accel, motion.dt, b.critical_acceleration)
            outcomes.append(Outcome(rid, ground_motion_id(rid, meta), Run(peak, b.allowed)))
        if executor is not None:
            executor.count(len(outcomes))      # the executor protocol: the analyses it ran
        ctx = CheckContext(outcomes, project.analysis, margins_run=False)
        items, skipped = evaluate_criteria(ctx, [AnalysesCompleted, UnacceptableResponses])
        verdict = decide(items, skipped, rule=ctx.rule)
        return SlidingCheck(project, outcomes, items, verdict.verdict, verdict.reason, ctx.rule.allowed)

    def grid_cell(self, result, analyses):
        rows = ground_motion_table(result.records)
        ratios = sorted(o.run.response_ratio for o in result.records)
        return {"verdict": result.verdict, "reason": result.verdict_reason, "governing": None,
                "decided_at_design_level": True, "acmr": None, "acmr_required": None, "p_collapse_design": None,
                "target_p_collapse": None, "n_unacceptable": sum(r["unacceptable"] for r in rows),
                "allowed_unacceptable": result.allowed_unacceptable, "n_ground_motions": len(rows),
                "n_failed_analyses": 0, "superstructure_shear_p84": None, "superstructure_drift_p84": None,
                "median_theta_max_over_theta_c": float(np.median(ratios)),
                "critical_acceleration": result.project.system.critical_acceleration,
                "material": None, "demand": None, "model": "newmark-rigid-plastic",
                "analyses": analyses, "analyses_saved": 0}

    def grid_draws(self, result, *, records, executor):
        """The amplitude × (1 ± 0.1 %) (SPEC §15's amplitude draw), stopping at the first that fails."""
        for n, amplitude in enumerate((0.999, 1.001), start=1):
            again = self.grid_check(result.project, records=records, records_dir=None, executor=executor,
                                    progress=None, amplitude=amplitude)
            if again.verdict != "PASS":
                return {"n": n, "failed": 1, "size": 2, "first_failure": f"amplitude × {amplitude}",
                        "what": "the amplitude × (1 ± 0.1 %)"}
        return {"n": 2, "failed": 0, "size": 2, "first_failure": None, "what": "the amplitude × (1 ± 0.1 %)"}

    def report(self, result):
        from rockdesign import mplfig as plt
        fig, ax = plt.subplots(figsize=(5, 3))
        ax.plot([o.run.displacement * 1e3 for o in result.records], "o")
        ax.axhline(result.project.system.allowed * 1e3, color="k")
        ax.set_xlabel("record")
        ax.set_ylabel("sliding [mm]")
        fig.set_layout_engine("tight")
        figure = svg(fig, "sliding", crop=False)
        return ReportParts(html=lambda: (
            f"<html><head><style>{stylesheet()}</style></head><body><h1>Sliding block — {result.project.name}</h1>"
            f"<p>Verdict: {result.verdict} — {result.verdict_reason}</p>{svg_image(figure)}</body></html>"))


def _missing(file, key):
    raise ProjectError("missing required value", file=file, key=f"sliding_block.{key}", expected="a number",
                       found="none")
