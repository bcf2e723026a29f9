"""Strict JSON from results that hold numpy values: the one converter every JSON writer uses."""
from __future__ import annotations

import math

import numpy as np


def json_ready(value):
    """``value`` with numpy scalars and arrays as Python numbers and lists, and non-finite floats
    (NaN, ±inf) as None, so that ``json.dumps`` writes strict JSON (RFC 8259 has no NaN)."""
    if isinstance(value, dict):
        return {k: json_ready(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_ready(v) for v in value]
    if isinstance(value, np.ndarray):
        return json_ready(value.tolist())
    if isinstance(value, (np.floating, float)):
        x = float(value)
        return x if math.isfinite(x) else None
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.generic):
        return value.item()
    return value


class SerialisedOnce:
    """A finished result whose ``as_json()`` is built once: :meth:`serialise` (the subclass's) runs on the first
    call and every later call returns the same dict, so results.json, results.csv, the report and the console
    summary of one check read one serialisation.  The dict is shared: read it, do not change it."""

    def serialise(self) -> dict:
        raise NotImplementedError

    def as_json(self) -> dict:
        cached = self.__dict__.get("_serialised")
        if cached is None:
            cached = self.__dict__["_serialised"] = self.serialise()
        return cached
