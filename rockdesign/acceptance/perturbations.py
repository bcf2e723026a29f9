"""The perturbation draws of the check, shared by every kind (SPEC §14–15): rocking after many impacts is
chaotic, so a verdict is also taken under draws perturbed well inside the input's own accuracy — the
amplitude by a factor uniform in 1 ± 0.1 % per ground motion, c_r by a factor uniform in 1 ± 2 % per draw
(capped at 1 where applied) and the integrator tolerances one decade tighter.  Seeded: the same draws on
every run."""
from __future__ import annotations

import numpy as np

AMPLITUDE_VARIATION = 0.001
RESTITUTION_VARIATION = 0.02
TOLERANCE_FACTOR = 0.1


def draw_words(*, restitution: bool = True) -> str:
    """What a perturbed suite run varies, in the verdict's words ("amplitude ± 0.1 %, c_r ± 2 %, rtol/10";
    without ``restitution`` for a kind with no coefficient of restitution)."""
    parts = [f"amplitude ± {100 * AMPLITUDE_VARIATION:g} %"]
    if restitution:
        parts.append(f"c_r ± {100 * RESTITUTION_VARIATION:g} %")
    parts.append(f"rtol/{1 / TOLERANCE_FACTOR:g}")
    return ", ".join(parts)


def perturbations(n_records: int, size: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """(amplitude factors size × n_records, c_r factors size), uniform in 1 ± the variations, seeded."""
    rng = np.random.default_rng(seed)
    amplitude = 1.0 + AMPLITUDE_VARIATION * rng.uniform(-1.0, 1.0, size=(size, n_records))
    restitution = 1.0 + RESTITUTION_VARIATION * rng.uniform(-1.0, 1.0, size=size)
    return amplitude, restitution
