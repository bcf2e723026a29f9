"""Coarse-to-fine order of a design grid (SPEC §15): analyse a coarse sub-grid first, then refine only
where the answer changes.

Along an axis of at least :data:`MIN_AXIS` values the grid is analysed at a stride ``s`` (a power of two, the
largest with ``2 s ≤ N − 1``; the last value always belongs), then at ``s/2``, … down to 1.  A cell that
appears at a finer level is analysed unless every corner of the coarser box around it (the nearest coarser
values below and above it along each axis; one corner per axis where it lies on a coarser value) is known to
agree: all robust PASS, or all FAIL.  A cell whose corners disagree, or where a corner is a fragile PASS, an
invalid variant or an error, is analysed — so the boundary between passing and failing regions is refined to
single cells.  A cell left out is "not analysed": it carries no verdict word, only the category its corners
agree on.  Axes with fewer values are analysed at every value (``every_cell`` analyses every cell)."""
from __future__ import annotations

import itertools
import math

import numpy as np

MIN_AXIS = 5
"""The fewest values along an axis for it to be analysed coarse first."""

AGREEING = ("robust PASS", "FAIL")
"""Categories whose agreement leaves the cells between them unanalysed."""


def category(cell: dict | None) -> str | None:
    """A cell's region: "robust PASS", "fragile PASS", "FAIL", "INVALID", "ERROR", or for a cell not analysed
    the category its corners agree on (``between``); None when unknown."""
    if cell is None:
        return None
    if not cell.get("analysed", True):
        return cell.get("between")
    v = cell.get("verdict")
    if v == "PASS":
        return "robust PASS" if cell.get("robust") else "fragile PASS"
    return v


def _stride(n: int) -> int:
    if n < MIN_AXIS:
        return 1
    s = 1
    while 2 * (2 * s) <= n - 1:
        s *= 2
    return s


def _lattice(n: int, stride: int) -> list[int]:
    return sorted(set(range(0, n, stride)) | {n - 1})


def levels(shape: tuple[int, ...], every_cell: bool = False) -> list[list[tuple[int, ...]]]:
    """The cells of each level, coarsest first (each cell once; indexes are tuples over the axes)."""
    if every_cell:
        return [list(itertools.product(*(range(n) for n in shape)))]
    depth = max(_stride(n).bit_length() - 1 for n in shape)
    out, seen = [], set()
    for level in range(depth + 1):
        cells = [c for c in itertools.product(*(_lattice(n, stride)
                                                for n, stride in zip(shape, level_strides(shape, level))))
                 if c not in seen]
        seen.update(cells)
        out.append(cells)
    return out


def corners(index: tuple[int, ...], shape: tuple[int, ...], stride: tuple[int, ...]) -> list[tuple[int, ...]]:
    """The corners of the coarser box (strides ``stride``) around ``index``."""
    sides = []
    for i, n, s in zip(index, shape, stride):
        lat = _lattice(n, s)
        below = max(x for x in lat if x <= i)
        above = min(x for x in lat if x >= i)
        sides.append(sorted({below, above}))
    return list(itertools.product(*sides))


def level_strides(shape: tuple[int, ...], level: int) -> tuple[int, ...]:
    """The strides along each axis at ``level`` (0: coarsest)."""
    return tuple(max(1, _stride(n) >> level) for n in shape)


def agreed(index, shape, level: int, known: dict) -> str | None:
    """The category every corner of the coarser box around ``index`` agrees on (one of :data:`AGREEING`), every
    corner far from its flip, or None: the cell must be analysed (``known``: index → cell of the coarser
    levels)."""
    from ..acceptance.flip import far_from_flip
    if level == 0:
        return None
    around = [known.get(c) for c in corners(index, shape, level_strides(shape, level - 1))]
    found = {category(c) for c in around}
    if len(found) == 1:
        (only,) = found
        if only in AGREEING and all(not c.get("analysed", True) or far_from_flip(c) for c in around):
            return only
    return None


def neighbours(index: tuple[int, ...], shape: tuple[int, ...]) -> list[tuple[int, ...]]:
    """The cells touching ``index`` along an axis or a diagonal (inside the grid)."""
    out = []
    for step in itertools.product((-1, 0, 1), repeat=len(shape)):
        other = tuple(i + d for i, d in zip(index, step))
        if any(step) and all(0 <= i < n for i, n in zip(other, shape)):
            out.append(other)
    return out


def unsafe(shape: tuple[int, ...], known: dict) -> list[tuple[int, ...]]:
    """Cells left out that touch a cell of another category (analysed, or left out between other corners): the
    inference would cross an edge there, so they must be analysed."""
    out = []
    for index, cell in sorted(known.items()):
        if cell is None or cell.get("analysed", True):
            continue
        mine = category(cell)
        if any(known.get(n) is not None and category(known[n]) != mine for n in neighbours(index, shape)):
            out.append(index)
    return out


AUDIT_FRACTION = 0.1
"""The share of the cells left out that is analysed as an audit of the inference (at least one)."""


def audit_sample(left_out: list[tuple[int, ...]], seed: int) -> list[tuple[int, ...]]:
    """A seeded sample of the cells left out (:data:`AUDIT_FRACTION`, at least one when any is left out), in grid
    order: the same cells on every run."""
    if not left_out:
        return []
    n = max(1, math.ceil(AUDIT_FRACTION * len(left_out)))
    pick = np.random.default_rng(seed).choice(len(left_out), size=n, replace=False)
    return sorted(left_out[int(k)] for k in pick)


__all__ = ["levels", "agreed", "category", "corners", "level_strides", "neighbours", "unsafe", "audit_sample",
           "MIN_AXIS", "AGREEING", "AUDIT_FRACTION"]
