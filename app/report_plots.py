"""Time-series figures of a mesocrack run, for app/report.py: the histories grouped by quantity, the x-y plots the
scene asks for and the energy balance; also what every figure of the report shares (SI prefixes, saving)."""
import math
import os
import re
import sys
import tomllib
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")  # headless: no display on compute nodes or CI
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# Units that read better with an SI prefix (MPa, mJ, µs); "-" and compound units are left alone.
SCALABLE_UNITS = {"Pa", "J", "N", "m", "s", "W", "m/s", "N/m", "N m"}
PREFIXES = [(1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, ""), (1e-3, "m"), (1e-6, "µ"), (1e-9, "n")]
# Trailing vector/tensor component of a series name: force_x, stress_xy, disp_z.
COMPONENT = re.compile(r"_(x|y|z|xx|yy|zz|xy|yx|xz|zx|yz|zy)$")
# The units a scene's length, force or modulus that the report reads may carry (scene/units.cpp has them all), in SI.
UNITS = {"m": 1, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "N": 1, "kN": 1e3, "MN": 1e6,
         "Pa": 1, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9}


class ReportError(Exception):
    """A file that cannot be read or written (missing, not HDF5, not a mesocrack file, damaged; a PNG or folder that
    cannot be written): reported in one line naming it, exit status 3 like the engine's file errors."""


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


def si(value):
    """A scene value ("50 mm", 0.05) in SI, or None when it is not one of UNITS."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    m = re.fullmatch(r"\s*([-+0-9.eE]+)\s*(\S*)\s*", str(value))
    if not m or m.group(2) not in UNITS | {"": 1}:
        return None
    try:
        return float(m.group(1)) * UNITS.get(m.group(2), 1)
    except ValueError:
        return None


def scene_tables(run):
    """The stored scene as a dict ({} when absent or not TOML)."""
    try:
        return tomllib.loads(run.get("scene_text") or "")
    except tomllib.TOMLDecodeError:
        return {}


def with_unit(name, unit):
    return f"{name} [{unit}]" if unit else name


SLICE_NOTE = "2D: forces, works and energies are those of a slice 1 m thick (per metre of thickness)"


def note_slice(fig, run):
    """A 2D run's forces and energies are its unit-thickness slice's: the figure says so in its top corner (and in the
    PNG's Description, which tests read)."""
    if run["dimension"] == 2:
        fig.text(0.003, 0.997, SLICE_NOTE, ha="left", va="top", fontsize=7, color="0.35")
        add_note(fig, SLICE_NOTE)


def add_note(fig, note):
    """A line of the PNG's Description (what the figure states, readable without looking at it)."""
    fig.mc_note = "; ".join(n for n in (getattr(fig, "mc_note", None), note) if n)


def fit_in_figure(fig, dpi):
    """Widen or heighten the figure until everything it draws lies inside it: a legend beside an equal-aspect picture
    can need more width than the layout found, and would be cut off at the edge. The layout centres its content, so
    growing by the overflow on both sides brings it in; a few rounds for layouts that do not."""
    tolerance = 0.5 / dpi  # half a pixel
    for _ in range(6):
        fig.canvas.draw()
        box = fig.get_tightbbox(fig.canvas.get_renderer())  # inches
        w, h = fig.get_size_inches()
        over_x = max(0.0, -box.x0) + max(0.0, box.x1 - w)
        over_y = max(0.0, -box.y0) + max(0.0, box.y1 - h)
        if over_x <= tolerance and over_y <= tolerance:
            return
        fig.set_size_inches(w + (over_x + 0.05 if over_x > tolerance else 0),
                            h + (over_y + 0.05 if over_y > tolerance else 0))


def save(fig, out_dir, stem, kind, dpi=120):
    path = os.path.join(out_dir, f"{stem}_{kind}.png")
    note = getattr(fig, "mc_note", None)
    try:
        fit_in_figure(fig, dpi)
        fig.savefig(path, dpi=dpi, metadata={"Description": note} if note else None)
    except OSError as e:
        raise ReportError(f"cannot write {path}: {e.strerror or e}") from None
    finally:
        plt.close(fig)
    return path


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
    note_slice(fig, run)
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
    uniaxial = run.get("summary", {}).get("uniaxial") or {}
    splitting = splitting_strength(run)
    for ax, (xn, yn) in zip(axes, pairs):
        xs, ys = hist[xn], hist[yn]
        # A series that runs negative (a shortening strain, a compressive stress) is drawn as its magnitude's
        # direction, −x, so that a compression curve reads left to right and upwards, as in the literature.
        sx, sy = (-1.0 if leans_negative(s["data"]) else 1.0 for s in (xs, ys))
        fx, ux = si_scale(sx * xs["data"], xs["unit"])
        fy, uy = si_scale(sy * ys["data"], ys["unit"])
        ax.plot(sx * xs["data"] * fx, sy * ys["data"] * fy, lw=1.3)
        ax.set_xlabel(with_unit(("−" if sx < 0 else "") + (xs["label"] or xn), ux))
        ax.set_ylabel(with_unit(("−" if sy < 0 else "") + (ys["label"] or yn), uy))
        ax.set_title(f"{yn} vs {xn}", fontsize="medium")
        if (xn, yn) == run.get("uniaxial_pair") and uniaxial:
            mark_uniaxial(ax, uniaxial, sx * xs["data"] * fx, sy * ys["data"] * fy, fx, fy, uy)
        if splitting is not None and yn == splitting["series"]:
            mark_splitting(fig, ax, run, splitting, sx * xs["data"] * fx, sy * ys["data"] * fy, fy, uy)
        ax.grid(alpha=0.3)
    fig.suptitle(f"{stem}: x-y plots")
    note_slice(fig, run)
    return [save(fig, out_dir, stem, "xy")]


def leans_negative(y):
    finite = y[np.isfinite(y)]
    return finite.size > 0 and -finite.min() > finite.max()


def mark_uniaxial(ax, u, x, y, fx, fy, uy):
    """On the stress-strain curve drawn (x, y, scaled as shown): the strength where the curve peaks, and E as the line
    of its secant (25–50 % of the peak) from the origin, as `summary` reads them. The curve's strain is the platens'
    (E_platens); in 2D its slope is the disc assembly's own ratio, E_platens × E_raw_2d / E before the plane reading."""
    strength, modulus = u.get("ucs", u.get("f_t")), u.get("E_platens")
    if not all(isinstance(v, (int, float)) and np.isfinite(v) and v > 0 for v in (strength, modulus)):
        return
    k = int(np.nanargmax(y))
    name = "UCS" if "ucs" in u else "f_t"
    passed = u.get("peak_passed", True)
    ax.plot([x[k]], [y[k]], "o", color="C3",
            label=f"{name} {y[k]:.3g} {uy}" + ("" if passed else " (largest so far: no peak)"))
    slope = modulus * (u["E_raw_2d"] / u["E"] if "E_raw_2d" in u and u.get("E") else 1.0)
    top = 0.6 * y[k]
    ax.plot([0, top / (slope * fy / fx)], [0, top], "--", color="C2", lw=1,
            label=f"E {modulus / 1e9:.3g} GPa (secant 25–50 %)")
    ax.legend(fontsize="small", loc="lower right")


def disc_size(scene, dimension):
    """A Brazilian disc's diameter D and thickness t [m] from the scene's [specimen], or None for another shape. Rigid
    cells (kind = "voronoi_cells") declare shape = "disc" with its radius (3D: a cylinder along z, its thickness); a
    packing declares shape = "disc" (3D: "cylinder"), the disc inscribed in its box [lo, hi]: D the box's smaller
    side in x-y, t its depth along z (the carve of preprocess/dense_packing.cpp). 2D: t = 1 m, the slice that every 2D
    force is per metre of."""
    sp = scene.get("specimen")
    if not isinstance(sp, dict) or sp.get("shape") not in ("disc", "cylinder"):
        return None
    if sp.get("kind") == "voronoi_cells":
        radius = si(sp.get("radius"))
        size = (2 * radius if radius else None, 1.0 if dimension == 2 else si(sp.get("thickness")))
    elif sp.get("kind") == "packing":
        lo, hi = ([si(v) for v in sp.get(k, [])] for k in ("lo", "hi"))
        if len(lo) != dimension or len(hi) != dimension or None in lo + hi:
            return None
        size = (min(hi[0] - lo[0], hi[1] - lo[1]), 1.0 if dimension == 2 else hi[2] - lo[2])
    else:
        return None
    return size if all(v is not None and v > 0 for v in size) else None


def splitting_strength(run):
    """A Brazilian disc's splitting strength f_st = 2P/(πDt) from its peak load P (Květoň (9.2) with P₁ = P₂ = P):
    {series, index, P, D, t, f_st} in SI, or None for another specimen. The load is the series the scene's
    [[summary]] peak_load reduces, else the y of its first x-y plot (the plates' reaction in scenes/brazilian_*)."""
    scene = scene_tables(run)
    size = disc_size(scene, run["dimension"])
    hist = run["history"]
    if size is None:
        return None
    entries = scene.get("summary") if isinstance(scene.get("summary"), list) else []
    names = [e.get("of") for e in entries if isinstance(e, dict) and e.get("name") == "peak_load"]
    names += [y for _, y in run["xy_plots"][:1]]
    load = next((n for n in names if n in hist), None)
    if load is None or hist[load]["unit"] != "N" or not np.isfinite(hist[load]["data"]).any():
        return None
    data = np.abs(hist[load]["data"])
    k = int(np.nanargmax(data))
    D, t = size
    return {"series": load, "index": k, "P": float(data[k]), "D": D, "t": t, "f_st": 2 * data[k] / (np.pi * D * t)}


def mark_splitting(fig, ax, run, s, x, y, fy, uy):
    """On the load curve drawn (x, y, scaled as shown): the peak P, and the splitting strength it gives in the legend
    and in the PNG's Description."""
    k = s["index"]
    per = " per metre of thickness" if run["dimension"] == 2 else ""
    df, du = si_scale([s["D"]], "m")
    tf, tu = si_scale([s["t"]], "m")
    strength = f"f_st = 2P/(πDt) = {s['f_st'] * 1e-6:.3g} MPa"
    ax.plot([x[k]], [y[k]], "o", color="C3", label=f"peak P = {abs(y[k]):.4g} {uy}{' per m' if per else ''}")
    ax.plot([], [], " ", label=f"{strength}\n(D = {s['D'] * df:.4g} {du}, t = {s['t'] * tf:.4g} {tu}; Květoň (9.2))")
    ax.legend(fontsize="small", loc="best")
    add_note(fig, f"splitting strength {strength} (Květoň (9.2)), peak P = {s['P']:.6g} N{per} of {s['series']}, "
                  f"D = {s['D']:.6g} m, t = {s['t']:.6g} m")


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
    note_slice(fig, run)
    return [save(fig, out_dir, stem, "energy")]
