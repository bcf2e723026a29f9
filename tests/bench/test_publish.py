"""Publishing a bench run into the docs, and the summary of benchmarks/results/*.json."""
from __future__ import annotations

import json

from rockdesign.bench.publish import BEGIN, END, latest_numbers_markdown, publish_docs, replace_block
from rockdesign.bench.speed import speed_summary, summarise_file


def _study():
    pts = [{"tolerance": 1e-6, "seconds": 0.001, "error_theta": 1e-7, "error_theta_max": 0.0,
            "error_impact_times": 1e-7},
           {"tolerance": 1e-10, "seconds": 0.002, "error_theta": 1e-11, "error_theta_max": 0.0,
            "error_impact_times": 1e-11}]
    scipy = [{"tolerance": 1e-10, "seconds": 0.2, "error_theta": 1e-11, "error_theta_max": 0.0,
              "error_impact_times": 1e-11}]
    prob = {"name": "ricker-anti", "system": "housner-block", "equations": "exact",
            "reference": {"kind": "converged", "error_bound": {"theta": 2e-12}},
            "methods": [{"name": "rockdesign", "family": "rockdesign", "points": pts, "failures": []},
                        {"name": "scipy DOP853", "family": "scipy", "points": scipy,
                         "failures": [{"tolerance": 1e-3, "error": "ValueError"}]}],
            "summary": {"ratio_to_rockdesign_1e-06": {"rockdesign": 1.0, "scipy DOP853": 200.0},
                        "ratio_to_rockdesign_1e-09": {"rockdesign": 1.0, "scipy DOP853": 100.0}}}
    machine = {"date": "2026-01-01T00:00:00", "uname": "Linux test", "cpu": "CPU", "nproc": 2,
               "load_average": [0.1, 0.1, 0.1], "python": "3.11", "numpy": "2", "scipy": "1.17", "numba": "0.6"}
    stability = [{"key": "zeno", "condition": "Zeno hang", "setup": "s", "engine": {"status": "completed"},
                  "engine_behaviour": "Ends it. More.", "seconds": 1.0,
                  "outcomes": [{"method": "rockdesign", "verdict": "ok", "detail": "d"},
                               {"method": "scipy DOP853", "verdict": "fails", "detail": "d"}]}]
    return {"machine": machine, "quick": True, "tolerances": [1e-6, 1e-10], "atol_over_rtol": 0.01,
            "timing": {"max_repeats": 3}, "problems": [prob], "stability": stability, "speed_benchmarks": []}


def test_latest_numbers_block():
    text = latest_numbers_markdown(_study())
    assert "2026-01-01" in text and "Linux test" in text
    assert "| ricker-anti | housner-block | 2.00 | 1.0e-11 | 2e-12 | DOP853 (200×) | DOP853 (100×) | 1 |" in text
    assert "figures/wp_overview_exact.png" in text


def test_replace_block_keeps_the_rest(tmp_path):
    f = tmp_path / "x.md"
    f.write_text(f"head\n{BEGIN}\nold\n{END}\ntail\n")
    assert replace_block(f, "new")
    assert f.read_text() == f"head\n{BEGIN}\nnew\n{END}\ntail\n"
    g = tmp_path / "y.md"
    g.write_text("no markers")
    assert not replace_block(g, "new") and g.read_text() == "no markers"


def test_publish_docs(tmp_path):
    bench, docs, other = tmp_path / "run", tmp_path / "docs", tmp_path / "benchmarks"
    for d in (bench, docs, other):
        d.mkdir()
    (bench / "wp_overview_exact.png").write_bytes(b"png")
    (bench / "stability_zeno.svg").write_bytes(b"svg")
    (docs / "workprecision.md").write_text(f"# WP\n{BEGIN}\n{END}\n")
    (other / "README.md").write_text(f"# B\n{BEGIN}\n{END}\n")
    written = publish_docs(_study(), bench, docs, readmes=[other / "README.md"])
    assert (docs / "figures" / "wp_overview_exact.png").read_bytes() == b"png"
    assert (docs / "figures" / "stability_zeno.svg").exists()
    md = (docs / "stability.md").read_text()
    assert "| Zeno hang [↓](#zeno) | ok | **fails** | Ends it. |" in md
    assert "](figures/stability_zeno.png)" in md
    assert "../docs/figures/wp_overview_exact.png" in (other / "README.md").read_text()
    assert len(written) == 5


def test_speed_summary_reads_every_result_file(tmp_path):
    (tmp_path / "engine.json").write_text(json.dumps({"date": "d", "machine": {"uname": "u"},
                                                      "summary": {"ratio_batch": 120.0, "goal_ratio_met_batch": False},
                                                      "single_record": [{"system": "block", "ratio": 250.0}]}))
    (tmp_path / "broken.json").write_text("{")
    items = {i["name"]: i for i in speed_summary(tmp_path)}
    assert items["engine"]["date"] == "d" and items["engine"]["machine"] == "u"
    assert items["engine"]["headline"]["summary.ratio_batch"] == 120.0
    assert items["engine"]["headline"]["single_record[0].ratio"] == 250.0
    assert "error" in items["broken"]
    assert speed_summary(tmp_path / "missing") == []
    assert summarise_file(tmp_path / "engine.json")["summary"]["ratio_batch"] == 120.0
