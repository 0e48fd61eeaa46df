"""Pictures of a single-shear pull test ([pullout], Tang ch. 8), for app/report.py: the load-slip curve, the FRP's
strain profiles at the scene's load levels (Fig. 8.8; without them, at the end of the run) and the cracks, breaks and
first yields, at 31, 60, 90 and 100 % of the capacity and at the end (Fig. 8.12). The [pullout] keys (sheet width,
bonded length, load levels) are read from the scene the run stored."""
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")  # headless: no display on compute nodes or CI
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from report_plots import UNITS, save, si  # noqa: E402
from report_specimen import MODE_COLOURS, crack_segments, draw_discs  # noqa: E402

FRACTIONS = (0.31, 0.6, 0.9, 1.0)  # of the capacity: Tang §8.2.3
YIELD_COLOUR = "tab:orange"  # first yields, beside MODE_COLOURS' breaks


def pullout_keys(run):
    """The scene's [pullout] table with its values in SI, or None (no [pullout], or a value not understood)."""
    try:
        t = tomllib.loads(run.get("scene_text") or "").get("pullout")
    except tomllib.TOMLDecodeError:
        return None
    if not t:
        return None
    keys = {k: si(t[k]) for k in ("width", "bonded_from", "bonded_to", "frp_modulus", "frp_thickness") if k in t}
    keys["load_levels"] = [si(v) for v in t.get("load_levels", [])]
    keys["frp_phase"] = str(t.get("frp_phase", ""))
    unread = [f"{k} = {t[k]!r}" for k, v in keys.items() if v is None or (k == "load_levels" and None in v)]
    if unread or len(keys) < 7:
        # The engine read these keys (scene/units.cpp); a unit outside UNITS only costs the pull-test pictures.
        print(f"report: [pullout] {', '.join(unread) or 'keys missing'}: not understood here (units: "
              f"{', '.join(UNITS)}); no pull-test pictures", file=sys.stderr)
        return None
    return keys


def first_reaching(load, peak, level):
    """The first history row, up to the peak, at which the load reaches `level`, or None."""
    hit = np.nonzero(load[:peak + 1] >= level)[0]
    return int(hit[0]) if len(hit) else None


def plot_pullout(run, stem, out_dir):
    """<stem>_pullout.png (load-slip, strain profiles) and <stem>_pullout_cracks.png (cracks at the fractions
    of the capacity), for a run with [pullout]."""
    h = run["history"]
    keys = pullout_keys(run)
    if keys is None or "pullout.load" not in h or len(h["pullout.load"]["data"]) < 2:
        return []
    b = keys["width"]
    load = h["pullout.load"]["data"] * b  # N for the sheet's width
    slip = h["pullout.slip"]["data"]
    time = h["time"]["data"]
    peak = int(np.argmax(load))
    length = abs(keys["bonded_to"] - keys["bonded_from"])
    gauges = sorted((int(k.rsplit("_", 1)[1]), v["data"]) for k, v in h.items() if k.startswith("pullout.strain_"))
    positions = (np.arange(len(gauges)) + 0.5) * length / max(len(gauges), 1)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4), constrained_layout=True)
    a1.plot(slip * 1e3, load * 1e-3, lw=1)
    a1.plot(slip[peak] * 1e3, load[peak] * 1e-3, "o", color="tab:red",
            label=f"{capacity_name(run)} {load[peak] * 1e-3:.2f} kN at slip {slip[peak] * 1e3:.3f} mm")
    a1.set_xlabel("slip at the bonded length's loaded end [mm]")
    a1.set_ylabel(f"load for b_f = {b * 1e3:g} mm [kN]")
    a1.legend(fontsize="small")
    ep_tp = keys["frp_modulus"] * keys["frp_thickness"]
    # The profiles at the scene's load levels on the way to the capacity; without load levels, the profile at the
    # end of the run (an elastic pull's steady state, scenes/pull_elastic_2d.toml).
    rows = [(first_reaching(load, peak, level), f"{level * 1e-3:g} kN") for level in keys["load_levels"]]
    if not keys["load_levels"]:
        rows = [(len(load) - 1, f"{load[-1] * 1e-3:.3g} kN, end of the run")]
    for k, (row, label) in enumerate(rows):
        if row is None or not gauges:
            continue
        colour = f"C{k}"
        a2.plot(positions * 1e3, [g[row] * 1e6 for _, g in gauges], "o-", ms=3, color=colour, label=label)
        a2.plot(0, load[row] / (ep_tp * b) * 1e6, "s", color=colour, mfc="none")  # ε₀ of (8.5)
    draw_shear_lag(a2, (run.get("summary") or {}).get("pullout") or {}, length)
    a2.set_xlabel("distance from the bonded length's loaded end [mm]")
    a2.set_ylabel("FRP strain [µε]")
    a2.set_title("strain profiles (squares: ε₀ = F/(E_p t_p b_f), (8.5))", fontsize="medium")
    if a2.lines:
        a2.legend(fontsize="small", title="load")
    out = [save(fig, out_dir, stem, "pullout")]
    if run["cracks"] is not None and run["specimen"] is not None:
        out += plot_pullout_cracks(run, stem, out_dir, keys, load, time, peak)
    return out


def capacity_name(run):
    """What the largest load is: the capacity once the summary saw the load fall past its peak, else only the largest
    load so far (an elastic or interrupted pull)."""
    passed = ((run.get("summary") or {}).get("pullout") or {}).get("peak_passed", True)
    return "capacity" if passed else "largest load so far (no peak)"


def draw_shear_lag(ax, summary, length):
    """The linear shear-lag solution ε₀ sinh(λ(L − x))/sinh(λL) that `summary` sets beside the final profile of a
    scene declaring [pullout] interface_stiffness (Tang §8.1), with how far the gauges lie from it."""
    s = summary.get("shear_lag")
    if not isinstance(s, dict) or not all(isinstance(s.get(k), (int, float)) for k in ("lambda", "epsilon_0")):
        return
    x = np.linspace(0, length, 200)
    lam = s["lambda"]
    strain = s["epsilon_0"] * np.sinh(lam * (length - x)) / np.sinh(lam * length)
    off = s.get("max_deviation_over_epsilon_0")
    off = f", gauges within {100 * off:.2g} % of ε₀" if isinstance(off, (int, float)) else ""
    ax.plot(x * 1e3, strain * 1e6, "--", color="0.3", label=f"shear lag, λL = {lam * length:.3g}{off}")


def plot_pullout_cracks(run, stem, out_dir, keys, load, time, peak):
    """The cracks near the bonded length (from 15 mm before its loaded end to 5 mm past its other end, 12 mm
    deep) logged by the first time the load reached each fraction of the capacity, and all of them at the end: the
    breaks by mode and by where they lie (the adhesive or the concrete), the first yields of softening bonds as dots."""
    c, spec = run["cracks"], run["specimen"]
    xy, r = spec["x"], spec["radius"]
    top = (xy[:, 1] + r).max()
    x0, x1 = sorted((keys["bonded_from"], keys["bonded_to"]))
    x0, x1 = x0 - 15e-3, x1 + 5e-3
    window = ((x0, top - 12e-3), (x1, top))
    near = (xy[:, 0] > x0 - 1e-3) & (xy[:, 0] < x1 + 1e-3) & (xy[:, 1] > top - 13e-3)
    stages = [(f"{f:.0%} of the capacity", time[first_reaching(load, peak, f * load[peak])]) for f in FRACTIONS]
    stages.append(("end of the run", np.inf))
    names = spec["phase_names"]
    frp = names.index(keys["frp_phase"]) if keys["frp_phase"] in names else -1
    fig, axes = plt.subplots(len(stages), 1, figsize=(11, 2.0 * len(stages) + 0.6), constrained_layout=True)
    factor = 1e3
    for ax, (label, until) in zip(axes, stages):
        draw_discs(ax, xy[near], r[near], window, factor, facecolors="0.92")
        # A softening bond's first yield (kind 1, engine/crack.hpp) marks the damage zone ahead of the breaks: a dot
        # at its contact point, under the breaks.
        yields = (c["kind"] == 1) & (c["time"] <= until)
        if yields.any():
            p = c["position"][yields] * factor
            ax.scatter(p[:, 0], p[:, 1], s=4, c=YIELD_COLOUR, marker="o", linewidths=0, zorder=2.5)
        for mode, colour in MODE_COLOURS.items():
            for glue, style in ((True, ":"), (False, "-")):
                sel = (c["kind"] == 0) & (c["mode"] == mode) & (c["time"] <= until)
                pair = (c["phase_a"] == frp) | (c["phase_b"] == frp)
                sel &= pair if glue else ~pair
                if sel.any():
                    ax.add_collection(LineCollection(crack_segments(c, sel, factor), colors=colour,
                                                     linewidths=1.0, linestyles=style, zorder=3))
        n = int(((c["kind"] == 0) & (c["time"] <= until)).sum())
        ax.set_title(f"{label}: {n} broken bonds, {int(yields.sum())} first yields", fontsize="medium", loc="left")
        ax.set_ylabel("y [mm]")
    axes[-1].set_xlabel("x [mm]")
    handles = [Line2D([], [], color=MODE_COLOURS[1], label="tensile break"),
               Line2D([], [], color=MODE_COLOURS[2], label="shear break"),
               Line2D([], [], color=YIELD_COLOUR, marker="o", ms=3, ls="none", label="first yield (softening)"),
               Line2D([], [], color="0.3", ls=":", label="adhesive (FRP-concrete)"),
               Line2D([], [], color="0.3", ls="-", label="concrete")]
    axes[0].legend(handles=handles, loc="lower left", bbox_to_anchor=(0, 1.15), ncol=5, fontsize="small")
    fig.suptitle(f"{stem}: cracks near the bonded length (Tang Fig. 8.12), over the initial specimen")
    return [save(fig, out_dir, stem, "pullout_cracks", dpi=150)]
