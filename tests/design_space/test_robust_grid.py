"""Robust design charts without analyses: the coarse-to-fine order of the grid, the robust
recommendation and the words of a cell (the analysed cells are compared with ``rockdesign check`` in
test_grid.py)."""
from __future__ import annotations

import itertools

import pytest

from rockdesign.design_space.cells import margin_undecided, robustness
from rockdesign.design_space.recommend import recommended
from rockdesign.display import verdict_words
from rockdesign.design_space.refine import agreed, corners, levels, level_strides
from rockdesign.design_space.store import shape_problem


def test_levels_cover_every_cell_once_coarse_first():
    for shape in [(10, 10), (5,), (7, 3), (3, 3), (16,), (2, 9)]:
        order = levels(shape)
        flat = [c for lvl in order for c in lvl]
        assert sorted(flat) == sorted(itertools.product(*(range(n) for n in shape)))
        assert len(flat) == len(set(flat))
    assert levels((10,))[0] == [(0,), (4,), (8,), (9,)]       # stride 4, the last value always
    assert levels((3, 3)) == [sorted(itertools.product(range(3), range(3)))]   # short axes: every value
    assert len(levels((10, 10), every_cell=True)) == 1


def test_corners_bracket_a_cell_with_the_coarser_lattice():
    assert level_strides((10, 10), 0) == (4, 4)
    assert sorted(corners((2, 5), (10, 10), (4, 4))) == [(0, 4), (0, 8), (4, 4), (4, 8)]
    assert sorted(corners((4, 6), (10, 10), (4, 4))) == [(4, 4), (4, 8)]      # on a coarse line: 2 corners


def _c(verdict, robust=None, flip=None):
    """An analysed cell, far from its flip unless ``flip`` says otherwise."""
    if flip is None:
        flip = 2.0 if verdict == "PASS" else 0.5
    return {"verdict": verdict, "robust": robust, "analysed": True, "flip_margin": flip}


def test_a_cell_is_left_out_only_between_agreeing_robust_or_failing_corners():
    shape = (9,)                                     # stride 4: 0, 4, 8, then 2, 6, then the odd ones
    known = {(0,): _c("FAIL"), (4,): _c("FAIL"), (8,): _c("PASS", True)}
    assert agreed((2,), shape, 1, known) == "FAIL"
    assert agreed((6,), shape, 1, known) is None     # FAIL | PASS: the boundary is refined
    known[(4,)] = _c("PASS", False)                  # a fragile PASS is never interpolated
    assert agreed((2,), shape, 1, known) is None
    known = {(0,): _c("PASS", True), (4,): _c("PASS", True)}
    assert agreed((2,), shape, 1, known) == "robust PASS"
    known[(4,)] = _c("INVALID")
    assert agreed((2,), shape, 1, known) is None
    # agreeing corners near their flip (SPEC §15: a chaotic landscape is not smooth): analysed
    known = {(0,): _c("PASS", True, 1.3), (4,): _c("PASS", True, 1.2)}
    assert agreed((2,), shape, 1, known) is None
    known[(4,)] = _c("PASS", True, 1.25)
    assert agreed((2,), shape, 1, known) == "robust PASS"
    known = {(0,): _c("FAIL", flip=0.5), (4,): _c("FAIL", flip=0.9)}     # a FAIL that passes at 0.9 × design
    assert agreed((2,), shape, 1, known) is None
    known[(4,)] = _c("FAIL", flip=0.8)
    assert agreed((2,), shape, 1, known) == "FAIL"
    known[(4,)] = {**_c("FAIL", flip=0.7), "flip_margin_is_lower_bound": True}   # only known to be ≥ 0.7
    assert agreed((2,), shape, 1, known) is None
    known[(4,)] = {**_c("FAIL"), "flip_margin": None}                   # no distance known: never inferred
    assert agreed((2,), shape, 1, known) is None


def test_no_cell_left_out_touches_a_cell_of_another_category():
    from rockdesign.design_space.refine import audit_sample, neighbours, unsafe
    assert sorted(neighbours((0, 0), (3, 3))) == [(0, 1), (1, 0), (1, 1)]
    assert len(neighbours((1, 1), (3, 3))) == 8
    left = {"analysed": False, "between": "robust PASS"}
    known = {(0, 0): _c("PASS", True), (0, 1): left, (0, 2): _c("PASS", True),
             (1, 0): _c("PASS", True), (1, 1): left, (1, 2): _c("FAIL"),
             (2, 0): _c("PASS", True), (2, 1): _c("PASS", True), (2, 2): _c("PASS", True)}
    assert unsafe((3, 3), known) == [(0, 1), (1, 1)]          # both touch the FAIL at (1, 2), (0, 1) diagonally
    known[(1, 2)] = _c("PASS", True)
    assert unsafe((3, 3), known) == []
    known[(1, 2)] = {"analysed": False, "between": "FAIL"}     # two inferred regions meeting: an edge too
    assert (1, 2) in unsafe((3, 3), known)
    cells = [(i, j) for i in range(10) for j in range(10)]
    sample = audit_sample(cells, 7)
    assert len(sample) == 10 and sample == audit_sample(cells, 7) and sample == sorted(sample)
    assert audit_sample([(1, 1)], 0) == [(1, 1)] and audit_sample([], 0) == []


def _cell(i, verdict="PASS", robust=True, shear=None, mass=1000.0, failed=0, analysed=True):
    return {"index": [i], "values": {"x": float(i)}, "labels": {"x": f"{i} m"}, "verdict": verdict,
            "robust": robust if verdict == "PASS" else None, "analysed": analysed,
            "draws": {"n": 3 if failed else 10, "failed": failed}, "demand": shear,
            "material": mass, "acmr": None, "acmr_required": None, "n_unacceptable": 0,
            "n_ground_motions": 11, "allowed_unacceptable": 1,
            "robustness": "robust: …" if robust else "not robust: fails in 1 of 3 draws"}


def test_the_recommendation_is_a_robust_pass_whenever_one_exists():
    cells = [_cell(0, mass=500.0, robust=False, failed=1), _cell(1, mass=800.0), _cell(2, mass=900.0),
             _cell(3, "FAIL", mass=100.0)]
    rec = recommended(cells, prefer="material")
    assert rec["index"] == [1] and rec["robust"] is True and "fragile_candidates" not in rec
    assert "chosen over its neighbours" in rec["reason"] and "0 m: PASS (not robust" in rec["reason"]
    assert "2 m: PASS (robust), more material" in rec["reason"]
    # no robust PASS: the best fragile one, said so, with the fragile candidates named
    cells = [_cell(0, robust=False, failed=1, mass=700.0), _cell(1, robust=False, failed=1, mass=600.0),
             _cell(2, "FAIL")]
    rec = recommended(cells)
    assert rec["robust"] is False and rec["index"] == [1]
    assert [c["index"] for c in rec["fragile_candidates"]] == [[1], [0]]
    assert rec["no_robust_pass"].startswith("no variant passes robustly")
    # a cell that was not analysed is never recommended
    assert recommended([_cell(0, analysed=False, mass=1.0), _cell(1, mass=2.0)])["index"] == [1]


def test_prefer_shear_or_material():
    cells = [_cell(0, shear=0.30, mass=500.0), _cell(1, shear=0.20, mass=900.0)]
    assert recommended(cells)["index"] == [1] and recommended(cells)["prefer"] == "shear"
    assert recommended(cells, prefer="material")["index"] == [0]


def test_words_of_a_cell_and_the_margin_rule():
    assert verdict_words({**_cell(0), **robustness({"n": 10, "failed": 0, "size": 10})}) == "PASS (robust)"
    fragile = {**_cell(0), **robustness({"n": 3, "failed": 1, "size": 10, "first_failure": "c_r − 2 %: 2 of 11"})}
    assert verdict_words(fragile) == "PASS (not robust: fails in 1 of 3 draws)"
    assert verdict_words({"analysed": False, "verdict": None}) == "not analysed"
    assert verdict_words(_cell(0, "FAIL")) == "FAIL"
    # an ACMR within the scans' 1 % (+ 0.1 % amplitude) of its requirement is not a robust PASS
    assert margin_undecided({"acmr": 1.97, "acmr_required": 1.96}, 0.01)
    assert margin_undecided({"acmr": 1.99, "acmr_required": 1.96}, 0.01) is None
    assert margin_undecided({"acmr": 1.5, "acmr_required": 1.96}, 0.01) is None    # informative (binomial rule)
    assert margin_undecided({"acmr": None, "acmr_required": None}, 0.01) is None


@pytest.mark.parametrize("change, problem", [({"robust": "yes"}, "robust"), ({"robust": None}, "robust"),
                                             ({"draws": {"n": -1, "failed": 0}}, "draws"),
                                             ({"analysed": False}, "not an analysed")])
def test_a_stored_cell_with_bad_robustness_is_analysed_again(change, problem):
    cell = {"verdict": "PASS", "reason": "PASS", "analyses": 3, "decided_at_design_level": False,
            "robust": True, "draws": {"n": 10, "failed": 0}, "analysed": True}
    from rockdesign.design_space.store import FORMAT
    assert shape_problem({"format": FORMAT, "digest": "d", "cell": cell}, "d") is None
    assert problem in shape_problem({"format": FORMAT, "digest": "d", "cell": {**cell, **change}}, "d")


def _tcell(i, mass, flip=2.0, robust=True, verdict="PASS"):
    c = _cell(i, verdict=verdict, robust=robust, mass=mass)
    c["values"] = {"podium.width": 0.3 + 0.1 * i}
    c["labels"] = {"podium.width": f"{0.3 + 0.1 * i:.2g} m"}
    c["flip_margin"] = flip
    return c


def _with_tolerance(cells, fails_at, prefer="material"):
    """with_tolerance over a one-key chart whose neighbour checks are stand-ins: a neighbour fails when its width
    lies in ``fails_at`` (a set of rounded widths)."""
    import tomllib

    from rockdesign.design_space.recommend import with_tolerance
    from rockdesign.design_space.tolerance import tolerances
    raw = tomllib.loads(open("examples/podium_flat.toml", encoding="utf-8").read())
    from rockdesign.design_space.variants import parse_vary
    variables = [parse_vary("podium.width=0.3m:0.6m:4", raw)]
    tols, _ = tolerances(variables, None, raw, file="p.toml")
    asked = []

    def run(jobs):
        out = {}
        for name, variant in jobs:
            w = round(variant.values["podium.width"], 4)
            asked.append(w)
            out[name] = {"values": variant.values, "labels": variant.labels, "reason": "stand-in", "analyses": 1,
                         "verdict": "FAIL" if w in fails_at else "PASS", "n_unacceptable": 2 if w in fails_at else 0,
                         "acmr": None, "flip_margin": None}
        return out
    rec = recommended(cells, prefer=prefer)
    return with_tolerance(rec, cells, run, variables, tols, raw, "p.toml", prefer=prefer), asked


def test_the_recommendation_is_the_preferred_robust_pass_that_survives_its_tolerance():
    cells = [_tcell(0, 100.0), _tcell(1, 200.0), _tcell(2, 300.0), _tcell(3, 50.0, verdict="FAIL")]
    rec, asked = _with_tolerance(cells, set())
    assert rec["index"] == [0] and rec["tolerance_robust"] and asked == [0.297, 0.303]
    assert [n["side"] for n in rec["neighbourhood"]] == ["−", "+"]
    assert "tolerance: passes at each of its 2 tolerance neighbours" in rec["reason"]
    # 0.3 m fails at 0.297 m: the next by material, said so; its neighbours checked one candidate at a time
    rec, asked = _with_tolerance(cells, {0.297})
    assert rec["index"] == [1] and rec["tolerance_robust"] and asked == [0.297, 0.303, 0.396, 0.404]
    assert "survives its construction tolerance" in rec["reason"]
    assert "not surviving their tolerance: podium.width = 0.3 m" in rec["reason"]
    # a flip margin at or below 1 is tried last, whatever its material
    cells[0]["flip_margin"] = 0.95
    rec, asked = _with_tolerance(cells, set())
    assert rec["index"] == [1] and asked[:2] == [0.396, 0.404]


def test_no_robust_pass_survives_its_tolerance_is_said_with_the_nearest_candidates():
    cells = [_tcell(0, 100.0, flip=1.1), _tcell(1, 200.0, flip=1.4), _tcell(2, 300.0, flip=1.2)]
    rec, _ = _with_tolerance(cells, {0.297, 0.303, 0.404, 0.495, 0.505})
    assert rec["tolerance_robust"] is False and rec["no_tolerance_robust_pass"] is True
    # nearest: fewest failing neighbours (0.4 m: one of two), then the largest flip margin
    assert rec["index"] == [1]
    assert [c["index"] for c in rec["candidates"]] == [[1], [2], [0]]
    assert [c["neighbours_failed"] for c in rec["candidates"]] == [1, 2, 2]      # (0.5 m: flip 1.2 before 1.1)
    assert rec["no_tolerance_robust"].startswith("no robust PASS survives its construction tolerance")
    assert "podium.width = 0.4 m (flip margin 1.4, fails at 1 of 2 neighbours)" in rec["no_tolerance_robust"]
