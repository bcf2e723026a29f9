"""The named method sections of the calculation report's appendix, and the citation of them.

A signed calculation cites the thesis, published sources and the tool's own method sections printed
in the report itself — never files of the software's repository.  Texts that the library writes for
results.json (model-selection reasons, check sources, quantity references) name the developer
documentation (``docs/model.md §7``); :func:`cite` rewrites such a reference to the appendix section
that states the same method (``Appendix M4``), so the report is self-contained while results.json
stays as it is.

    cite(text) -> text                 every repository reference replaced by its appendix section
    PLANAR_METHODS, CYLINDER_METHODS   the appendix sections, (key, title, paragraphs)
"""
from __future__ import annotations

import re
from dataclasses import dataclass


@dataclass(frozen=True)
class Method:
    """One appendix section: its label (``M4``), title and paragraphs (plain text with thesis symbols)."""

    label: str
    title: str
    paragraphs: tuple[str, ...]


PLANAR_METHODS = (
    Method("M1", "Equations of motion, impacts, rest and overturning", (
        "All planar systems follow one Lagrangian equation in the tilt θ once the position of the column "
        "top (u_B, w_B) and its first two derivatives with respect to θ are known for the current phase and "
        "rocking side: thesis Eq 4.8 with the sign of its θ̇² term corrected (the thesis's Appendix Eqs "
        "A.5/A.6 have it right), together with the superstructure's Eq 4.9. For a solitary block it reduces "
        "to Housner's Eqs 3.11/3.12, θ̈ = −p²(sin(sα − θ) + (ü_g/g) cos(sα − θ)), s = ±1 the rocking side. "
        "Column kinematics: Eqs 3.1–3.2 (block), 3.35–3.36 (flat extensions), 3.46–3.47 (curved, rolling), "
        "3.51–3.52 (curved, rocking about the edge of the extension).",
        "Linearized equations (first order in α and θ): θ̈ = −p²(sα − θ + ü_g/g) (Eq 3.15); with curved "
        "extensions Eqs 3.59–3.61 with the exact β of Eq 3.44; frames and podia replace p by p̂.",
        "A rigid superstructure is modelled as a frame whose cap beam carries m_B + m_T (γ̂ = γ(1 + η)), not "
        "as a very stiff oscillator, which after impacts does not tend to the rigid result (Eq 4.21 keeps "
        "the top-mass velocity while Eq 4.20 slows θ̇). Before uplift a podium's superstructure is the "
        "fixed-base oscillator of Eq 4.3.",
        "Impacts at θ = 0: θ̇⁺ = √c_r θ̇⁻ and the side flips (Eqs 2.11, 2.15); a podium keeps its "
        "superstructure velocity (Eq 4.21). Phase changes of curved bases at |θ| = β keep θ and θ̇ "
        "continuous.",
        "Rest: after an impact with |θ̇⁺| below the rest velocity (as in the thesis's code) while the ground "
        "acceleration is below the uplift threshold, the body rests; it uplifts again when the threshold "
        "is crossed afresh by 10⁻⁹ g. This ends the infinitely many impacts in finite time of free rocking "
        "with c_r < 1; it changes residual motion, not peaks.",
        "Overturning: dynamic when |θ| reaches π/2; static when the capacity is exceeded, θ_max ≥ θc — "
        "the body may still come back (thesis Sec 2.2), but the limit state is exceeded (thesis Fig 4.9). "
        "The project chooses which one the check counts; both are reported.",
        "Verification of the integrator: between events the linearized single-degree-of-freedom "
        "equations are linear with constant coefficients, so under a ground acceleration linear in time "
        "the response has a closed form (particular solution plus cosh/sinh) and every event is the "
        "root of a closed form. This exact solution is the reference of the solver verification.",
    )),
    Method("M2", "Design quantities and corrections to the printed thesis", (
        "Frequency parameter p = √(g/(R(1 + λ))) (Eq 3.13); frame p̂ (Eq 3.76); podium p̂ (Eq 4.32). "
        "Coefficient of restitution from conservation of angular momentum about the new pivot (Housner): "
        "block Eq 3.14, frame Eq 3.80, podium Eq 4.20; a measured c_r may replace it. Uplift when the ground "
        "acceleration reaches g tan α (Eq 3.34; α' with flat extensions); a podium with an elastic "
        "superstructure uplifts by Eq 4.7. Rotation capacity θc where the static restoring force vanishes "
        "(Eq 3.56 with atan). Equivalent sizes R̂ (Eqs 3.81, 3.89, 3.70–3.71, 3.90) hold to linear order "
        "until the first impact and are reported as design insight, never analysed in place of the model.",
        "Corrections of misprints, each verified against the thesis's own tables or an independent "
        "derivation: Eq 3.56 atan instead of tan (Table 6.5 reproduces only with atan); Eq 3.49 "
        "(r cos θ − R cos(α−θ))/D; Eq 3.39 sin²α' instead of sin²α with flat extensions (impacts about "
        "the extended pivots); Eq 4.8 sign of the θ̇² term; Eqs 4.5–4.6 superstructure shear with the "
        "factor 2 of Eq 4.7; Eq 2.18 θ/α = (a_g/(gα) − 1)(cosh(pt) − 1); Eq 2.12 ΔE = (1 − c_r) T; Eq 3.44 "
        "valid if ρ ≥ ½(tan α' − tan α); Eq 3.54 R sin(α−α') + r sin α' = 0; overturning at |θ| = π/2 as "
        "in the thesis's text (its code B.4 used π/4).",
    )),
    Method("M3", "Displacement capacity with extensions (generalisation of Polyakov's 2B)", (
        "Polyakov's rule 2 (thesis Sec 4.2.5) compares SD_max, the peak of the elastic relative-displacement "
        "spectrum of the ground motion, with 2B, the width of a flat-based block. For columns with "
        "extensions rockdesign replaces 2B by the column-top displacement at the rotation capacity, "
        "u_B(θc) = 2u_C(θc) (Eqs 3.46/3.51 with Eq 3.83): 2B' with flat extensions, the closed form of the "
        "rolling or rocking phase with curved ones. This generalisation is rockdesign's, not Polyakov's or "
        "the thesis's; the report labels it 'capacity u_B(θc)'.",
        "Classes of a record (thesis Fig 4.9), x = SD_max/u_B(θc), y = u_B,max/u_B(θc): a1 both safe, "
        "rule conservative; a2 both safe, rule unconservative; b the analysis overturns while the rule "
        "says safe (false negative); c the rule predicts overturning, the analysis survives; d both "
        "overturn.",
    )),
    Method("M4", "Choosing the analysed model", (
        "No more model than the structure needs, verified with numbers. Superstructure: rigid (the γ̂ "
        "frame of M1) when ω_s/p is at least the project's switch ratio (default 10), else the two-degree-"
        "of-freedom (2DOF) podium. The thesis finds deformability negligible for ω_s/p > 6 (Sec 4.2.4); "
        "measured on its reference podium (tan α = 0.15, γ = 10, η = 5; minimum overturning amplitude under "
        "antisymmetric Ricker pulses relative to rigid): ω_s/p = 30: −1 to −2 %; 6: −3 to −12 %; "
        "3: −19 to −20 %.",
        "Equations: the linearized ones first; they differ from the exact ones by up to 0.05α near "
        "θ_max ≈ 1.5α (thesis Table 3.4: B4 1.545 exact against 1.594 linear). The records with the largest "
        "θ_max/θc are re-analysed with the full model (2DOF where the superstructure is elastic, exact "
        "equations); the simpler model is kept only if no verdict changes and θ_max/θc moves by less than "
        "the linearization tolerance. When the full model is itself chosen there is nothing to compare.",
    )),
    Method("M5", "Integrator, events and tolerances", (
        "Explicit Runge–Kutta pairs with dense output: Dormand–Prince 5(4), and Dormand–Prince 8(5,3) "
        "(DOP853, 7th-order dense output) for the 2DOF podium at rtol < 5·10⁻⁸, where DOP853 needs fewer "
        "function evaluations for the same accuracy (measured work–precision crossover). Steps end on every "
        "record sample (records are linear between samples). Events — uplift, impact, phase change, "
        "overturning, the first exceedance of θc — are located as roots of the dense output, each step "
        "scanned at 8 interior points and split at extrema of θ so that two crossings in one step are not "
        "missed; a terminal event is refined by re-stepping to it and a Newton correction on θ.",
        "Tolerance: a single rocking history after many impacts is chaotic (a 0.03 % change of amplitude "
        "flips single outcomes), so no tolerance makes it exact; the verdict rests on suite statistics. "
        "The default rtol is the loosest at which P(overturn), the median and largest θ_max/θc, the margin "
        "median and the classes of the example projects equal those at rtol = 10⁻¹²; atol = 0.01·rtol.",
        "Early termination (rocking spectra): after the excitation the mechanical energy never increases, "
        "so an analysis stops once θ_max < θc and the energy is below the potential energy at θ_max: "
        "none of θ_max, the overturning flags or the impact count can change any more.",
    )),
    Method("M6", "Fragility, collapse margin and perturbation ensembles", (
        "Fragility: from the incremental analysis, record i overturns first at the factor s_i on its "
        "design-level record; with IM_i its intensity there, the capacity is x_i = s_i·IM_i (later "
        "safe-again bands do not raise it). Lognormal fit by the method of moments, or by censored maximum "
        "likelihood when records do not overturn up to the scan limit; a binomial maximum-likelihood fit "
        "to the outcomes at common intensity stripes (Baker 2015, Earthquake Spectra 31(1)); 90 % "
        "percentile bootstrap intervals over records.",
        "Collapse margin: an adaptation of FEMA P695 (2009) Ch. 7, written for conventional seismic-force-"
        "resisting systems, with overturning standing for collapse. CMR = median overturning intensity over "
        "the design intensity; SSF = 1 (P695's spectral shape factor needs a period-based ductility that a "
        "rigid rocking body does not have; SSF ≥ 1 in P695, so 1 is conservative); β_TOT = √(β_RTR² + β_DR² "
        "+ β_TD² + β_MDL²) rounded to 0.025 with β_RTR = 0.4 and the quality ratings A/B/C/D = "
        "0.10/0.20/0.35/0.50 (FEMA P695 Tables 3-1, 3-2, 5-3; rating B, 'good', unless the project gives "
        "others).",
        "Perturbation ensembles: every record is re-analysed several times at the design level with "
        "amplitude × U(1 ± 0.1 %), c_r × U(1 ± 2 %) and both integrator tolerances × 0.1 (seeded). A record "
        "whose runs disagree with each other or with the nominal analysis has an outcome that is not "
        "robust (thesis Ch. 7). The verdict uses the nominal fraction with its exact Clopper–Pearson "
        "bound: records are independent binomial trials, runs of one record are not.",
    )),
    Method("M7", "Default excitation", (
        "A project that gives only a design PGA is analysed with the FEMA P695 far-field suite (FEMA 2009, "
        "Appendix A; 44 horizontal components), every record scaled to that PGA. The report lists the "
        "records, their scale factors and processing.",
    )),
)
"""The appendix of the planar report."""

CYLINDER_METHODS = (
    Method("C1", "Equations of the rocking and wobbling cylinder", (
        "A solid rigid cylinder tilts by θ ≥ 0 toward the azimuth φ about a point of its base rim, does not "
        "slide and stays above its footprint (thesis Ch. 5). Tilt: Eq 5.22 as printed, M θ̈ + φ̇² X(θ) = "
        "−(g/R) sin(α−θ) − cos(α−θ)(ü_gx cos φ + ü_gy sin φ)/R with M = (15 + cos²α)/12 and the "
        "centrifugal coefficient X(θ) = sin θ cos θ (5/4 sin²α − 4/3 cos²α) − 3/2 sin θ sin²α + "
        "cos α sin α (cos²θ − sin²θ − cos θ). Azimuth: Eq 5.23 with the coefficient J = (16 + 5 sin²α)/12 · "
        "sin²θ + (1 − cos θ)(sin 2α sin θ − 3 sin²α cos θ): the thesis prints (4 + sin²α)/3 for the first "
        "coefficient; its own Eq 5.19 and an independent Lagrangian give (16 + 5 sin²α)/12.",
        "Damped model: the spring–dashpot contact of Eqs 5.36–5.37 (ω_n, ζ); contact force "
        "N/(mg) = 1 − (ω_n² w_T + 2ζω_n ẇ_T)/g with w_T the upward displacement of the contact point. Rigid "
        "contact: N/(mg) = 1 + R(sin(α−θ) θ̈ − cos(α−θ) θ̇²)/g.",
        "Quasi-impacts: a spinning cylinder does not pass through θ = 0; the contact point sweeps round "
        "the rim while θ is small (Sec 5.4.1). The azimuth rate there scales like the angular momentum "
        "about the vertical divided by sin²θ, so φ̇ becomes very large (without bound as θ → 0) although "
        "the cylinder barely moves: it is the speed of the contact point round the rim, not a rotation "
        "of the body that does work. The step control resolves it without any restitution law; the "
        "azimuth turned is Δφ of Eq 5.38. The report therefore shows φ̇ only where θ exceeds a stated "
        "threshold, and the path of the centre of mass in plan.",
        "Verification: an independent Lagrangian written from the kinematics of Eqs 5.11 and 5.17, "
        "integrated by a general-purpose DOP853 solver, agrees with the engine within 10⁻⁷ rad on a FEMA "
        "P695 pair for both models; steady wobbling from θ = 0.1 rad stays at θ = 0.1 within 10⁻¹² rad for "
        "three periods; a pulse along one azimuth reproduces the planar engine on a block of the "
        "cylinder's inertia.",
    )),
    Method("C2", "Integrator, uplift, quasi-impacts, rest and the free-vibration window", (
        "DOP853 (8th-order Runge–Kutta with 5th/3rd-order error estimators and 7th-order dense output). "
        "Steps end on every record sample (records are linear between samples) and at the end of the "
        "excitation. Uplift (Eq 5.24) when the resultant ground acceleration reaches g tan α, found exactly "
        "on each linear record segment; the cylinder starts at θ = 10⁻⁷ rad toward the inertia force (the "
        "result does not depend on this seed: 10⁻⁷ and 10⁻⁹ rad give the same response).",
        "Quasi-impacts are resolved by the step control, never skipped; a minimum of θ below 1 % of α counts "
        "as a quasi-impact. Overturning: θ reaching θ_ot (located on the dense output). A one-directional "
        "excitation without spin stays planar (Housner's planar cylinder, Eq 5.26).",
        "Rest rule of the damped model: at a quasi-impact whose rocking energy is at most that of a tilt rate "
        "equal to the rest velocity, while the resultant ground acceleration is below g tan α, the cylinder "
        "rests until the next uplift. The undamped model conserves energy and never comes back to rest: "
        "after the record it keeps the energy it has at the record's end and may still overturn.",
        "Free-vibration window: every pair is analysed for the project's free vibration after the record "
        "(default 10 s, the time within which near-threshold rocking bodies still overturn after the "
        "excitation, thesis Sec 2.2). Overturning is irreversible, so a longer window can only add "
        "overturning pairs: for the undamped model the reported P(overturn) is that of the record and this "
        "window, a lower bound of the value over unlimited time; the damped model dissipates energy at "
        "every quasi-impact and comes to rest or to steady wobbling.",
    )),
)
"""The appendix of the cylinder report."""

_SECTION = {"2": "M1", "3": "M2", "4": "M1", "5": "M1", "6": "M3", "7": "M4", "8": "M4", "9": "M2"}
"""Section of the developer model description → appendix section of the report."""

_REFERENCES = (
    (re.compile(r"\(ours, docs/model\.md §6\)"), "(rockdesign's, Appendix M3)"),
    (re.compile(r"rockdesign's docs/model\.md §(\d)"), lambda m: f"Appendix {_SECTION.get(m.group(1), 'M1')}"),
    (re.compile(r"docs/model\.md\s*§(\d)(?:,\s*§(\d))?"),
     lambda m: f"Appendix {_SECTION.get(m.group(1), 'M1')}"),
    (re.compile(r"docs/model\.md(?:, \"[^\"]*\")?"), "Appendix M1"),
    (re.compile(r"docs/engine\.md(?:, \"[^\"]*\")?(?: \(engine statuses\))?"), "Appendix M5"),
    (re.compile(r"docs/tolerances\.md"), "Appendix M5"),
    (re.compile(r"docs/early_termination\.md"), "Appendix M5"),
    (re.compile(r"docs/fragility\.md(?: \(perturbation ensembles\))?"), "Appendix M6"),
    (re.compile(r"docs/project-file\.md"), "Appendix M7"),
    (re.compile(r"docs/cylinder\.md"), "Appendix C1–C2"),
    (re.compile(r"tests/golden"), "the pinned reference outputs of the test suite"),
)


def cite(text):
    """``text`` with every reference to a file of the repository replaced by the appendix section that
    states the same method; other text unchanged (None → None)."""
    if not text:
        return text
    out = str(text)
    for pattern, replacement in _REFERENCES:
        out = pattern.sub(replacement, out)
    return out
