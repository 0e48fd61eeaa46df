#!/usr/bin/python3
"""Květoň (2019) §9.2–9.3, quasi-static: the L-shaped specimen and the compact-tension specimen of rigid cells.

Runs scenes/l_shape_kveton.toml and scenes/compact_tension_kveton.toml, each single-threaded through the real
`mesocrack run`: the L-shape over seeds of the node placement (--seeds), the compact-tension specimen with its
plates free to turn about z (the thesis's reference) and held (his variant (ii), which he finds carries slightly
more). Each run: the peak load, the load point's travel at the peak, and where the crack ran (from the crack log:
the L's crack as the height at which it crosses the leg, the CTS crack as its angle to the notch).
Output (--out): results.csv (one row per run), runs/<run>_curve.csv and runs/<run>_cracks.csv (its load–displacement
curve and its cracked facets), kveton_ch9.md (the table) and kveton_ch9.png (the curves and the cracked facets).

  benchmarks/kveton_l_shape_cts.py --jobs 2
  benchmarks/kveton_l_shape_cts.py --only l_shape --seeds 1-3
"""
import math
import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from uniaxial_accuracy import ROOT, append_rows, seed_list, study_arguments, study_main, timed_run  # noqa: E402

# specimen: scene, the history of the load and of the load point's travel, --set overrides.
SPECIMENS = {
    "l_shape": ("l_shape_kveton", "group.support.reaction_y", "group.load.disp_y", []),
    "cts_free": ("compact_tension_kveton", "group.load.reaction_y", "group.load.disp_y", []),
    "cts_held": ("compact_tension_kveton", "group.load.reaction_y", "group.load.disp_y",
                 ["groups[0].fix=all", "groups[1].fix=all"]),
}
OUTLINES = {  # [mm], counter-clockwise, as in the scenes
    "l_shape": [(0, 0), (250, 0), (250, 250), (500, 250), (500, 500), (0, 500)],
    "cts": [(0, 0), (200, 0), (200, 200), (0, 200), (0, 105), (64, 105), (64, 95), (0, 95)],
}
FIELDS = ["specimen", "seed", "cells", "peak_kN", "travel_at_peak_mm", "crack_mm_or_deg", "steps", "cpu_s"]


def plan(a):
    todo = []
    for sp in a.only.split(","):
        if sp not in SPECIMENS:
            sys.exit(f"--only: '{sp}' is not one of {', '.join(SPECIMENS)}")
        todo += [(sp, s) for s in (seed_list(a.seeds) if sp == "l_shape" else [1])]
    return todo


def broken_facets(f):
    """Centroids [mm] of the facets that cracked (crack log rows of kind 0)."""
    if "cracks" not in f:
        return np.zeros((0, 3))
    kind = f["cracks/kind"][:]
    return f["cracks/position"][:][kind == 0] * 1e3


def crack_measure(specimen, broken):
    """The L: the median height [mm] of the cracks across the leg (x < 250 mm). The CTS: the angle [deg] of the
    least-squares line through the cracks beyond the notch tip to the notch's direction (positive: upwards)."""
    if specimen == "l_shape":
        leg = broken[broken[:, 0] < 250]
        return float(np.median(leg[:, 1])) if len(leg) else float("nan")
    ahead = broken[broken[:, 0] > 64]
    if len(ahead) < 2:
        return float("nan")
    slope = np.polyfit(ahead[:, 0], ahead[:, 1], 1)[0]
    return math.degrees(math.atan(slope))


def run_all(exe, out, jobs, todo, csv_path):
    def one(item):
        sp, seed = item
        scene, load, travel, sets = SPECIMENS[sp]
        h5 = out / "runs" / f"{sp}_{seed}.h5"
        s, cpu, _ = timed_run(exe, ROOT / "scenes" / f"{scene}.toml", h5, [f"seed={seed}"] + sets, keep=True)
        with h5py.File(h5, "r") as f:
            p, u = f["history"][load][:], np.abs(f["history"][travel][:])
            broken = broken_facets(f)
        for g in h5.parent.glob(h5.stem + ".*"):
            g.unlink()
        (h5.parent / f"{h5.stem}_history.csv").unlink()
        i = int(np.argmax(p))
        np.savetxt(out / "runs" / f"{h5.stem}_curve.csv", np.c_[u * 1e3, p * 1e-3], delimiter=",", fmt="%.6g",
                   header="travel_mm,load_kN", comments="")
        np.savetxt(out / "runs" / f"{h5.stem}_cracks.csv", broken, delimiter=",", fmt="%.3f", header="x_mm,y_mm,z_mm",
                   comments="")
        return {"specimen": sp, "seed": seed, "cells": s["specimen"]["cells"], "peak_kN": p[i] * 1e-3,
                "travel_at_peak_mm": u[i] * 1e3, "crack_mm_or_deg": crack_measure(sp, broken),
                "steps": s["steps"], "cpu_s": cpu}

    append_rows(csv_path, FIELDS, jobs, todo, one,
                lambda r: (f"{r['specimen']} seed {r['seed']}: {r['cells']} cells, peak {r['peak_kN']:.2f} kN at "
                           f"{r['travel_at_peak_mm']:.3f} mm, {r['cpu_s']:.0f} CPU s"))


def read_csv(path):
    return np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def analyse(rows, out):
    lines = ["| specimen | seed | cells | peak [kN] | travel at peak [mm] | crack | load steps | CPU s |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        crack = (f"crosses the leg at y = {r['crack_mm_or_deg']:.0f} mm" if r["specimen"] == "l_shape"
                 else f"{r['crack_mm_or_deg']:+.0f}° to the notch")
        lines.append(f"| {r['specimen'].replace('_', ' ')} | {r['seed']:.0f} | {r['cells']:.0f} | {r['peak_kN']:.2f} | "
                     f"{r['travel_at_peak_mm']:.3f} | {crack} | {r['steps']:.0f} | {r['cpu_s']:.0f} |")
    (out / "kveton_ch9.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    plot(rows, out)


def plot(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    curves = {p.name[:-len("_curve.csv")]: read_csv(p) for p in (out / "runs").glob("*_curve.csv")}
    fig, ax = plt.subplots(2, 2, figsize=(11, 9))
    for (key, title), axis in zip([("l_shape", "L-shape (§9.2)"), ("cts", "compact tension (§9.3)")], ax[0]):
        for name, c in sorted(curves.items()):
            if name.startswith(key):
                axis.plot(c[:, 0], c[:, 1], label=name.replace("_", " "))
        axis.set(xlabel="load point travel [mm]", ylabel="load [kN]", title=title + ", quasi-static")
        axis.legend()
    for (key, run), axis in zip([("l_shape", "l_shape_1"), ("cts", "cts_free_1")], ax[1]):
        outline = np.array(OUTLINES[key] + OUTLINES[key][:1])
        axis.plot(outline[:, 0], outline[:, 1], "k-", lw=1)
        path = out / "runs" / f"{run}_cracks.csv"
        if path.exists():
            b = read_csv(path)
            axis.scatter(b[:, 0], b[:, 1], s=6, c="crimson")
        axis.set(aspect="equal", xlabel="x [mm]", ylabel="y [mm]", title=f"{run.replace('_', ' ')}: cracked facets")
    fig.tight_layout()
    fig.savefig(out / "kveton_ch9.png", dpi=110)


def main():
    ap = study_arguments(__doc__, "kveton_l_shape_cts", ",".join(SPECIMENS))
    ap.add_argument("--seeds", default="1", help="node placements of the L-shape: 1-3 or 1,3,5")
    study_main(ap, FIELDS, ("specimen",), lambda r: (r["specimen"], int(r["seed"])), plan,
               lambda t: {"specimen": t[0], "seed": t[1]}, run_all, analyse)


if __name__ == "__main__":
    sys.exit(main())
