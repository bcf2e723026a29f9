"""The layout of the engine's arrays: event kinds, status codes, options, summary and diagnostics.

The kernels exchange plain float arrays (numba-friendly); these named positions are the only way the
rest of the package reads or writes them (the physical parameters ``sp`` are laid out in
:mod:`rockdesign.planar.dynamics.eom`, the excitation in :mod:`rockdesign.motions.excitation`).
"""
from __future__ import annotations

# event kinds
EV_UPLIFT = 1
EV_IMPACT = 2
EV_PHASE_ROCKING = 3   # |θ| rises through β: rolling → rocking about the extension edge
EV_PHASE_ROLLING = 4   # |θ| falls through β
EV_REST = 5
EV_OVERTURN = 6        # dynamic: |θ| reaches π/2
EV_EXCEEDED = 7        # static: |θ| reaches θc for the first time
EVENT_NAMES = {EV_UPLIFT: "uplift", EV_IMPACT: "impact", EV_PHASE_ROCKING: "phase-rocking",
               EV_PHASE_ROLLING: "phase-rolling", EV_REST: "rest", EV_OVERTURN: "overturn",
               EV_EXCEEDED: "capacity-exceeded"}

# status codes
ST_OK = 0
ST_OVERTURNED = 1
ST_STEP_COLLAPSE = 2
ST_TOO_MANY_STEPS = 3
ST_ENERGY_BOUND = 4    # stopped early: the remaining energy cannot change θ_max or the verdict
ST_STOPPED_EXCEEDED = 5
ST_TOO_MANY_EVENTS = 6
STATUS_NAMES = {ST_OK: "completed", ST_OVERTURNED: "overturned (|θ| = π/2)",
                ST_STEP_COLLAPSE: "step size collapsed", ST_TOO_MANY_STEPS: "step limit reached",
                ST_ENERGY_BOUND: "stopped: energy bound reached", ST_STOPPED_EXCEEDED: "stopped at θc",
                ST_TOO_MANY_EVENTS: "event limit reached"}

COMPLETED_STATUSES = (ST_OK, ST_OVERTURNED, ST_ENERGY_BOUND, ST_STOPPED_EXCEEDED)
"""Statuses of an analysis that ran to a conclusion; the others (step size collapsed, step or event
limit reached) mean it failed, and its result must not be used (docs/engine.md)."""

# options array
O_T_END = 0
O_RTOL = 1
O_ATOL = 2
O_H_MAX = 3
O_MAX_STEPS = 4
O_ENERGY_STOP = 5
O_STOP_EXCEEDED = 6
O_SCAN = 7
O_MAX_EVENTS = 8
O_METHOD = 9           # METHOD_* (0: chosen per system by the work-precision data)
N_OPTIONS = 10

# steppers
METHOD_AUTO = 0        # DOP853 for the 2DOF podium at rtol < DOP853_BELOW_RTOL, DP5(4) otherwise
METHOD_DP5 = 5         # Dormand–Prince 5(4), 4th-order dense output
METHOD_DOP853 = 8      # Dormand–Prince 8(5,3), 7th-order dense output
METHOD_NAMES = {METHOD_AUTO: "auto", METHOD_DP5: "dp5", METHOD_DOP853: "dop853"}
DOP853_BELOW_RTOL = 5e-8
"""The automatic choice uses DOP853 for a 2DOF podium when rtol is below this: the work-precision crossover
measured on the podium under a 30-s record (benchmarks/bench_engine.py, ``stepper_choice``).  Both methods
then land on every record sample; DP5(4) needs ≈ 1.4–1.7 steps per sample at rtol 1e-6…1e-7 (cheaper), 2.6
at 1e-8 and 5.3 at 1e-10, where DOP853 takes 1.07 steps per sample (and is 40× to 3000× more accurate).
SDOF systems take about one DP5(4) step per sample down to rtol 1e-10: DP5(4) is cheaper there (equal at 1e-12)."""

# summary array
S_THETA_MAX = 0
S_T_THETA_MAX = 1
S_UB_MAX = 2
S_IMPACTS = 3
S_T_UPLIFT = 4
S_EXCEEDED = 5
S_T_EXCEEDED = 6
S_DYNAMIC = 7
S_T_OVERTURN = 8
S_IMPACTS_BEFORE_OVERTURN = 9
S_DRIFT_MAX = 10
S_T_END = 11
S_UPLIFTS = 12
S_IMPACTS_BEFORE_EXCEEDED = 13
S_UPLIFT_TIME = 14     # total time spent uplifted [s]
S_FS_MAX = 15          # 2DOF podium: peak |f_s| = peak absolute acceleration of the superstructure [m/s²] (SPEC §13)
S_T_FS_MAX = 16        # its time [s]
S_CAP_ACC_MAX = 17     # rigid masses (frame, rigid superstructure): peak |absolute acceleration| of the cap beam
                       # while rocking, between impacts [m/s²] (SPEC §13)
S_CAP_DV_MAX = 18      # rigid masses: largest jump |Δu̇_B| of the cap beam's velocity at an impact [m/s]
N_SUMMARY = 19

# diagnostics array
D_STEPS = 0
D_REJECTED = 1
D_NFEV = 2
D_EVENTS = 3
D_REST = 4
D_STATUS = 5
D_REFINE = 6
D_EVENTS_STORED = 7
N_DIAG = 8
