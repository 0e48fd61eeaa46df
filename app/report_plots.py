"""Time-series figures of a mesocrack run, for app/report.py: the histories grouped by quantity, the x-y plots the
scene asks for and the energy balance; also what every figure of the report shares (SI prefixes, saving)."""
import math
import os
import re
import sys
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


def with_unit(name, unit):
    return f"{name} [{unit}]" if unit else name


SLICE_NOTE = "2D: forces, works and energies are those of a slice 1 m thick (per metre of thickness)"


def note_slice(fig, run):
    """A 2D run's forces and energies are its unit-thickness slice's: the figure says so in its top corner (and in the
    PNG's Description, which tests read)."""
    if run["dimension"] == 2:
        fig.text(0.003, 0.997, SLICE_NOTE, ha="left", va="top", fontsize=7, color="0.35")
        fig.mc_note = SLICE_NOTE


def save(fig, out_dir, stem, kind, dpi=120):
    path = os.path.join(out_dir, f"{stem}_{kind}.png")
    note = getattr(fig, "mc_note", None)
    try:
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
