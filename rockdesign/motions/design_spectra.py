"""Code design spectra (pseudo-acceleration, 5 % damping unless stated) for spectrum scaling.

* Eurocode 8 (EN 1998-1:2004 §3.2.2.2, Tables 3.2/3.3) horizontal elastic spectrum S_e(T),
  Type 1 (default) or Type 2, ground types A–E, damping correction η = √(10/(5+ξ)) ≥ 0.55
  (ξ in %, Eq 3.6).
* ASCE 7 (ASCE/SEI 7-16 §11.4.6, Fig 11.4-1) two-period design spectrum S_a(T) from S_DS, S_D1
  and T_L.

All values are SI: periods in s, accelerations in m/s².
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

EC8_GROUND_TYPES = {
    # type: {ground type: (S, T_B, T_C, T_D)}  EN 1998-1 Table 3.2 (Type 1) and Table 3.3 (Type 2)
    1: {"A": (1.0, 0.15, 0.4, 2.0), "B": (1.2, 0.15, 0.5, 2.0), "C": (1.15, 0.20, 0.6, 2.0),
        "D": (1.35, 0.20, 0.8, 2.0), "E": (1.4, 0.15, 0.5, 2.0)},
    2: {"A": (1.0, 0.05, 0.25, 1.2), "B": (1.35, 0.05, 0.25, 1.2), "C": (1.5, 0.10, 0.25, 1.2),
        "D": (1.8, 0.10, 0.30, 1.2), "E": (1.6, 0.05, 0.25, 1.2)},
}


@dataclass(frozen=True)
class EC8Spectrum:
    """EN 1998-1 horizontal elastic response spectrum S_e(T) (Eqs 3.2–3.5).

    Attributes:
        ag: design ground acceleration on type A ground a_g = γ_I a_gR [m/s²].
        ground_type: A, B, C, D or E.
        spectrum_type: 1 (high seismicity, M_s > 5.5) or 2.
        damping: viscous damping ratio ξ (0.05 = 5 %), through η = √(10/(5+100ξ)) ≥ 0.55.
    """

    ag: float
    ground_type: str = "C"
    spectrum_type: int = 1
    damping: float = 0.05

    @property
    def parameters(self) -> tuple[float, float, float, float]:
        """(S, T_B [s], T_C [s], T_D [s]) of Table 3.2/3.3."""
        return EC8_GROUND_TYPES[self.spectrum_type][self.ground_type]

    @property
    def eta(self) -> float:
        """Damping correction η = √(10/(5+ξ[%])) ≥ 0.55 (EN 1998-1 Eq 3.6)."""
        return max(math.sqrt(10.0 / (5.0 + 100.0 * self.damping)), 0.55)

    def psa(self, periods) -> np.ndarray:
        """S_e(T) [m/s²] at periods T [s] (EN 1998-1 Eqs 3.2–3.5; the T_D branch continues past 4 s)."""
        T = np.asarray(periods, dtype=float)
        S, TB, TC, TD = self.parameters
        plateau = self.ag * S * self.eta * 2.5
        T_safe = np.maximum(T, 1e-12)
        rising = self.ag * S * (1.0 + T / TB * (self.eta * 2.5 - 1.0))
        falling = np.where(T <= TD, plateau * TC / T_safe, plateau * TC * TD / T_safe ** 2)
        return np.where(T <= TB, rising, np.where(T <= TC, plateau, falling))

    def describe(self) -> str:
        """One line naming the spectrum and its parameters (for reports)."""
        S, TB, TC, TD = self.parameters
        return (f"EN 1998-1 Type {self.spectrum_type} elastic spectrum, ground type {self.ground_type} "
                f"(a_g = {self.ag:.4g} m/s², S = {S}, T_B = {TB} s, T_C = {TC} s, T_D = {TD} s, "
                f"ξ = {100 * self.damping:g} %, η = {self.eta:.3f})")


@dataclass(frozen=True)
class ASCE7Spectrum:
    """ASCE/SEI 7-16 §11.4.6 design response spectrum S_a(T) (5 % damping).

    Attributes:
        SDS: short-period design spectral acceleration S_DS [m/s²].
        SD1: 1-s design spectral acceleration S_D1 [m/s²·s] (given like an acceleration, "0.6 g").
        TL: long-period transition period T_L [s].
    """

    SDS: float
    SD1: float
    TL: float = 8.0

    @property
    def T0(self) -> float:
        """T_0 = 0.2 S_D1/S_DS [s]."""
        return 0.2 * self.SD1 / self.SDS

    @property
    def TS(self) -> float:
        """T_S = S_D1/S_DS [s]."""
        return self.SD1 / self.SDS

    def psa(self, periods) -> np.ndarray:
        """S_a(T) [m/s²]: S_DS(0.4 + 0.6T/T_0) | S_DS | S_D1/T | S_D1 T_L/T² (ASCE 7-16 Eqs 11.4-5 to 11.4-8)."""
        T = np.asarray(periods, dtype=float)
        T_safe = np.maximum(T, 1e-12)
        long_period = np.where(T <= self.TL, self.SD1 / T_safe, self.SD1 * self.TL / T_safe ** 2)
        return np.where(T < self.T0, self.SDS * (0.4 + 0.6 * T / self.T0),
                        np.where(T <= self.TS, self.SDS, long_period))

    def describe(self) -> str:
        """One line naming the spectrum and its parameters (for reports)."""
        return (f"ASCE 7-16 design spectrum (S_DS = {self.SDS:.4g} m/s², S_D1 = {self.SD1:.4g} m/s², "
                f"T_0 = {self.T0:.3g} s, T_S = {self.TS:.3g} s, T_L = {self.TL:g} s, 5 % damping)")
