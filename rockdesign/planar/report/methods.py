"""The named method sections of the calculation report's appendix, and the citation of them.

The planar kind's sections (columns, frames, podiums); the :class:`~rockdesign.report.methods.Method`
type and :func:`~rockdesign.report.methods.cite` are shared by every kind.  A signed calculation cites the thesis, published sources and the tool's own method sections printed
in the report itself — never files of the software's repository.  Texts that the library writes for
results.json (model-selection reasons, check sources, quantity references) name the developer
documentation (``docs/model.md §7``); :func:`cite` rewrites such a reference to the appendix section
that states the same method (``Appendix M4``), so the report is self-contained while results.json
stays as it is.

    PLANAR_METHODS   the appendix sections, (key, title, paragraphs)
"""
from __future__ import annotations

from ...report.methods import Method


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
        "resisting systems, with overturning standing for collapse. CMR = Ŝ_CT/S_MT, the median overturning "
        "intensity over the design intensity, with Ŝ_CT counted as FEMA P695 Ch. 6 (§6.4) defines it: the "
        "intensity at which one half of the records have overturned (the ⌈n/2⌉-th smallest capacity; with "
        "more than half of them censored it is not defined and only bounded below); the median of the "
        "fitted lognormal is reported beside it and does not decide. SSF = 1 (P695's spectral shape factor needs a period-based ductility that a "
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


