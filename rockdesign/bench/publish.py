"""Publish a bench run into the documentation: figures, docs/stability.md, the "latest numbers" blocks.

``rockdesign bench -o DIR --docs docs`` calls :func:`publish_docs`: it copies the figures into
``docs/figures/``, writes ``docs/stability.md`` from the run, and replaces the text between
``<!-- bench:begin -->`` and ``<!-- bench:end -->`` in ``docs/workprecision.md`` and
``benchmarks/README.md`` (when they carry the markers) with the latest table, date and machine.
"""
from __future__ import annotations

import math
import shutil
from pathlib import Path

from .stability import stability_markdown
from .timing import host_description

BEGIN = "<!-- bench:begin -->"
END = "<!-- bench:end -->"


def _value(v) -> str:
    return ("yes" if v else "no") if isinstance(v, bool) else format(v, ".4g")


def _fmt(x, spec: str) -> str:
    return "–" if x is None or (isinstance(x, float) and not math.isfinite(x)) else format(x, spec)


def _best_scipy(prob: dict, target: float) -> tuple[str | None, float | None]:
    ratios = prob["summary"][f"ratio_to_rockdesign_{target:.0e}"]
    best = min(((k, v) for k, v in ratios.items() if k.startswith("scipy") and v is not None),
               key=lambda kv: kv[1], default=(None, None))
    return best


def _ours_rtol(study: dict) -> float:
    """The sweep tolerance closest to the engine default 1e-10 (the one the tables quote)."""
    return min(study["tolerances"], key=lambda t: abs(math.log10(t) + 10.0))


def latest_numbers_markdown(study: dict, figure_prefix: str = "figures/") -> str:
    """The "latest numbers" block: machine, per-problem highlights table, speed benchmarks, charts."""
    m = study["machine"]
    mode = "quick" if study.get("quick") else "full"
    lines = [f"Latest run ({mode}): **{m['date']}** on {host_description(m)} — {m['cpu']}, {m['nproc']} cores, load "
             f"average {m['load_average']} at the start; Python {m['python']}, numpy {m['numpy']}, scipy "
             f"{m['scipy']}, numba {m['numba']}. Tolerances {', '.join(f'{t:.0e}' for t in study['tolerances'])} "
             f"(atol = {study['atol_over_rtol']:g}·rtol); times are medians of up to "
             f"{study['timing']['max_repeats']} runs after a warm-up run.", "",
             f"| problem | system | rockdesign at rtol {_ours_rtol(study):.0e}: ms | max \\|Δθ\\| [rad] | "
             "reference bound [rad] | "
             "cheapest scipy at ≤ 1e-6 rad (× rockdesign) | cheapest scipy at ≤ 1e-9 rad (× rockdesign) | "
             "scipy crashes |",
             "|---|---|---:|---:|---:|---|---|---:|"]
    for prob in study["problems"]:
        ours = next((x for x in prob["methods"] if x["name"] == "rockdesign"), None)
        if not ours or not ours["points"]:
            continue
        pt = min(ours["points"], key=lambda q: abs(math.log10(q["tolerance"]) - math.log10(_ours_rtol(study))))
        cells = []
        for target in (1e-6, 1e-9):
            name, ratio = _best_scipy(prob, target)
            cells.append(f"{name.split()[-1]} ({ratio:.0f}×)" if name else "none reaches it")
        crashes = sum(len(x["failures"]) for x in prob["methods"])
        bound = prob["reference"]["error_bound"].get("theta")
        lines.append(f"| {prob['name']} | {prob['system']} | {pt['seconds'] * 1e3:.2f} | {pt['error_theta']:.1e} | "
                     f"{_fmt(bound, '.0e')} | {cells[0]} | {cells[1]} | {crashes} |")
    lines.append("")
    speed = study.get("speed_benchmarks") or []
    if speed:
        lines += ["Speed benchmarks found in `benchmarks/results/`:", ""]
        for item in speed:
            heads = ", ".join(f"`{k.removeprefix('summary.')}` = {_value(v)}"
                              for k, v in list(item.get("headline", {}).items())[:12])
            lines.append(f"- **{item['name']}** ({item.get('date') or 'undated'}): {heads or item.get('error', '')}")
        lines.append("")
    lines += [f"![work-precision, exact equations]({figure_prefix}wp_overview_exact.png)", "",
              f"![work-precision, linearized equations]({figure_prefix}wp_overview_linear.png)", ""]
    return "\n".join(lines)


def replace_block(path: Path, text: str) -> bool:
    """Replace the text between the bench markers of ``path``; False if the file or markers are missing."""
    path = Path(path)
    if not path.is_file():
        return False
    content = path.read_text()
    if BEGIN not in content or END not in content:
        return False
    head, rest = content.split(BEGIN, 1)
    _, tail = rest.split(END, 1)
    path.write_text(f"{head}{BEGIN}\n{text}\n{END}{tail}")
    return True


def publish_docs(study: dict, bench_dir: Path, docs_dir: Path, readmes=()) -> list[Path]:
    """Copy figures, write stability.md and update the marked blocks; returns the files written.

    Args:
        study: the bench.json object of the run.
        bench_dir: the run's output folder (where its figures are).
        docs_dir: the documentation folder (``docs``): figures go to ``docs_dir/figures``.
        readmes: other Markdown files whose bench block is updated (figure links relative to them).
    """
    bench_dir, docs_dir = Path(bench_dir), Path(docs_dir)
    fig_dir = docs_dir / "figures"
    fig_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for src in sorted(bench_dir.glob("wp_*")) + sorted(bench_dir.glob("stability_*")):
        if src.suffix in (".png", ".svg"):
            dst = fig_dir / src.name
            shutil.copyfile(src, dst)
            written.append(dst)
    if study.get("stability"):
        md = docs_dir / "stability.md"
        md.write_text(stability_markdown(study["stability"], figure_prefix="figures/", machine=study["machine"]))
        written.append(md)
    wp = docs_dir / "workprecision.md"
    if replace_block(wp, latest_numbers_markdown(study, "figures/")):
        written.append(wp)
    for readme in readmes:
        readme = Path(readme)
        prefix = Path(*([".."] * len(readme.resolve().parent.relative_to(docs_dir.resolve().parent).parts)),
                      docs_dir.name, "figures").as_posix() + "/"
        if replace_block(readme, latest_numbers_markdown(study, prefix)):
            written.append(readme)
    return written
