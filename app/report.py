#!/usr/bin/python3
"""PNG plots of a mesocrack run.

    /usr/bin/python3 app/report.py OUT.h5 [--out-dir DIR]

Writes <stem>_history.png, <stem>_xy.png (if the scene asks for x-y plots),
<stem>_energy.png (if energy series exist), <stem>_specimen.png (2D) or
<stem>_slice.png (3D), <stem>_cracks.png (if the run logged cracks),
<stem>_cells.png (rigid cells: the crack pattern of their damaged facets),
<stem>_fibres.png (rigid cells with fibres: the cracks with the fibres bridging
them, and the load against displacement) and,
for a pull test ([pullout]), <stem>_pullout.png and <stem>_pullout_cracks.png
next to OUT.h5 (or into DIR) and prints their paths. The figures are drawn by
report_plots.py (time series), report_specimen.py (specimen and cracks) and
report_pullout.py (pull tests), report_fibres.py (fibres).
The file is opened read-only and without HDF5 file locking, so a run that is
still writing can be looked at.
"""
import argparse
import json
import tomllib
import os
import sys
from collections import OrderedDict

import h5py
import numpy as np

# The figures' modules stand beside this script, in the source tree (app/) as installed (share/mesocrack):
# found there whichever folder Python was started from.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_plots import ReportError, plot_energy, plot_history, plot_xy  # noqa: E402
from report_specimen import plot_cells, plot_cracks, plot_cracks_at_peak, plot_specimen  # noqa: E402
from report_pullout import plot_pullout  # noqa: E402
from report_fibres import plot_fibres  # noqa: E402

FORMAT = "mesocrack-1"


# ---------------------------------------------------------------- reading


def text(value):
    """Attribute or scalar dataset as str: the engine writes fixed-length UTF-8 (bytes in h5py)."""
    if isinstance(value, np.ndarray):
        value = value.item() if value.size == 1 else value.tolist()
    if isinstance(value, (bytes, np.bytes_)):
        value = value.decode("utf-8", "replace")
    return str(value).rstrip("\0")


def open_run(path):
    if not os.path.exists(path):
        raise ReportError("no such file")
    if not os.path.isfile(path):
        raise ReportError("not a regular file")
    try:
        try:  # locking=False: the engine may hold the file open for writing.
            f = h5py.File(path, "r", locking=False)
        except TypeError:  # h5py older than 3.5 has no locking argument
            f = h5py.File(path, "r")
    except OSError as e:
        raise ReportError(f"cannot open as HDF5 ({str(e).splitlines()[0]})") from None
    fmt = text(f.attrs["format"]) if "format" in f.attrs else None
    if fmt != FORMAT:
        f.close()
        what = "no 'format' attribute" if fmt is None else f"format is '{fmt}', expected '{FORMAT}'"
        raise ReportError(f"not a mesocrack file ({what})")
    return f


def leading(d, n=None):
    """The first n rows of a table (all of them without n) that a killed run left readable: read chunk by chunk, up
    to the first chunk its unfinished flush pointed to before the chunk was in the file."""
    n = d.shape[0] if n is None else min(n, d.shape[0])
    step = d.chunks[0] if d.chunks else max(n, 1)
    parts = []
    for first in range(0, n, step):
        try:
            parts.append(np.asarray(d[first:min(first + step, n)]))
        except OSError:
            break
    return np.concatenate(parts) if parts else np.asarray(d[:0])


def read_run(f):
    """Everything the plots need, as numpy arrays (the file is closed afterwards)."""
    run = {"dimension": int(f.attrs.get("dimension", 2)),
           "scene_file": text(f.attrs.get("scene_file", "")),
           "history": OrderedDict(), "xy_plots": [], "specimen": None, "frame": None,
           "scene_text": text(f["scene"][()]) if isinstance(f.get("scene"), h5py.Dataset) else ""}
    if run["dimension"] not in (2, 3):
        raise ReportError(f"dimension attribute is {run['dimension']}, expected 2 or 3")
    D = run["dimension"]

    hist = f.get("history")
    if isinstance(hist, h5py.Group):
        datasets = {k: d for k, d in hist.items() if isinstance(d, h5py.Dataset) and d.ndim == 1}
        series = {k: leading(d) for k, d in datasets.items()}
        # A running engine appends series one by one: cut all to the common length.
        S = min((len(y) for y in series.values()), default=0)
        if "time" in series and S > 0:
            for name, d in datasets.items():
                run["history"][name] = {"data": np.asarray(series[name][:S], dtype=float),
                                        "unit": text(d.attrs.get("unit", "")),
                                        "label": text(d.attrs["label"]) if "label" in d.attrs else None}
        pairs = text(hist.attrs.get("xy_plots", ""))
        run["xy_plots"] = [tuple(p.split(":", 1)) for p in pairs.split(";") if ":" in p]

    spec = f.get("specimen")
    if isinstance(spec, h5py.Group) and "x" in spec and "radius" in spec:
        x = np.asarray(spec["x"], dtype=float).reshape(-1, D)
        r = np.asarray(spec["radius"], dtype=float)
        phase = np.asarray(spec["phase"], dtype=int) if "phase" in spec else np.zeros(len(r), int)
        names = text(spec.attrs.get("phase_names", "")).split(",") if "phase_names" in spec.attrs else []
        if len(x) == len(r) == len(phase):
            run["specimen"] = {"x": x, "radius": r, "phase": phase, "phase_names": [n.strip() for n in names],
                               "outlines": read_outlines(spec)}

    run["cracks"] = read_cracks(f, D, run["specimen"])
    run["cells"] = read_cells(f, run)

    frames = f.get("frames")
    if isinstance(frames, h5py.Group) and "time" in frames and "x" in frames:
        rows = [frames[k].shape[0] for k in ("time", "x", "force") if k in frames]
        F = min(rows)
        # Only the last complete row is read (50k particles x many frames is large); in a killed run's file, the
        # last that reads.
        for k in range(F - 1, -1, -1):
            try:
                run["frame"] = {"index": k, "count": F, "time": float(frames["time"][k]),
                                "step": int(frames["step"][k]) if "step" in frames else None,
                                "x": np.asarray(frames["x"][k], dtype=float).reshape(-1, D),
                                "force": (np.asarray(frames["force"][k], dtype=float).reshape(-1, D)
                                          if "force" in frames else None),
                                "cell_corner": (np.asarray(frames["cell_corner"][k], dtype=float).reshape(-1, D)
                                                if "cell_corner" in frames and frames["cell_corner"].shape[0] > k
                                                else None),
                                "contacts": read_contacts(f, k, D)}
                break
            except OSError:
                continue
    return run


def read_summary(path):
    """The summary JSON `mesocrack report` passes (absent: the plots mark nothing from it)."""
    if not path:
        return {}
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return {}


def uniaxial_pair(scene_text):
    """(axial strain, stress) of the scene's [uniaxial], the pair its stress-strain plot shows; None without."""
    try:
        u = tomllib.loads(scene_text).get("uniaxial", {})
    except tomllib.TOMLDecodeError:
        return None
    return (u["axial_strain"], u["stress"]) if "axial_strain" in u and "stress" in u else None


def read_outlines(spec):
    """Aggregate outlines in the picture plane (2D; 3D: the mid-plane section), or []."""
    if "outline_xy" not in spec or "outline_start" not in spec:
        return []
    xy = np.asarray(spec["outline_xy"], dtype=float).reshape(-1, 2)
    start = np.asarray(spec["outline_start"], dtype=int)
    return [xy[a:b] for a, b in zip(start[:-1], start[1:]) if b - a >= 3]


def load_peak(run):
    """Where the load the scene plots (the y of its first x-y plot) peaks: {series, unit, value, time}, or None."""
    h = run["history"]
    for _, y in run["xy_plots"][:1]:
        if y in h and "time" in h and len(h[y]["data"]) > 0:
            k = int(np.argmax(np.abs(h[y]["data"])))
            return {"series": y, "unit": h[y]["unit"], "value": float(h[y]["data"][k]),
                    "time": float(h["time"]["data"][k])}
    return None


def read_cells(f, run):
    """A specimen of rigid cells (None for particles): its corners, its facets and the cells' faces as polygons over
    them (README, "Output", /specimen/cells), and, when frames hold the facets' damage, the contact facets' damage in
    the last frame and, when the scene plots a load that peaked before it, in the last frame by the peak."""
    g, frames = f.get("specimen/cells"), f.get("frames")
    if not isinstance(g, h5py.Group):
        return None
    D = run["dimension"]
    cells = {"corner": np.asarray(g["corner"], dtype=float).reshape(-1, D),
             "contacts": int(g.attrs["contacts"]), "frames": []}
    for k in ("facet_start", "facet_corner", "face_start", "face_corner", "face_cell", "facet_a", "facet_b"):
        if k in g:
            cells[k] = np.asarray(g[k], dtype=np.int64)
    if not isinstance(frames, h5py.Group) or not all(k in frames for k in ("time", "step", "damage")):
        return cells
    F = min(frames[k].shape[0] for k in ("time", "step", "damage"))
    if F == 0:
        return cells
    times = np.asarray(frames["time"][:F], dtype=float)
    picks = [(F - 1, None)]
    peak = load_peak(run)
    if peak is not None:
        by_peak = int(np.searchsorted(times, peak["time"], side="right")) - 1
        if 0 <= by_peak < F - 1:
            picks.insert(0, (by_peak, peak))
    fibres = f.get("specimen/fibres")
    has_fibres = isinstance(fibres, h5py.Group) and "fibre_state" in frames and frames["fibre_state"].shape[0] >= F
    if has_fibres:
        point = np.asarray(fibres["point"], dtype=float)
        start, line = np.asarray(fibres["line_start"], dtype=np.int64), np.asarray(fibres["line_point"], dtype=np.int64)
        cells["fibres"] = {"a": point[line[start[:-1]]], "b": point[line[start[1:] - 1]],
                           "family": np.asarray(fibres["family"], dtype=np.int64)}
    for k, p in picks:
        frame = {"index": k, "count": F, "time": float(times[k]), "step": int(frames["step"][k]),
                 "damage": np.asarray(frames["damage"][k], dtype=float), "peak": p}
        if has_fibres:
            frame["fibre_state"] = np.asarray(frames["fibre_state"][k], dtype=float).astype(np.int64)
            frame["fibre_force"] = np.asarray(frames["fibre_force"][k], dtype=float)
        cells["frames"].append(frame)
    return cells


def read_contacts(f, k, D):
    """Frame k's contacts between bodies (README, "Output", /contacts), or None: rows frame_first[k] on, frame_count[k]
    of them (without frame_count: up to the next frame's first row, the last frame's to the end of the tables)."""
    g = f.get("contacts")
    names = ("pair", "normal_force", "shear_force", "bonded", "branch")
    if not isinstance(g, h5py.Group) or "frame_first" not in g or not all(n in g for n in names):
        return None
    first = g["frame_first"]
    if k >= first.shape[0]:
        return None
    rows = min(g[n].shape[0] for n in names)
    a = int(first[k])
    if "frame_count" in g and k < g["frame_count"].shape[0]:
        b = a + int(g["frame_count"][k])
    else:
        b = int(first[k + 1]) if k + 1 < first.shape[0] else rows
    a, b = max(0, min(a, rows)), max(0, min(b, rows))
    b = max(a, b)
    return {"pair": np.asarray(g["pair"][a:b], dtype=np.int64).reshape(-1, 2),
            "normal_force": np.asarray(g["normal_force"][a:b], dtype=float),
            "shear_force": np.asarray(g["shear_force"][a:b], dtype=float),
            "bonded": np.asarray(g["bonded"][a:b], dtype=np.int64),
            "branch": np.asarray(g["branch"][a:b], dtype=float).reshape(-1, D),
            "unit": text(g["normal_force"].attrs.get("unit", "N"))}


def read_cracks(f, D, spec):
    """The crack log (None without one): positions, normals, mode (1 tensile, 2 shear), kind (0 break,
    1 first yield), phase pair, time, the two bodies' rows of the specimen (-1 for an id it does not hold) and the
    crack's length in the plane (2·min(R_a, R_b))."""
    g = f.get("cracks")
    if not isinstance(g, h5py.Group) or "position" not in g:
        return None
    t = {k: leading(g[k]) for k in ("position", "normal", "mode", "kind", "phase_a", "phase_b", "id_a", "id_b",
                                    "time")}
    n = min(len(v) for v in t.values())
    c = {"position": np.asarray(t["position"][:n], dtype=float).reshape(-1, D),
         "normal": np.asarray(t["normal"][:n], dtype=float).reshape(-1, D),
         "mode": np.asarray(t["mode"][:n], dtype=int), "kind": np.asarray(t["kind"][:n], dtype=int),
         "phase_a": np.asarray(t["phase_a"][:n], dtype=int), "phase_b": np.asarray(t["phase_b"][:n], dtype=int),
         "time": np.asarray(t["time"][:n], dtype=float),
         "size": np.zeros(n), "row_a": np.full(n, -1), "row_b": np.full(n, -1)}
    if spec is not None and "id" in f["specimen"]:
        ids = np.asarray(f["specimen"]["id"], dtype=np.int64)
        order = np.argsort(ids)

        def row_of(q):  # the specimen's row of each id, -1 for an id it does not hold
            at = np.minimum(np.searchsorted(ids, q, sorter=order), len(ids) - 1)
            return np.where(ids[order[at]] == q, order[at], -1) if len(ids) else np.full(len(q), -1)

        c["row_a"], c["row_b"] = (row_of(np.asarray(t[k][:n], dtype=np.int64)) for k in ("id_a", "id_b"))
        known = (c["row_a"] >= 0) & (c["row_b"] >= 0)
        c["size"][known] = 2 * np.minimum(spec["radius"][c["row_a"][known]], spec["radius"][c["row_b"][known]])
    return c


# ---------------------------------------------------------------- main


def main(argv=None):
    parser = argparse.ArgumentParser(description="PNG plots of a mesocrack run (HDF5 output file).")
    parser.add_argument("file", help="mesocrack output file (.h5)")
    parser.add_argument("--out-dir", help="directory for the PNGs (default: next to the file)")
    parser.add_argument("--summary", help="the run's `mesocrack summary` JSON, for the values the plots mark")
    args = parser.parse_args(argv)
    try:
        with open_run(args.file) as f:
            try:
                run = read_run(f)
            except (OSError, KeyError, ValueError) as e:  # damaged or half-written file
                raise ReportError(f"cannot read ({str(e).splitlines()[0] if str(e) else type(e).__name__})")
        run["summary"] = read_summary(args.summary)
        run["uniaxial_pair"] = uniaxial_pair(run["scene_text"])
        out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.file))
        try:
            os.makedirs(out_dir, exist_ok=True)
        except OSError as e:
            raise ReportError(f"cannot create output directory {out_dir}: {e.strerror}")
        stem = os.path.splitext(os.path.basename(args.file))[0]
        for plot in (plot_history, plot_xy, plot_energy, plot_specimen, plot_cracks, plot_cracks_at_peak, plot_cells,
                     plot_fibres, plot_pullout):
            for path in plot(run, stem, out_dir):
                print(path, flush=True)
    except ReportError as e:  # every ReportError is about a file: exit 3, as `mesocrack` does for file errors
        print(f"error: report: {args.file}: {e}", file=sys.stderr)
        return 3
    return 0


if __name__ == "__main__":
    sys.exit(main())
