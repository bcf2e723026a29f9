"""Dormand–Prince 8(5,3) (Hairer's DOP853) with its 7th-order dense output, as small numba kernels.

The second stepper of the engine, beside DP5(4) (:mod:`rockdesign.planar.dynamics.rk`): where steps are
bound by the tolerance rather than by the record samples (the 2DOF podium, whose uplifted
superstructure makes DP5(4) take ≈ 8 steps per sample at rtol 1e-10), an 8th-order step covers a
sample in one or two steps.  Which system uses which method is decided by the work-precision data
(``benchmarks/bench_engine.py``; :func:`rockdesign.planar.dynamics.model.default_method`).

Written by hand (not scipy's ``DOP853`` class) because the event-driven integrator needs one step,
one error norm and one dense output as allocation-free kernels it can call from its own loop.  The
coefficients are the published ones, written out below from Hairer & Wanner's Fortran ``dop853.f`` (the
``parameter`` block of its core integrator ``DP86CO``; E. Hairer, S. P. Nørsett, G. Wanner, *Solving
Ordinary Differential Equations I*, 2nd ed., Springer 1993, Sec. II.5–II.6; code at
http://www.unige.ch/~hairer/software.html) — the same decimal literals scipy's ``solve_ivp(method="DOP853")``
uses, so the doubles are the same to the bit.  The step, the combined 5th/3rd-order error norm and the
dense output follow ``dop853.f`` (and scipy's ``DOP853``, which transcribes it).

The dense output is returned in the engine's common monomial form
``y(t + x h) = y + h Σ_{k=1..7} Q[:, k−1] x^k`` (x ∈ [0, 1]), so event location
(:mod:`rockdesign.planar.dynamics.events`) evaluates the 4th-order DP5 and the 7th-order DOP853 interpolants
with the same code.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .eom import rhs

N_STAGES = 12                   # stages of the 8th-order step; stage 13 (row 12) is f(t + h, y_new) (FSAL)
N_STAGES_EXTENDED = 16          # + 3 stages (14–16) for the dense output

# dop853.f's coefficients under its own names (stage numbers 1–16 there, rows/columns 0–15 here):
# c_i the stage times, a_ij the tableau, b_j the 8th-order weights (= a_13,j, the FSAL stage), bhh_k the
# weights of the 3rd-order estimate, er_j the 5th-order error estimate, d_ij the dense output's last four
# coefficient rows (dop853.f's d4j … d7j).
_C = {2: 0.526001519587677318785587544488e-01, 3: 0.789002279381515978178381316732e-01,
      4: 0.118350341907227396726757197510e+00, 5: 0.281649658092772603273242802490e+00,
      6: 0.333333333333333333333333333333e+00, 7: 0.25e+00, 8: 0.307692307692307692307692307692e+00,
      9: 0.651282051282051282051282051282e+00, 10: 0.6e+00, 11: 0.857142857142857142857142857142e+00,
      12: 1.0, 13: 1.0,       # stages 12 and 13 are evaluated at t + h
      14: 0.1e+00, 15: 0.2e+00, 16: 0.777777777777777777777777777778e+00}
_A = {
    2: {1: 5.26001519587677318785587544488e-2},
    3: {1: 1.97250569845378994544595329183e-2, 2: 5.91751709536136983633785987549e-2},
    4: {1: 2.95875854768068491816892993775e-2, 3: 8.87627564304205475450678981324e-2},
    5: {1: 2.41365134159266685502369798665e-1, 3: -8.84549479328286085344864962717e-1,
        4: 9.24834003261792003115737966543e-1},
    6: {1: 3.7037037037037037037037037037e-2, 4: 1.70828608729473871279604482173e-1,
        5: 1.25467687566822425016691814123e-1},
    7: {1: 3.7109375e-2, 4: 1.70252211019544039314978060272e-1, 5: 6.02165389804559606850219397283e-2,
        6: -1.7578125e-2},
    8: {1: 3.70920001185047927108779319836e-2, 4: 1.70383925712239993810214054705e-1,
        5: 1.07262030446373284651809199168e-1, 6: -1.53194377486244017527936158236e-2,
        7: 8.27378916381402288758473766002e-3},
    9: {1: 6.24110958716075717114429577812e-1, 4: -3.36089262944694129406857109825e0,
        5: -8.68219346841726006818189891453e-1, 6: 2.75920996994467083049415600797e1,
        7: 2.01540675504778934086186788979e1, 8: -4.34898841810699588477366255144e1},
    10: {1: 4.77662536438264365890433908527e-1, 4: -2.48811461997166764192642586468e0,
         5: -5.90290826836842996371446475743e-1, 6: 2.12300514481811942347288949897e1,
         7: 1.52792336328824235832596922938e1, 8: -3.32882109689848629194453265587e1,
         9: -2.03312017085086261358222928593e-2},
    11: {1: -9.3714243008598732571704021658e-1, 4: 5.18637242884406370830023853209e0,
         5: 1.09143734899672957818500254654e0, 6: -8.14978701074692612513997267357e0,
         7: -1.85200656599969598641566180701e1, 8: 2.27394870993505042818970056734e1,
         9: 2.49360555267965238987089396762e0, 10: -3.0467644718982195003823669022e0},
    12: {1: 2.27331014751653820792359768449e0, 4: -1.05344954667372501984066689879e1,
         5: -2.00087205822486249909675718444e0, 6: -1.79589318631187989172765950534e1,
         7: 2.79488845294199600508499808837e1, 8: -2.85899827713502369474065508674e0,
         9: -8.87285693353062954433549289258e0, 10: 1.23605671757943030647266201528e1,
         11: 6.43392746015763530355970484046e-1},
    13: {1: 5.42937341165687622380535766363e-2, 6: 4.45031289275240888144113950566e0,      # b_j
         7: 1.89151789931450038304281599044e0, 8: -5.8012039600105847814672114227e0,
         9: 3.1116436695781989440891606237e-1, 10: -1.52160949662516078556178806805e-1,
         11: 2.01365400804030348374776537501e-1, 12: 4.47106157277725905176885569043e-2},
    14: {1: 5.61675022830479523392909219681e-2, 7: 2.53500210216624811088794765333e-1,
         8: -2.46239037470802489917441475441e-1, 9: -1.24191423263816360469010140626e-1,
         10: 1.5329179827876569731206322685e-1, 11: 8.20105229563468988491666602057e-3,
         12: 7.56789766054569976138603589584e-3, 13: -8.298e-3},
    15: {1: 3.18346481635021405060768473261e-2, 6: 2.83009096723667755288322961402e-2,
         7: 5.35419883074385676223797384372e-2, 8: -5.49237485713909884646569340306e-2,
         11: -1.08347328697249322858509316994e-4, 12: 3.82571090835658412954920192323e-4,
         13: -3.40465008687404560802977114492e-4, 14: 1.41312443674632500278074618366e-1},
    16: {1: -4.28896301583791923408573538692e-1, 6: -4.69762141536116384314449447206e0,
         7: 7.68342119606259904184240953878e0, 8: 4.06898981839711007970213554331e0,
         9: 3.56727187455281109270669543021e-1, 13: -1.39902416515901462129418009734e-3,
         14: 2.9475147891527723389556272149e0, 15: -9.15095847217987001081870187138e0},
}
_BHH = {1: 0.244094488188976377952755905512e+00, 9: 0.733846688281611857341361741547e+00,
        12: 0.220588235294117647058823529412e-01}
_ER = {1: 0.1312004499419488073250102996e-01, 6: -0.1225156446376204440720569753e+01,
       7: -0.4957589496572501915214079952e+00, 8: 0.1664377182454986536961530415e+01,
       9: -0.3503288487499736816886487290e+00, 10: 0.3341791187130174790297318841e+00,
       11: 0.8192320648511571246570742613e-01, 12: -0.2235530786388629525884427845e-01}
_D = {
    4: {1: -0.84289382761090128651353491142e+01, 6: 0.56671495351937776962531783590e+00,
        7: -0.30689499459498916912797304727e+01, 8: 0.23846676565120698287728149680e+01,
        9: 0.21170345824450282767155149946e+01, 10: -0.87139158377797299206789907490e+00,
        11: 0.22404374302607882758541771650e+01, 12: 0.63157877876946881815570249290e+00,
        13: -0.88990336451333310820698117400e-01, 14: 0.18148505520854727256656404962e+02,
        15: -0.91946323924783554000451984436e+01, 16: -0.44360363875948939664310572000e+01},
    5: {1: 0.10427508642579134603413151009e+02, 6: 0.24228349177525818288430175319e+03,
        7: 0.16520045171727028198505394887e+03, 8: -0.37454675472269020279518312152e+03,
        9: -0.22113666853125306036270938578e+02, 10: 0.77334326684722638389603898808e+01,
        11: -0.30674084731089398182061213626e+02, 12: -0.93321305264302278729567221706e+01,
        13: 0.15697238121770843886131091075e+02, 14: -0.31139403219565177677282850411e+02,
        15: -0.93529243588444783865713862664e+01, 16: 0.35816841486394083752465898540e+02},
    6: {1: 0.19985053242002433820987653617e+02, 6: -0.38703730874935176555105901742e+03,
        7: -0.18917813819516756882830838328e+03, 8: 0.52780815920542364900561016686e+03,
        9: -0.11573902539959630126141871134e+02, 10: 0.68812326946963000169666922661e+01,
        11: -0.10006050966910838403183860980e+01, 12: 0.77771377980534432092869265740e+00,
        13: -0.27782057523535084065932004339e+01, 14: -0.60196695231264120758267380846e+02,
        15: 0.84320405506677161018159903784e+02, 16: 0.11992291136182789328035130030e+02},
    7: {1: -0.25693933462703749003312586129e+02, 6: -0.15418974869023643374053993627e+03,
        7: -0.23152937917604549567536039109e+03, 8: 0.35763911791061412378285349910e+03,
        9: 0.93405324183624310003907691704e+02, 10: -0.37458323136451633156875139351e+02,
        11: 0.10409964950896230045147246184e+03, 12: 0.29840293426660503123344363579e+02,
        13: -0.43533456590011143754432175058e+02, 14: 0.96324553959188282948394950600e+02,
        15: -0.39177261675615439165231486172e+02, 16: -0.14972683625798562581422125276e+03},
}



def _table(rows: dict, shape: tuple, first_row: int = 1) -> np.ndarray:
    """A dense array of dop853.f's numbered coefficients: ``rows[i][j]`` at [i − first_row, j − 1]."""
    out = np.zeros(shape)
    for i, row in rows.items():
        for j, value in row.items():
            out[i - first_row, j - 1] = value
    return out


C853 = _table({1: _C}, (1, N_STAGES_EXTENDED))[0]
A853 = _table(_A, (N_STAGES_EXTENDED, N_STAGES_EXTENDED))     # row 12 holds the weights b (the FSAL stage)
B853 = np.ascontiguousarray(A853[N_STAGES, :N_STAGES])
E3 = np.zeros(N_STAGES + 1)                                  # b − bhh: the 3rd-order error estimate
E3[:N_STAGES] = B853
E3 -= _table({1: _BHH}, (1, N_STAGES + 1))[0]
E5 = _table({1: _ER}, (1, N_STAGES + 1))[0]                  # the 5th-order error estimate
D853 = _table(_D, (4, N_STAGES_EXTENDED), first_row=4)
ERROR_EXPONENT_853 = -1.0 / 8.0       # error estimator of order 7
FSAL_ROW_853 = N_STAGES


@njit(cache=True)
def dop853_step(t, y, f0, h, K, y_new, ytmp, rocking, side, phase, kind, xp, samples, sp, n):
    """One DOP853 step of size h from (t, y) with f0 = f(t, y) (Hairer–Nørsett–Wanner II.5; dop853.f's stages).

    Fills K[0..12] with the stage derivatives (K[12] = f(t+h, y_new), FSAL) and ``y_new``; only the
    first ``n`` components take part.  Returns the number of right-hand-side evaluations (12).
    Sums run over the stages in order, skipping the tableau's zeros (stage-outer loops: the
    components' sums are independent chains the processor overlaps).
    """
    for i in range(n):
        K[0, i] = f0[i]
    # one call site of the (inlined) right-hand side: stages 1–11, then f at the new point
    for s in range(1, N_STAGES + 1):
        for i in range(n):
            ytmp[i] = 0.0
        for j in range(s):
            a = A853[s, j]          # row 12 holds the weights B
            if a != 0.0:
                for i in range(n):
                    ytmp[i] += a * K[j, i]
        for i in range(n):
            ytmp[i] = y[i] + h * ytmp[i]
        if s == N_STAGES:
            for i in range(n):
                y_new[i] = ytmp[i]
        rhs(t + C853[s] * h, ytmp, K[s], rocking, side, phase, kind, xp, samples, sp)
    return N_STAGES


@njit(cache=True)
def dop853_error_norm(y, y_new, K, h, rtol, atol, n, work):
    """dop853.f's error norm (as scipy's DOP853): |h|·‖e5‖² / √((‖e5‖² + 0.01‖e3‖²)·n), scaled by
    atol + rtol·max(|y|, |y_new|).

    ``work``: scratch of at least 8 floats.
    """
    for i in range(n):
        work[i] = 0.0
        work[4 + i] = 0.0
    for j in range(N_STAGES + 1):
        a5 = E5[j]
        a3 = E3[j]
        for i in range(n):
            work[i] += a5 * K[j, i]
            work[4 + i] += a3 * K[j, i]
    e5 = 0.0
    e3 = 0.0
    for i in range(n):
        sc = atol + rtol * max(abs(y[i]), abs(y_new[i]))
        e5 += (work[i] / sc) ** 2
        e3 += (work[4 + i] / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@njit(cache=True)
def dop853_dense(t, y, y_new, h, K, Q, ytmp, rocking, side, phase, kind, xp, samples, sp, n, work):
    """The 7th-order dense output of an accepted step into Q (monomial form); 3 more evaluations.

    As dop853.f's dense output (and scipy's ``DOP853``): stages 13–15 into K, then F₀ = Δy,
    F₁ = h f₀ − Δy, F₂ = 2Δy − h(f₁ + f₀), F₃.. = h D K and
    y(x) = y + x(F₀ + (1−x)(F₁ + x(F₂ + (1−x)(F₃ + …)))), expanded here into powers of x.
    ``work``: scratch of at least 8 floats.  Returns the number of evaluations (3).
    """
    for s in range(N_STAGES + 1, N_STAGES_EXTENDED):
        for i in range(n):
            ytmp[i] = 0.0
        for j in range(s):
            a = A853[s, j]
            if a != 0.0:
                for i in range(n):
                    ytmp[i] += a * K[j, i]
        for i in range(n):
            ytmp[i] = y[i] + h * ytmp[i]
        rhs(t + C853[s] * h, ytmp, K[s], rocking, side, phase, kind, xp, samples, sp)
    # F₃.. = h D K into Q[:, 3..6] (stage-outer sums), then F₀..F₂ and the expansion per component
    for r in range(D853.shape[0]):
        for i in range(n):
            Q[i, 3 + r] = 0.0
        for j in range(N_STAGES_EXTENDED):
            d = D853[r, j]
            if d != 0.0:
                for i in range(n):
                    Q[i, 3 + r] += d * K[j, i]
    c = work
    for i in range(n):
        dy = y_new[i] - y[i]
        f_0 = dy
        f_1 = h * K[0, i] - dy
        f_2 = 2.0 * dy - h * (K[FSAL_ROW_853, i] + K[0, i])
        # Horner in the mixed basis, from the innermost factor outwards: p ← (p + F_k)·(x or 1 − x)
        for k in range(8):
            c[k] = 0.0
        c[0] = h * Q[i, 6]
        for k in range(5, -1, -1):
            if k % 2 == 1:          # multiply by x (shift up)
                for m in range(7, 0, -1):
                    c[m] = c[m - 1]
                c[0] = 0.0
            else:                   # multiply by (1 − x)
                for m in range(7, 0, -1):
                    c[m] = c[m] - c[m - 1]
            if k == 0:
                c[0] += f_0
            elif k == 1:
                c[0] += f_1
            elif k == 2:
                c[0] += f_2
            else:
                c[0] += h * Q[i, k]
        # the outermost factor x: y(x) − y = Σ_{m=0..6} c[m] x^(m+1) = h Σ Q[i, m] x^(m+1)
        for m in range(7):
            Q[i, m] = c[m] / h
    return N_STAGES_EXTENDED - N_STAGES - 1
