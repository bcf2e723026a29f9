"""The recommended design of a design chart (SPEC §15, CONTRACT §7.4 and §8.1, docs/design.md "The recommended
design"): the preferred robust PASS (least superstructure shear, or least material) whose tolerance
neighbourhood — each varied key at ± its construction tolerance (:mod:`.tolerance`), the others nominal — also
passes in its own check; where none does, said so, with the nearest candidates and their distances to the flip.
"""
from __future__ import annotations

import math

from ..display import verdict_words

PREFER = ("material", "shear")
"""What the recommendation minimises among robust passing variants (``--prefer``)."""


def _rank(prefer: str | None):
    """The order of preference over cells, by their neutral keys (each kind maps its physics into them,
    :meth:`~rockdesign.kinds.base.StructureKind.grid_cell`): ``demand`` — the force the recommendation minimises,
    equal to three significant digits — then ``material`` [kg]; or material first (``prefer = "material"``)."""
    def shear(c):
        x = c.get("demand")
        return float(f"{x:.3g}") if x is not None else math.inf

    def mass(c):
        x = c.get("material")
        return x if x is not None else math.inf
    if prefer == "material":
        return lambda c: (mass(c), shear(c))
    return lambda c: (shear(c), mass(c))


def _labels(cell: dict) -> str:
    return ", ".join(f"{k} = {v}" for k, v in cell["labels"].items())


def _neighbours(best: dict, cells: list[dict], rank, what: str) -> str:
    """Why ``best`` was chosen over the cells next to it in the grid (one step along each axis)."""
    here = tuple(best["index"])
    parts = []
    for c in cells:
        idx = tuple(c["index"])
        if sum(abs(a - b) for a, b in zip(idx, here)) != 1:
            continue
        changed = [k for k in best["labels"] if c["labels"][k] != best["labels"][k]]
        name = ", ".join(f"{k} = {c['labels'][k]}" for k in changed)
        words = verdict_words(c)
        if c.get("analysed", True) and c.get("verdict") == "PASS" and c.get("robust"):
            words += f", more {what}" if rank(c) > rank(best) else f", {what} not lower"
        parts.append(f"{name}: {words}")
    return "; ".join(parts)


def recommended(cells: list[dict], material: tuple[str, str] = ("material", "no demand to rank by"),
                prefer: str | None = None, choice: dict | None = None,
                demand: str = "demand (") -> dict | None:
    """The recommended design (SPEC §15): a robust PASS whenever one exists — among the analysed passing cells
    that pass all their perturbation draws, the lowest 84th-percentile superstructure shear coefficient (equal
    to 3 significant digits: the least column material n·m_C), or with ``prefer = "material"`` (or without an
    elastic superstructure) the least material (``material``: what is least and why, the kind's
    :attr:`~rockdesign.kinds.base.StructureKind.design_material`); with its margin, its robustness and why it
    was chosen over its neighbours.  Where no cell passes robustly, the best fragile PASS with
    ``"robust": false`` and the fragile candidates named (``fragile_candidates``); None when no cell passes.
    ``choice``: the cell to recommend instead of the best-ranked one (the one that survives its tolerance,
    :func:`with_tolerance`), described the same way."""
    passing = [c for c in cells if c.get("analysed", True) and c["verdict"] == "PASS"]
    if not passing:
        return None
    robust = [c for c in passing if c.get("robust")]
    rank = _rank(prefer)
    best = choice if choice is not None else min(robust or passing, key=rank)
    margin = []
    if best.get("acmr") is not None and best.get("acmr_required"):
        margin.append(f"ACMR {best['acmr']:.3g} ≥ {best['acmr_required']:.3g} required "
                      f"(×{best['acmr'] / best['acmr_required']:.3g})")
    if best.get("n_unacceptable") is not None and best.get("acceptance") != "binomial":
        margin.append(f"{best['n_unacceptable']} of {best['n_ground_motions']} ground motions unacceptable "
                      f"({best['allowed_unacceptable']} allowed)")
    if best.get("acceptance") == "binomial" and best.get("p_overturn_bound") is not None:
        margin.append(f"P(overturn) ≤ {best['p_overturn_bound']:.3g} at 95 % confidence "
                      f"(limit {best['binomial_limit']:.3g})")
    shear = best.get("demand")
    mass = best.get("material")
    what = material[0] + (f" {mass / 1000:.3g} t" if mass is not None and math.isfinite(mass) else "")
    kind_of_pass = "robust passing" if robust else "passing"
    by_shear = prefer != "material" and shear is not None
    why = (f"the {kind_of_pass} variant with the lowest {demand} {shear:.3g})" if by_shear else
           f"the {kind_of_pass} variant with the least {what}"
           + (f" ({material[1]})" if prefer != "material" else " (preferred: material)"))
    if choice is not None and choice is not min(robust or passing, key=rank):
        why = why.replace(" variant with ", " variant that survives its construction tolerance with ", 1)
    reason = f"{why}; margin: " + "; ".join(margin) if margin else why
    reason += "; " + (best.get("robustness") or "robustness not evaluated")
    near = _neighbours(best, cells, rank, "shear" if by_shear else "material")
    if near:
        reason += f"; chosen over its neighbours ({near})"
    out = {"values": best["values"], "labels": best["labels"], "index": best["index"], "reason": reason,
           "robust": bool(best.get("robust")), "prefer": "shear" if by_shear else "material"}
    if not robust:
        fragile = sorted(passing, key=rank)
        out["fragile_candidates"] = [{"labels": c["labels"], "index": c["index"],
                                      "robustness": c.get("robustness")} for c in fragile]
        out["no_robust_pass"] = ("no variant passes robustly: every passing variant fails in some perturbation "
                                 "draw or has its margin at its requirement; fragile candidates: "
                                 + "; ".join(_labels(c) for c in fragile[:5]) + (" …" if len(fragile) > 5 else ""))
    return out


def check_exit_code(cells: list[dict]) -> int:
    """0 when at least one variant passes, 1 when none does (CONTRACT §6.3)."""
    return 0 if any(c.get("analysed", True) and c["verdict"] == "PASS" for c in cells) else 1


MAX_CANDIDATES = 12
"""Robust passing variants whose tolerance neighbourhood is checked, best-ranked first, before the chart says that
none of them survives its tolerance (each costs one check per neighbour)."""
AT_ONCE = 1
"""Candidates whose neighbourhoods are checked together (their variants share batches): one, since the best-ranked
candidate usually survives and a second one's checks would be spent for nothing."""


def neighbourhood_of(candidate: dict, variables, tolerances: dict, raw: dict, file: str) -> list:
    """The tolerance neighbours of a cell: each varied key at its value ± its tolerance, the others nominal
    (a key built exactly, tolerance 0, has none), as validated variants."""
    from .variants import neighbour_variant
    out = []
    index = tuple(candidate["index"])
    for var in variables:
        base = candidate["values"][var.key]
        tol = tolerances[var.key].plus_minus(base)
        if tol <= 0.0:
            continue
        for sign in (-1.0, 1.0):
            out.append((var.key, sign, neighbour_variant(raw, variables, index, var.key, base + sign * tol,
                                                        file=file)))
    return out


def _neighbour_entry(key: str, sign: float, cell: dict, tolerance) -> dict:
    """design.json ``recommended.neighbourhood[]`` (CONTRACT §8.1) from a neighbour's cell."""
    return {"key": key, "side": "+" if sign > 0 else "−", "tolerance": tolerance.as_json(),
            "values": cell["values"], "labels": cell["labels"], "verdict": cell["verdict"],
            "n_unacceptable": cell.get("n_unacceptable"), "acmr": cell.get("acmr"),
            "flip_margin": cell.get("flip_margin"), "reason": cell.get("reason"), "analyses": cell.get("analyses")}


def _summary(entries: list[dict]) -> str:
    bad = [e for e in entries if e["verdict"] != "PASS"]
    if not entries:
        return "no tolerance neighbours (every varied key is built exactly)"
    if not bad:
        return f"passes at each of its {len(entries)} tolerance neighbours"
    return (f"fails at {len(bad)} of its {len(entries)} tolerance neighbours ("
            + "; ".join(f"{e['key']} {e['side']}: {e['verdict']}" + (f", {e['n_unacceptable']} unacceptable"
                                                                      if e.get("n_unacceptable") is not None else "")
                        for e in bad) + ")")


def with_tolerance(rec: dict | None, cells: list[dict], run_neighbours, variables, tolerances: dict, raw: dict,
                   file: str, *, material=("material", "no demand to rank by"),
                   prefer: str | None = None, say=None,
                   demand: str = "demand (") -> dict | None:
    """The recommendation that survives its construction tolerance (module docstring).

    Args:
        rec: :func:`recommended` of the cells (None: no cell passes — nothing to do).
        run_neighbours: ``run_neighbours(list of (key, variant)) -> {key: cell}``: the checks of neighbour variants
            (the grid's :class:`~rockdesign.design_space.batches.VariantChecker`).
        tolerances: ``{key: Tolerance}`` of the varied keys (:func:`~rockdesign.design_space.tolerance.tolerances`).
        say: ``say(text)`` as each round of neighbourhood checks starts.

    Returns the recommendation with ``tolerance_robust``, ``neighbourhood`` (the chosen cell's neighbour runs) and,
    where no robust PASS survives, ``no_tolerance_robust_pass`` and ``candidates`` (those tried, nearest to
    surviving first: fewest failing neighbours, then the largest flip margin).
    """
    if rec is None:
        return None
    rank = _rank(prefer)
    # a robust PASS whose flip margin is ≤ 1 passes only at the exact design level (ground motions overturn in
    # bands below it): tried after those with a margin above 1
    robust = sorted((c for c in cells if c.get("analysed", True) and c["verdict"] == "PASS" and c.get("robust")),
                    key=lambda c: (not (c.get("flip_margin") or 0.0) > 1.0, rank(c)))
    chosen = robust[:MAX_CANDIDATES] if robust else [next(c for c in cells if c["index"] == rec["index"])]
    tried: list[tuple[dict, list[dict]]] = []
    survivor = None
    for start in range(0, len(chosen), AT_ONCE):
        group = chosen[start:start + AT_ONCE]
        jobs, where = [], []
        for c in group:
            for key, sign, variant in neighbourhood_of(c, variables, tolerances, raw, file):
                name = (tuple(c["index"]), key, sign)
                jobs.append((name, variant))
                where.append((c, key, sign, name))
        if say is not None and jobs:
            say(f"tolerance neighbourhood of {', '.join(_labels(c) for c in group)}: {len(jobs)} checks "
                "(each varied key ± its construction tolerance)")
        found = run_neighbours(jobs) if jobs else {}
        for c in group:
            entries = [_neighbour_entry(key, sign, found[name], tolerances[key])
                       for cc, key, sign, name in where if cc is c]
            tried.append((c, entries))
            if survivor is None and all(e["verdict"] == "PASS" for e in entries):
                survivor = (c, entries)
        if survivor is not None or not robust:
            break
    if survivor is not None:
        best, entries = survivor
        out = dict(rec) if best["index"] == rec["index"] else recommended(cells, material, prefer, choice=best,
                                                                          demand=demand)
        out.update(tolerance_robust=bool(best.get("robust")), neighbourhood=entries)
        out["reason"] += f"; tolerance: {_summary(entries)}" + _flip_words(best)
        skipped = [c for c, _ in tried[:[c for c, _ in tried].index(best)]]
        if skipped:
            out["reason"] += ("; preferred over it but not surviving their tolerance: "
                              + "; ".join(_labels(c) for c in skipped))
        return out
    nearest = sorted(tried, key=lambda t: (sum(e["verdict"] != "PASS" for e in t[1]),
                                           -(t[0].get("flip_margin") or 0.0)))
    best, entries = nearest[0]
    out = recommended(cells, material, prefer, choice=best, demand=demand)
    out.update(tolerance_robust=False, neighbourhood=entries, no_tolerance_robust_pass=True,
               candidates=[{"values": c["values"], "labels": c["labels"], "index": c["index"],
                            "robust": bool(c.get("robust")), "flip_margin": c.get("flip_margin"),
                            "neighbours_failed": sum(e["verdict"] != "PASS" for e in es),
                            "neighbourhood": es} for c, es in nearest])
    what = "robust PASS" if robust else "PASS"
    more = f" (the {len(chosen)} best-ranked of {len(robust)} tried)" if len(robust) > len(chosen) else ""
    out["no_tolerance_robust"] = (
        f"no {what} survives its construction tolerance{more}: every candidate fails in some tolerance "
        "neighbour; nearest: " + "; ".join(
            f"{_labels(c)} (flip margin {_num(c.get('flip_margin'))}, fails at "
            f"{sum(e['verdict'] != 'PASS' for e in es)} of {len(es)} neighbours)" for c, es in nearest[:5]))
    out["reason"] += f"; tolerance: {_summary(entries)}" + _flip_words(best)
    return out


def _flip_words(cell: dict) -> str:
    x = cell.get("flip_margin")
    if x is None:
        return ""
    return (f"; distance to the flip: λ = {'≥ ' if cell.get('flip_margin_is_lower_bound') else ''}{x:.3g} × the "
            f"design intensity ({cell.get('flip_governing')})")


def _num(x) -> str:
    return "—" if x is None else f"{x:.3g}"


__all__ = ["recommended", "with_tolerance", "neighbourhood_of", "check_exit_code", "PREFER", "MAX_CANDIDATES"]
