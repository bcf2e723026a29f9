"""The stored variants of a design grid (``DIR/variants/<digest>.json``): what makes a run resumable (SPEC §15).

A stored variant is reused only when everything that decides its result is the same, so the digest that
names its file covers:

- the variant's own project text (every key, the varied values written in);
- the content of what its check analyses: the records of its excitation as read and scaled (the suite
  files and their records, a ``records_dir``'s AT2 files, the scale factors) — the same project text next
  to another suite file, or with another records folder, is another variant;
- the tool: rockdesign's version, the kernels' sources (:func:`rockdesign.kernel_cache.sources_digest`),
  and the numerical libraries' versions.

The file also carries its digest and the cell's shape is checked when read: a file that cannot be read,
is truncated, or holds something else (another version's layout, a hand-edited value) is not used — the
variant is analysed again and the caller is told why (``warn``), never a traceback.  The cell's place in
the grid (``index``, ``values``, ``labels``, ``notes``) is not taken from the file: the grid that reads it
writes the variant's place in *its* grid.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import struct
import threading
from pathlib import Path

from .. import __version__
from ..jsonable import json_ready

FORMAT = 4
"""The layout of a stored variant (a file of another layout is analysed again)."""

VERDICTS = ("PASS", "FAIL", "INVALID", "ERROR")
NUMBERS = ("acmr", "acmr_required", "p_collapse_design", "target_p_collapse", "superstructure_shear_p84",
           "superstructure_drift_p84", "median_theta_max_over_theta_c", "material", "demand", "flip_margin")
"""The shared numbers of a stored cell (finite or None); a kind's own numbers are checked as numbers too (a stored
float must be finite)."""
COUNTS = ("n_unacceptable", "allowed_unacceptable", "n_ground_motions")
PLACE = ("index", "values", "labels", "notes")
"""The cell's place in a grid: written by the grid that reads the variant, not stored."""


def content_digest(obj) -> str:
    """A digest of the content of ``obj``: numbers (exactly), strings, numpy arrays (dtype, shape, bytes),
    sequences, mappings, dataclasses and plain objects (their attributes but ``file``, the name error messages
    quote, e.g. "p.toml [podium.width = 0.4 m]"), recursively; functions and modules by name.  Two objects with the same content have the same digest in any process."""
    h = hashlib.sha256()
    _feed(h, obj, set())
    return h.hexdigest()


def _feed(h, obj, seen: set) -> None:
    import numpy as np
    if obj is None or isinstance(obj, bool):
        h.update(f"<{obj!r}>".encode())
    elif isinstance(obj, int):
        h.update(f"i{obj};".encode())
    elif isinstance(obj, float):
        h.update(b"f" + struct.pack("<d", obj))
    elif isinstance(obj, str):
        data = obj.encode("utf-8", "surrogatepass")
        h.update(f"s{len(data)}:".encode() + data)
    elif isinstance(obj, bytes):
        h.update(f"b{len(obj)}:".encode() + obj)
    elif isinstance(obj, Path):
        _feed(h, ("path", str(obj)), seen)
    elif isinstance(obj, np.ndarray):
        a = np.ascontiguousarray(obj)
        h.update(f"a{a.dtype.str}{a.shape}:".encode())
        h.update(a.tobytes() if a.dtype != object else repr(a.tolist()).encode())
    elif isinstance(obj, np.generic):
        _feed(h, obj.item(), seen)
    elif isinstance(obj, (list, tuple)):
        h.update(f"l{len(obj)}[".encode())
        for x in obj:
            _feed(h, x, seen)
        h.update(b"]")
    elif isinstance(obj, (set, frozenset)):
        _feed(h, ("set", sorted(repr(x) for x in obj)), seen)
    elif isinstance(obj, dict):
        h.update(f"d{len(obj)}{{".encode())
        for k in sorted(obj, key=repr):
            _feed(h, k, seen)
            _feed(h, obj[k], seen)
        h.update(b"}")
    elif callable(obj) and hasattr(obj, "__qualname__"):
        h.update(f"c{getattr(obj, '__module__', '')}.{obj.__qualname__};".encode())
    else:
        if id(obj) in seen:          # a cycle: its content is already in the digest
            h.update(b"<cycle>")
            return
        seen.add(id(obj))
        h.update(f"o{type(obj).__module__}.{type(obj).__qualname__}(".encode())
        if dataclasses.is_dataclass(obj):
            state = {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)}
        elif hasattr(obj, "__dict__"):
            state = vars(obj)
        elif hasattr(obj, "__slots__"):
            state = {k: getattr(obj, k) for k in obj.__slots__ if hasattr(obj, k)}
        else:
            state = repr(obj)
        if isinstance(state, dict) and "file" in state:
            state = {k: v for k, v in state.items() if k != "file"}     # the name errors quote, not content
        _feed(h, state, seen)
        h.update(b")")


def tool_digest() -> str:
    """rockdesign's version, the kernels' sources and the numerical libraries' versions."""
    import numba
    import numpy

    from ..kernel_cache import sources_digest
    return f"{__version__}\n{sources_digest()}\nnumpy {numpy.__version__}\nnumba {numba.__version__}"


def variant_digest(kind: str, project_text: str, records_digest: str, tool: str) -> str:
    """The name of a stored variant: the kind, the variant's project text, the content of its records and
    the tool (see module docstring)."""
    text = f"format {FORMAT}\n{tool}\nkind {kind}\nrecords {records_digest}\n{project_text}"
    return hashlib.sha256(text.encode("utf-8", "surrogatepass")).hexdigest()[:24]


class VariantStore:
    """The folder of stored variants; ``warn(text)`` is told about a stored file that is not used."""

    def __init__(self, folder, warn=None):
        self.folder = Path(folder)
        self.warn = warn or (lambda text: None)

    def path(self, digest: str) -> Path:
        return self.folder / f"{digest}.json"

    def load(self, digest: str) -> dict | None:
        """The stored cell of ``digest`` (without its place in a grid), or None: not stored, or stored in a
        file that cannot be used (:meth:`warn` says why; the variant is analysed again)."""
        path = self.path(digest)
        if not path.exists() and not path.is_symlink():
            return None
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
            problem = shape_problem(data, digest)
        except (OSError, UnicodeDecodeError, ValueError) as exc:
            problem = f"unreadable ({type(exc).__name__}: {exc})"
        if problem:
            self.warn(f"stored variant '{path}' not used ({problem}): analysed again")
            return None
        cell = dict(data["cell"])
        for k in PLACE:
            cell.pop(k, None)
        return cell

    def save(self, digest: str, cell: dict) -> None:
        """Store ``cell`` atomically (an interruption leaves no half-written file)."""
        self.folder.mkdir(parents=True, exist_ok=True)
        path = self.path(digest)
        body = json_ready({k: v for k, v in cell.items() if k not in PLACE and k != "resumed"})
        tmp = path.with_suffix(f".{threading.get_ident()}.tmp")
        tmp.write_text(json.dumps({"format": FORMAT, "digest": digest, "cell": body}, default=_json_default,
                                  allow_nan=False), encoding="utf-8")
        tmp.replace(path)


def shape_problem(data, digest: str) -> str | None:
    """What is wrong with a stored variant's content (None: it can be used)."""
    if not isinstance(data, dict) or not isinstance(data.get("cell"), dict):
        return "not a stored variant"
    if data.get("format") != FORMAT:
        return f"layout {data.get('format')!r}, this version writes {FORMAT}"
    if data.get("digest") != digest:
        return "its digest does not match its name"
    cell = data["cell"]
    if cell.get("verdict") not in VERDICTS:
        return f"verdict {cell.get('verdict')!r}"
    if not isinstance(cell.get("reason"), str):
        return "no reason"
    for k in NUMBERS:
        v = cell.get(k, 0.0)
        if v is not None and (isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v)):
            return f"{k} = {v!r}"
    for k, v in cell.items():                       # the kind's own numbers (StructureKind.design_columns)
        if isinstance(v, float) and not math.isfinite(v):
            return f"{k} = {v!r}"
    for k in COUNTS + ("analyses", "analyses_saved", "n_failed_analyses"):
        v = cell.get(k, 0)
        if v is not None and (isinstance(v, bool) or not isinstance(v, int) or v < 0):
            return f"{k} = {v!r}"
    if not isinstance(cell.get("analyses"), int) or not isinstance(cell.get("decided_at_design_level"), bool):
        return "missing counts"
    robust, draws = cell.get("robust", "missing"), cell.get("draws")
    verdict_only = str(cell.get("robustness") or "").startswith("not evaluated")    # a tolerance neighbour
    if robust not in (True, False, None) or (robust is None) != (cell["verdict"] != "PASS" or verdict_only):
        return f"robust = {robust!r} for {cell['verdict']}"
    if not isinstance(draws, dict) or any(isinstance(draws.get(k), bool) or not isinstance(draws.get(k), int)
                                          or draws[k] < 0 for k in ("n", "failed")):
        return f"draws = {draws!r}"
    if cell.get("analysed") is not True:
        return "not an analysed variant"
    return None


def _json_default(x):
    if hasattr(x, "item"):           # numpy scalars: ints stay ints
        v = x.item()
        return v if not isinstance(v, float) or math.isfinite(v) else None
    try:
        return float(x)
    except (TypeError, ValueError):
        raise TypeError(f"not JSON: {type(x).__name__}") from None
