"""The outcome of one analysis in the words the shared acceptance code reads (docs/architecture.md, "One front
door per kind of structure").

Each kind maps its physics into these names: a rocking column's θ_max/θc (thesis Eq 3.56), a cylinder's
θ_max/θ_ot (Sec 5.5.1), a test kind's displacement over its allowance are all a run's ``response_ratio``; the
unacceptable response (overturning, for the thesis's structures) is ``overturned``.  The acceptance rule, the
margins and the design grid read nothing else of a run, so a kind needs no field of another kind.
"""
from __future__ import annotations

from typing import Mapping, Protocol


class Run(Protocol):
    """One analysis of one record, as the acceptance rule reads it."""

    @property
    def status(self) -> str:
        """"completed" for an analysis that ran to a conclusion, the engine's word otherwise."""

    @property
    def failed(self) -> bool:
        """True when the analysis did not run to a conclusion (its result may not be used)."""

    @property
    def overturned(self) -> bool:
        """True when the response is unacceptable (§16.4.1.1): the structure overturned."""

    @property
    def response_ratio(self) -> float:
        """The peak response over the kind's capacity measure (dimensionless; 1 is the capacity): θ_max/θc of a
        planar column (Eq 3.56), θ_max/θ_ot of a cylinder (Sec 5.5.1)."""


class Margin(Protocol):
    """The incremental scan of one record (SPEC §11): the factors on its design scaling that were analysed."""

    @property
    def overturn_scale(self) -> float | None:
        """The lowest factor at which the record's analysis overturned (None: none did up to the scan's end)."""


class Outcome(Protocol):
    """One record of a check: its id, its metadata (event, year, station), its design-level run and its scan."""

    @property
    def id(self) -> str: ...

    @property
    def meta(self) -> Mapping: ...

    @property
    def run(self) -> Run: ...

    @property
    def margin(self) -> Margin | None: ...
