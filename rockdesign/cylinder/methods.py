"""The appendix of the cylinder's calculation report: its method sections (thesis Ch. 5)."""
from __future__ import annotations

from ..report.methods import Method


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
    Method("C3", "First overturning intensities, fragility and collapse margin", (
        "Incremental analysis: each pair, as scaled for the design (factor 1), is analysed on a geometric "
        "grid of factors (consecutive factors at most 1.2 apart) from half the factor at which its resultant "
        "PGA reaches g tan α up to 1 and on to the project's margin_max_scale, until the first factor at "
        "which θ reaches θ_ot; that factor is bisected to margin_precision. Responses are not monotonic in "
        "amplitude (thesis Sec 2.2): a pair safe at the design level may overturn below it, and the first "
        "crossing counts. A pair that does not overturn up to margin_max_scale is censored there.",
        "Fragility: the capacity of pair i is x_i = s_i·PGA_r,i, its first overturning factor times its "
        "design-level resultant PGA max √(ü_gx² + ü_gy²) (the intensity a pair is scaled by, Table 5.4). "
        "Lognormal fit by the method of moments, or by censored maximum likelihood when pairs are censored; "
        "a binomial maximum-likelihood fit to the outcomes at common intensity stripes (Baker 2015, "
        "Earthquake Spectra 31(1)); 90 % percentile bootstrap intervals over pairs.",
        "Collapse margin: an adaptation of FEMA P695 (2009) Ch. 7, written for conventional seismic-force-"
        "resisting systems, with overturning standing for collapse and each pair one ground motion. "
        "CMR = Ŝ_CT/S_MT with S_MT the median design-level resultant PGA and Ŝ_CT counted as FEMA P695 "
        "Ch. 6 (§6.4) defines it: the intensity at which one half of the pairs have overturned (the "
        "⌈n/2⌉-th smallest capacity); the median of the fitted lognormal is reported beside it and does not "
        "decide. SSF = 1 (P695's spectral shape factor needs a period-based ductility that a rigid rocking "
        "body does not have; SSF ≥ 1 in P695, so 1 is conservative); β_TOT = √(β_RTR² + β_DR² + β_TD² + "
        "β_MDL²) rounded to 0.025 with β_RTR = 0.4 and the quality ratings A/B/C/D = 0.10/0.20/0.35/0.50 "
        "(FEMA P695 Tables 3-1, 3-2, 5-3). The margin governs at the risk category's target P(collapse) of "
        "ASCE 7-22 Table 1.3-2: ACMR ≥ exp(−β_TOT Φ⁻¹(x)).",
    )),
)
"""The appendix of the cylinder report."""
