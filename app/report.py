#!/usr/bin/python3
"""PNG plots of a mesocrack run.

    /usr/bin/python3 app/report.py OUT.h5 [--out-dir DIR]

Writes <stem>_history.png, <stem>_xy.png (if the scene asks for x-y plots),
<stem>_energy.png (if energy series exist) and <stem>_specimen.png (2D) or
<stem>_slice.png (3D) next to OUT.h5 (or into DIR) and prints their paths.
The file is opened read-only and without HDF5 file locking, so a run that is
still writing can be looked at.
"""
import argparse
import math
import os
import re
import sys
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")  # headless: no display on compute nodes or CI
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import EllipseCollection, LineCollection, PolyCollection  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

FORMAT = "mesocrack-1"
# Units that read better with an SI prefix (MPa, mJ, µs); "-" and compound units are left alone.
SCALABLE_UNITS = {"Pa", "J", "N", "m", "s", "W", "m/s", "N/m", "N m"}
PREFIXES = [(1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, ""), (1e-3, "m"), (1e-6, "µ"), (1e-9, "n")]
# Trailing vector/tensor component of a series name: force_x, stress_xy, disp_z.
COMPONENT = re.compile(r"_(x|y|z|xx|yy|zz|xy|yx|xz|zx|yz|zy)$")


class ReportError(Exception):
    """An expected problem with the input: reported in one line, exit status 2."""


def text(value):
    """Attribute or scalar dataset as str: the engine writes fixed-length UTF-8 (bytes in h5py)."""
    if isinstance(value, np.ndarray):
        value = value.item() if value.size == 1 else value.tolist()
    if isinstance(value, (bytes, np.bytes_)):
        value = value.decode("utf-8", "replace")
    return str(value).rstrip("\0")


def si_scale(values, unit):
    """(factor, prefixed unit) such that values * factor mostly reads between 1 and 1000."""
    values = np.asarray(values, dtype=float)
    finite = np.abs(values[np.isfinite(values)])
    if unit not in SCALABLE_UNITS or finite.size == 0 or finite.max() == 0:
        return 1.0, unit
    peak = finite.max()
    for mult, prefix in PREFIXES:
        if peak >= mult:
            return 1.0 / mult, prefix + unit
    return 1.0 / PREFIXES[-1][0], PREFIXES[-1][1] + unit


def with_unit(name, unit):
    return f"{name} [{unit}]" if unit else name


# ---------------------------------------------------------------- reading


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


def read_run(f):
    """Everything the plots need, as numpy arrays (the file is closed afterwards)."""
    run = {"dimension": int(f.attrs.get("dimension", 2)),
           "scene_file": text(f.attrs.get("scene_file", "")),
           "history": OrderedDict(), "xy_plots": [], "specimen": None, "frame": None}
    if run["dimension"] not in (2, 3):
        raise ReportError(f"dimension attribute is {run['dimension']}, expected 2 or 3")
    D = run["dimension"]

    hist = f.get("history")
    if isinstance(hist, h5py.Group):
        series = {k: d for k, d in hist.items() if isinstance(d, h5py.Dataset) and d.ndim == 1}
        # A running engine appends series one by one: cut all to the common length.
        S = min((d.shape[0] for d in series.values()), default=0)
        if "time" in series and S > 0:
            for name, d in series.items():
                run["history"][name] = {"data": np.asarray(d[:S], dtype=float),
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

    frames = f.get("frames")
    if isinstance(frames, h5py.Group) and "time" in frames and "x" in frames:
        rows = [frames[k].shape[0] for k in ("time", "x", "force") if k in frames]
        F = min(rows)
        if F > 0:  # only the last complete row is read: 50k particles x many frames is large
            k = F - 1
            run["frame"] = {"index": k, "count": F, "time": float(frames["time"][k]),
                            "step": int(frames["step"][k]) if "step" in frames else None,
                            "x": np.asarray(frames["x"][k], dtype=float).reshape(-1, D),
                            "force": (np.asarray(frames["force"][k], dtype=float).reshape(-1, D)
                                      if "force" in frames else None)}
    return run


def read_outlines(spec):
    """Aggregate outlines in the picture plane (2D; 3D: the mid-plane section), or []."""
    if "outline_xy" not in spec or "outline_start" not in spec:
        return []
    xy = np.asarray(spec["outline_xy"], dtype=float).reshape(-1, 2)
    start = np.asarray(spec["outline_start"], dtype=int)
    return [xy[a:b] for a, b in zip(start[:-1], start[1:]) if b - a >= 3]


def draw_outlines(ax, run, factor):
    outlines = run["specimen"]["outlines"] if run["specimen"] else []
    if outlines:
        ax.add_collection(PolyCollection([o * factor for o in outlines], facecolors="none", edgecolors="0.1",
                                         linewidths=0.8))


def read_cracks(f, D, spec):
    """The crack log (None without one): positions, normals, mode (1 tensile, 2 shear), kind (0 break,
    1 first yield), phase pair, and the crack's length in the plane (2·min(R_a, R_b))."""
    g = f.get("cracks")
    if not isinstance(g, h5py.Group) or "position" not in g:
        return None
    n = min(g[k].shape[0] for k in ("position", "normal", "mode", "kind", "phase_a", "phase_b", "id_a", "id_b"))
    c = {"position": np.asarray(g["position"][:n], dtype=float).reshape(-1, D),
         "normal": np.asarray(g["normal"][:n], dtype=float).reshape(-1, D),
         "mode": np.asarray(g["mode"][:n], dtype=int), "kind": np.asarray(g["kind"][:n], dtype=int),
         "phase_a": np.asarray(g["phase_a"][:n], dtype=int), "phase_b": np.asarray(g["phase_b"][:n], dtype=int),
         "size": np.zeros(n)}
    if spec is not None and "id" in f["specimen"]:
        ids = np.asarray(f["specimen"]["id"], dtype=np.int64)
        order = np.argsort(ids)
        radius_of = lambda q: spec["radius"][order[np.searchsorted(ids, q, sorter=order)]]
        c["size"] = 2 * np.minimum(radius_of(np.asarray(g["id_a"][:n])), radius_of(np.asarray(g["id_b"][:n])))
    return c


# ---------------------------------------------------------------- plots


def time_axis(run):
    t = run["history"]["time"]["data"]
    factor, unit = si_scale(t, "s")
    return t * factor, f"time [{unit}]"


def history_groups(history):
    """Series sharing a prefix and unit go in one subplot (all energy.* in J, wall.top.force_x|y|z).
    Dimensionless series ("-") are only grouped when they are components of one quantity
    (strain_xx, strain_yy): porosity and coordination share a unit but not a scale."""
    groups = OrderedDict()
    for name, s in history.items():
        if name in ("time", "step"):
            continue
        prefix, _, last = name.rpartition(".")
        base = COMPONENT.sub("", last)
        if not prefix:
            key = (name,)
        elif s["unit"] in ("-", ""):
            key = (prefix, s["unit"], base)
        else:
            key = (prefix, s["unit"])
        groups.setdefault(key, []).append(name)
    return list(groups.values())


def plot_series(ax, run, names, t):
    """Draw series on one axes; title, legend and y label come from the names' common parts."""
    hist = run["history"]
    unit = hist[names[0]]["unit"]
    factor, unit = si_scale(np.concatenate([hist[n]["data"] for n in names]), unit)
    prefix = names[0].rpartition(".")[0]
    for n in names:
        s = hist[n]
        legend = s["label"] or (n[len(prefix) + 1:] if prefix else n)
        ax.plot(t, s["data"] * factor, lw=1.2, label=legend)
    if len(names) == 1:
        s = hist[names[0]]
        ax.set_title(names[0], fontsize="medium")
        ax.set_ylabel(with_unit(s["label"] or names[0].rpartition(".")[2], unit))
    else:
        bases = {COMPONENT.sub("", n.rpartition(".")[2]) for n in names}
        base = bases.pop() if len(bases) == 1 else None
        ax.set_title(f"{prefix}.{base}_*" if base else f"{prefix}.*", fontsize="medium")
        ax.set_ylabel(with_unit(base or prefix.rpartition(".")[2], unit))
        ax.legend(fontsize="x-small", framealpha=0.7)
    ax.grid(alpha=0.3)


def grid(n, width=4.2, height=2.9):
    ncols = min(3, n)
    nrows = math.ceil(n / ncols)
    fig, axes = plt.subplots(nrows, ncols, figsize=(width * ncols, height * nrows),
                             squeeze=False, constrained_layout=True)
    axes = axes.ravel()
    for ax in axes[n:]:
        ax.remove()
    return fig, axes[:n], ncols


def plot_history(run, stem, out_dir):
    groups = history_groups(run["history"])
    if not groups:
        return []
    t, tlabel = time_axis(run)
    fig, axes, ncols = grid(len(groups))
    for i, (ax, names) in enumerate(zip(axes, groups)):
        plot_series(ax, run, names, t)
        if i + ncols >= len(groups):  # x label only under the last plot of each column
            ax.set_xlabel(tlabel)
    fig.suptitle(f"{stem}: histories ({run['scene_file'] or 'unknown scene'})")
    return [save(fig, out_dir, stem, "history")]


def plot_xy(run, stem, out_dir):
    hist = run["history"]
    pairs = []
    for xn, yn in run["xy_plots"]:
        missing = [n for n in (xn, yn) if n not in hist]
        if missing:
            print(f"report: xy plot {xn}:{yn} skipped, no series {', '.join(missing)}", file=sys.stderr)
        else:
            pairs.append((xn, yn))
    if not pairs:
        return []
    fig, axes, _ = grid(len(pairs), width=4.8, height=3.8)
    for ax, (xn, yn) in zip(axes, pairs):
        xs, ys = hist[xn], hist[yn]
        fx, ux = si_scale(xs["data"], xs["unit"])
        fy, uy = si_scale(ys["data"], ys["unit"])
        ax.plot(xs["data"] * fx, ys["data"] * fy, lw=1.3)
        ax.set_xlabel(with_unit(xs["label"] or xn, ux))
        ax.set_ylabel(with_unit(ys["label"] or yn, uy))
        ax.set_title(f"{yn} vs {xn}", fontsize="medium")
        ax.grid(alpha=0.3)
    fig.suptitle(f"{stem}: x-y plots")
    return [save(fig, out_dir, stem, "xy")]


def plot_energy(run, stem, out_dir):
    hist = run["history"]
    names = [n for n in hist if n.startswith("energy.")]
    if not names:
        return []
    t, tlabel = time_axis(run)
    terms = [n for n in names if n != "energy.residual"]
    has_residual = "energy.residual" in hist
    # The residual is small next to the terms: a second panel of its own makes it readable.
    fig, axes = plt.subplots(2 if has_residual else 1, 1, sharex=True, squeeze=False,
                             figsize=(8, 6.5 if has_residual else 4.5), constrained_layout=True,
                             gridspec_kw={"height_ratios": [2, 1]} if has_residual else None)
    axes = axes.ravel()
    factor, unit = si_scale(np.concatenate([hist[n]["data"] for n in names]), "J")
    for n in terms:
        axes[0].plot(t, hist[n]["data"] * factor, lw=1.3, label=hist[n]["label"] or n[len("energy."):])
    if has_residual:
        res = hist["energy.residual"]["data"] * factor
        axes[0].plot(t, res, "k--", lw=1.2, label="residual")
        axes[1].plot(t, res, "k", lw=1.2)
        axes[1].axhline(0, color="0.5", lw=0.8)
        axes[1].set_ylabel(f"residual [{unit}]")
        axes[1].grid(alpha=0.3)
    axes[0].set_ylabel(f"energy [{unit}]")
    axes[0].legend(fontsize="small", ncol=2, framealpha=0.7)
    axes[0].grid(alpha=0.3)
    axes[-1].set_xlabel(tlabel)
    axes[0].set_title(f"{stem}: energy balance")
    return [save(fig, out_dir, stem, "energy")]


def section(run):
    """Particles to draw as circles in a plane: (centres [M,2], radii, phase, |F| or None,
    axis names, plot limits, description). 2D: all discs. 3D: the spheres cut by y = centre."""
    spec, frame = run["specimen"], run["frame"]
    x = frame["x"] if frame and frame["x"].shape == spec["x"].shape else spec["x"]
    force = frame["force"] if frame and frame["force"] is not None and frame["force"].shape == x.shape else None
    fmag = np.linalg.norm(force, axis=1) if force is not None else None
    r, phase = spec["radius"], spec["phase"]
    if frame and x is frame["x"]:
        step = f", step {frame['step']}" if frame["step"] is not None else ""
        factor, unit = si_scale([frame["time"]], "s")
        when = f"t = {frame['time'] * factor:.4g} {unit}{step} (frame {frame['index'] + 1} of {frame['count']})"
    else:
        when = "initial specimen (no frames)"
    # Limits from the whole specimen, so a 3D section shows where it lies in the specimen.
    plane = [0, 1] if run["dimension"] == 2 else [0, 2]
    limits = ((x[:, plane] - r[:, None]).min(axis=0), (x[:, plane] + r[:, None]).max(axis=0))
    if run["dimension"] == 2:
        return x, r, phase, fmag, ("x", "y"), limits, when
    lo, hi = (x[:, 1] - r).min(), (x[:, 1] + r).max()
    yc = 0.5 * (lo + hi)
    d = np.abs(x[:, 1] - yc)
    cut = d < r
    rc = np.sqrt(r[cut] ** 2 - d[cut] ** 2)
    factor, unit = si_scale([yc], "m")
    when += f", section y = {yc * factor:.4g} {unit}"
    return (x[cut][:, plane], rc, phase[cut], fmag[cut] if fmag is not None else None, ("x", "z"), limits, when)


def draw_discs(ax, xy, r, limits, factor, **style):
    # One EllipseCollection in data units: fast for 50k discs, unlike one Circle patch each.
    coll = EllipseCollection(2 * r * factor, 2 * r * factor, np.zeros_like(r), units="xy",
                             offsets=xy * factor, offset_transform=ax.transData,
                             linewidths=0.3 if len(r) <= 2000 else 0, edgecolors="0.2", **style)
    ax.add_collection(coll)
    ax.set_xlim(limits[0][0] * factor, limits[1][0] * factor)
    ax.set_ylim(limits[0][1] * factor, limits[1][1] * factor)
    ax.set_aspect("equal")
    return coll


def touching_pairs(xy, r, tol=1e-3):
    """Pairs (i, j) whose discs touch or nearly (gap ≤ tol · the smaller radius): the bonds of a bonded
    specimen, found on a grid of cells one largest diameter wide."""
    h = 2 * r.max() * (1 + tol)
    cells = {}
    keys = np.floor((xy - xy.min(axis=0)) / h).astype(np.int64)
    for i, (a, b) in enumerate(keys):
        cells.setdefault((a, b), []).append(i)
    pairs = []
    for (a, b), members in cells.items():
        near = [j for da in (-1, 0, 1) for db in (-1, 0, 1) for j in cells.get((a + da, b + db), ())]
        near = np.asarray(near)
        for i in members:
            cand = near[near > i]
            if len(cand) == 0:
                continue
            gap = np.linalg.norm(xy[cand] - xy[i], axis=1) - r[cand] - r[i]
            for j in cand[gap <= tol * np.minimum(r[cand], r[i])]:
                pairs.append((i, j))
    return np.asarray(pairs, dtype=np.int64).reshape(-1, 2)


def draw_bond_phases(ax, xy, r, phase, names, factor):
    """Tang Fig. 4.13: the bonds coloured by the phases they join (2D, several phases)."""
    pairs = touching_pairs(xy, r)
    if len(pairs) == 0:
        return
    lo, hi = np.minimum(phase[pairs[:, 0]], phase[pairs[:, 1]]), np.maximum(phase[pairs[:, 0]], phase[pairs[:, 1]])
    cmap = plt.get_cmap("Dark2")
    handles = []
    for k, (a, b) in enumerate(sorted(set(zip(lo.tolist(), hi.tolist())))):
        sel = (lo == a) & (hi == b)
        segs = np.stack([xy[pairs[sel, 0]], xy[pairs[sel, 1]]], axis=1) * factor
        ax.add_collection(LineCollection(segs, colors=[cmap(k % 8)], linewidths=0.6))
        pa = names[a] if 0 <= a < len(names) and names[a] else f"phase {a}"
        pb = names[b] if 0 <= b < len(names) and names[b] else f"phase {b}"
        handles.append(Line2D([], [], color=cmap(k % 8), lw=1.5, label=f"{pa}-{pb} ({int(sel.sum())})"))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small", title="bonds")
    ax.set_title("bonds by phase pair", fontsize="medium")


def plot_specimen(run, stem, out_dir):
    if run["specimen"] is None or len(run["specimen"]["radius"]) == 0:
        return []
    kind = "specimen" if run["dimension"] == 2 else "slice"
    xy, r, phase, fmag, (ax0, ax1), limits, when = section(run)
    if fmag is not None and not (fmag > 0).any():
        fmag = None  # a specimen at rest (e.g. generated): nothing to colour by force
    # 2D specimens of several phases (mortar, aggregate …) also show their bonds by phase pair, as Tang's Fig.
    # 4.13; up to 50 000 discs (the neighbour search is plain Python).
    bond_panel = run["dimension"] == 2 and len(np.unique(phase)) > 1 and len(r) <= 50000
    panels = 1 + (fmag is not None) + bond_panel
    fig, axes = plt.subplots(1, panels, figsize=(6.5 * panels, 6), squeeze=False, constrained_layout=True)
    axes = axes.ravel()
    fig.suptitle(f"{stem}: {when}", fontsize="medium")
    if len(r) == 0:
        for ax in axes:
            ax.text(0.5, 0.5, "no particle cut by the section", ha="center", transform=ax.transAxes)
        return [save(fig, out_dir, stem, kind)]
    factor, lunit = si_scale(np.abs(limits).ravel(), "m")
    for ax in axes:
        ax.set_xlabel(f"{ax0} [{lunit}]")
        ax.set_ylabel(f"{ax1} [{lunit}]")

    names = run["specimen"]["phase_names"]
    cmap = plt.get_cmap("tab10")
    draw_discs(axes[0], xy, r, limits, factor, facecolors=cmap(phase % 10))
    draw_outlines(axes[0], run, factor)
    handles = [Patch(facecolor=cmap(p % 10), edgecolor="0.2",
                     label=names[p] if 0 <= p < len(names) and names[p] else f"phase {p}")
               for p in np.unique(phase)]
    axes[0].legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small",
                   title="phase")
    axes[0].set_title("phase", fontsize="medium")

    if fmag is not None:
        ffac, funit = si_scale(fmag, "N")
        # Contact forces are heavy-tailed: clip the colour scale at the 99.5th percentile
        # so the force chains show instead of a few hot spots on a dark background.
        vmax = np.percentile(fmag, 99.5) * ffac if fmag.max() > 0 else 1.0
        coll = draw_discs(axes[1], xy, r, limits, factor, cmap="inferno")
        coll.set_array(fmag * ffac)
        coll.set_clim(0, vmax)
        fig.colorbar(coll, ax=axes[1], label=f"|F| [{funit}]", shrink=0.8,
                     extend="max" if fmag.max() * ffac > vmax else "neither")
        axes[1].set_title("resultant contact force magnitude", fontsize="medium")
    if bond_panel:
        ax = axes[-1]
        ax.set_xlim(limits[0][0] * factor, limits[1][0] * factor)
        ax.set_ylim(limits[0][1] * factor, limits[1][1] * factor)
        ax.set_aspect("equal")
        draw_bond_phases(ax, xy, r, phase, names, factor)
    # More pixels for large specimens, so single discs stay visible when zooming in.
    return [save(fig, out_dir, stem, kind, dpi=200 if len(r) > 10000 else 120)]


MODE_COLOURS = {1: "tab:blue", 2: "tab:red"}


def plot_cracks(run, stem, out_dir):
    """2D: every crack as a segment across its bond (perpendicular to the normal, as long as the smaller
    diameter), over the specimen; colour = mode, line style = phase pair; first yields of softening bonds
    dotted. 3D: crack positions projected on the x-z plane."""
    c = run["cracks"]
    if c is None or run["specimen"] is None:
        return []
    xy, r, phase, _, (ax0, ax1), limits, when = section(run)
    fig, ax = plt.subplots(figsize=(7, 6), constrained_layout=True)
    factor, lunit = si_scale(np.abs(limits).ravel(), "m")
    if run["dimension"] == 2:
        draw_discs(ax, xy, r, limits, factor, facecolors="0.92")
    else:
        ax.set_xlim(limits[0][0] * factor, limits[1][0] * factor)
        ax.set_ylim(limits[0][1] * factor, limits[1][1] * factor)
        ax.set_aspect("equal")
    ax.set_xlabel(f"{ax0} [{lunit}]")
    ax.set_ylabel(f"{ax1} [{lunit}]")
    draw_outlines(ax, run, factor)
    names = run["specimen"]["phase_names"]
    pname = lambda p: names[p] if 0 <= p < len(names) and names[p] else f"phase {p}"
    pairs = sorted({(min(a, b), max(a, b)) for a, b in zip(c["phase_a"], c["phase_b"])})
    styles = ["-", "--", "-.", (0, (5, 1, 1, 1, 1, 1))]
    handles = []
    breaks = int((c["kind"] == 0).sum())
    for kind, width, dash in ((1, 0.6, ":"), (0, 1.2, None)):
        for mode, colour in MODE_COLOURS.items():
            for k, pair in enumerate(pairs):
                sel = (c["kind"] == kind) & (c["mode"] == mode) & \
                      (np.minimum(c["phase_a"], c["phase_b"]) == pair[0]) & \
                      (np.maximum(c["phase_a"], c["phase_b"]) == pair[1])
                if not sel.any():
                    continue
                label = f"{'yield' if kind else 'break'}, {'tensile' if mode == 1 else 'shear'}"
                if len(pairs) > 1:
                    label += f", {pname(pair[0])}-{pname(pair[1])}"
                label += f" ({int(sel.sum())})"
                p = c["position"][sel]
                if run["dimension"] == 2:
                    n = c["normal"][sel]
                    t = np.stack([-n[:, 1], n[:, 0]], axis=1) * (0.5 * c["size"][sel])[:, None]
                    segs = np.stack([p - t, p + t], axis=1) * factor
                    ax.add_collection(LineCollection(segs, colors=colour, linewidths=width,
                                                     linestyles=dash or styles[k % len(styles)]))
                    handles.append(Line2D([], [], color=colour, lw=width, ls=dash or styles[k % len(styles)], label=label))
                else:
                    ax.scatter(p[:, 0] * factor, p[:, 2] * factor, s=4 if kind == 0 else 1, c=colour,
                               marker="o" if k == 0 else "x", label=label)
    if run["dimension"] == 3:
        handles = ax.get_legend_handles_labels()[0]
        when += " (cracks: all, projected on the x-z plane)"
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small", title="cracks")
    else:
        ax.text(0.5, 0.5, "no bond has broken", ha="center", transform=ax.transAxes)
    ax.set_title(f"{stem}: {breaks} broken bonds; {when}", fontsize="medium")
    return [save(fig, out_dir, stem, "cracks", dpi=200 if len(r) > 10000 else 120)]


def save(fig, out_dir, stem, kind, dpi=120):
    path = os.path.join(out_dir, f"{stem}_{kind}.png")
    try:
        fig.savefig(path, dpi=dpi)
    except OSError as e:
        raise ReportError(f"cannot write {path}: {e.strerror or e}") from None
    finally:
        plt.close(fig)
    return path


# ---------------------------------------------------------------- main


def main(argv=None):
    parser = argparse.ArgumentParser(description="PNG plots of a mesocrack run (HDF5 output file).")
    parser.add_argument("file", help="mesocrack output file (.h5)")
    parser.add_argument("--out-dir", help="directory for the PNGs (default: next to the file)")
    args = parser.parse_args(argv)
    try:
        with open_run(args.file) as f:
            try:
                run = read_run(f)
            except (OSError, KeyError, ValueError) as e:  # damaged or half-written file
                raise ReportError(f"cannot read ({str(e).splitlines()[0] if str(e) else type(e).__name__})")
        out_dir = args.out_dir or os.path.dirname(os.path.abspath(args.file))
        try:
            os.makedirs(out_dir, exist_ok=True)
        except OSError as e:
            raise ReportError(f"cannot create output directory {out_dir}: {e.strerror}")
        stem = os.path.splitext(os.path.basename(args.file))[0]
        for plot in (plot_history, plot_xy, plot_energy, plot_specimen, plot_cracks):
            for path in plot(run, stem, out_dir):
                print(path, flush=True)
    except ReportError as e:
        print(f"report: {args.file}: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
