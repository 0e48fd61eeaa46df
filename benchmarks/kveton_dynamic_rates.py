#!/usr/bin/python3
"""Květoň (2019) §9.2–9.3 at rates: the L-shaped and compact-tension specimens of rigid cells in implicit dynamics.

Runs scenes/l_shape_dynamic_kveton.toml at the thesis's rates 0.1–2.4 m/s and scenes/compact_tension_dynamic_
kveton.toml at 0.035–4.3 m/s, single-threaded through the real `mesocrack run`, each rate with the rate-independent
facet law (the thesis's reference) and with the rate-dependent one of (8.16)–(8.17), set 1 of §9.2.3 (c₀ 1e-5 /s,
c₁ 0.05). The plate moves at its full rate from the first step, as in the thesis's reference runs. Steps of
min(2 µm / v, 20 µs); each run goes to a fixed travel of the load plate (L 0.5 mm, CTS 0.3 mm: past the
quasi-static peaks at 0.15–0.18 mm and 0.05 mm), since at high rates the load falls, as Květoň found, when the
cells under the plate break, long before the support has felt the peak. Each run: the largest loading force (the
load plate's reaction, with the inertia it meets), the largest support reaction, where the crack ran.
Output (--out): results.csv, runs/<run>_curve.csv, runs/<run>_cracks.csv, kveton_rates.md, kveton_rates.png.

  benchmarks/kveton_dynamic_rates.py --jobs 2
  benchmarks/kveton_dynamic_rates.py --only cts --laws reference
"""
import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from kveton_l_shape_cts import OUTLINES, broken_facets, crack_measure  # noqa: E402
from uniaxial_accuracy import ROOT, append_rows, study_arguments, study_main, timed_run  # noqa: E402

# specimen: scene, loading force, support reaction, load-point travel, its sign along y, rates [m/s], travel [m].
SPECIMENS = {
    "l_shape": ("l_shape_dynamic_kveton", "group.load.reaction_y", "group.support.reaction_y", "group.load.disp_y",
                -1, [0.1, 0.35, 0.74, 1.0, 2.4], 0.5e-3),
    "cts": ("compact_tension_dynamic_kveton", "group.load.reaction_y", "group.support.reaction_y",
            "group.load.disp_y", 1, [0.035, 0.1, 0.5, 1.0, 2.0, 4.3], 0.3e-3),
}
LAWS = {"reference": [], "set1": ["contacts[0].rate_c0=1e-5", "contacts[0].rate_c1=0.05"]}
FIELDS = ["specimen", "law", "rate", "cells", "load_kN", "load_travel_mm", "reaction_kN", "reaction_time_us",
          "cracked", "crack_mm_or_deg", "steps", "cpu_s"]


def plan(a):
    todo = []
    for sp in a.only.split(","):
        if sp not in SPECIMENS:
            sys.exit(f"--only: '{sp}' is not one of {', '.join(SPECIMENS)}")
        for law in a.laws.split(","):
            if law not in LAWS:
                sys.exit(f"--laws: '{law}' is not one of {', '.join(LAWS)}")
            todo += [(sp, law, v) for v in SPECIMENS[sp][5]]
    return todo


def overrides(sp, law, rate):
    travel = SPECIMENS[sp][6]
    dt = min(2e-6 / rate, 20e-6)
    sign = SPECIMENS[sp][4]
    return LAWS[law] + [f"groups[1].velocity=[0, {sign * rate}, 0]", f"timestep.fixed={dt}",
                        f"run.steps={int(round(travel / (rate * dt)))}", "run.stop[0].after_time=1e9",
                        "output.frame_every=1000000"]


def run_all(exe, out, jobs, todo, csv_path):
    def one(item):
        sp, law, rate = item
        scene, load, support, travel, sign = SPECIMENS[sp][:5]
        name = f"{sp}_{law}_{rate:g}"
        h5 = out / "runs" / f"{name}.h5"
        s, cpu, _ = timed_run(exe, ROOT / "scenes" / f"{scene}.toml", h5, overrides(sp, law, rate), keep=True)
        with h5py.File(h5, "r") as f:
            h = f["history"]
            t, p, r, u = h["time"][:], sign * h[load][:], -sign * h[support][:], sign * h[travel][:]
            cracked = int(h["facets.cracked"][-1])
            broken = broken_facets(f)
        for g in h5.parent.glob(h5.stem + ".*"):
            g.unlink()
        (h5.parent / f"{h5.stem}_history.csv").unlink()
        i, j = int(np.argmax(p)), int(np.argmax(r))
        np.savetxt(out / "runs" / f"{name}_curve.csv", np.c_[t * 1e6, u * 1e3, p * 1e-3, r * 1e-3], delimiter=",",
                   fmt="%.6g", header="time_us,travel_mm,load_kN,reaction_kN", comments="")
        np.savetxt(out / "runs" / f"{name}_cracks.csv", broken, delimiter=",", fmt="%.3f",
                   header="x_mm,y_mm,z_mm", comments="")
        return {"specimen": sp, "law": law, "rate": rate, "cells": s["specimen"]["cells"], "load_kN": p[i] * 1e-3,
                "load_travel_mm": u[i] * 1e3, "reaction_kN": r[j] * 1e-3, "reaction_time_us": t[j] * 1e6,
                "cracked": cracked, "crack_mm_or_deg": crack_measure("l_shape" if sp == "l_shape" else "cts", broken),
                "steps": s["steps"], "cpu_s": cpu}

    append_rows(csv_path, FIELDS, jobs, todo, one,
                lambda r: (f"{r['specimen']} {r['law']} {r['rate']:g} m/s: load {r['load_kN']:.2f} kN, reaction "
                           f"{r['reaction_kN']:.2f} kN, {r['cpu_s']:.0f} CPU s"))


def analyse(rows, out):
    lines = ["| specimen | facet law | rate [m/s] | largest loading force [kN] | at travel [mm] | largest support "
             "reaction [kN] | at [µs] | cracked facets | crack | steps | CPU s |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["specimen"], r["law"], r["rate"])):
        crack = (f"crosses the leg at y = {r['crack_mm_or_deg']:.0f} mm" if r["specimen"] == "l_shape"
                 else f"{r['crack_mm_or_deg']:+.0f}° to the notch")
        lines.append(f"| {r['specimen'].replace('_', '-')} | {r['law']} | {r['rate']:g} | {r['load_kN']:.2f} | "
                     f"{r['load_travel_mm']:.3f} | {r['reaction_kN']:.2f} | {r['reaction_time_us']:.0f} | "
                     f"{r['cracked']:.0f} | {crack} | {r['steps']:.0f} | {r['cpu_s']:.0f} |")
    (out / "kveton_rates.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    plot(rows, out)


def plot(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(2, 2, figsize=(11, 9))
    for sp, axis in zip(SPECIMENS, ax[0]):
        for law, style in zip(LAWS, ["o-", "s--"]):
            rs = sorted((r for r in rows if r["specimen"] == sp and r["law"] == law), key=lambda r: r["rate"])
            if not rs:
                continue
            v = [r["rate"] for r in rs]
            axis.plot(v, [r["load_kN"] for r in rs], style, label=f"loading force, {law}")
            axis.plot(v, [r["reaction_kN"] for r in rs], style, mfc="none", label=f"support reaction, {law}")
        axis.set(xscale="log", xlabel="displacement rate [m/s]", ylabel="largest force [kN]",
                 title=("L-shape (§9.2, Fig. 9.5)" if sp == "l_shape" else "compact tension (§9.3, Fig. 9.12)"))
        axis.legend(fontsize=8)
    for sp, axis in zip(SPECIMENS, ax[1]):
        outline = np.array(OUTLINES["l_shape" if sp == "l_shape" else "cts"])
        outline = np.vstack([outline, outline[:1]])
        axis.plot(outline[:, 0], outline[:, 1], "k-", lw=1)
        rates = SPECIMENS[sp][5]
        for rate, colour in zip([rates[0], rates[-1]], ["royalblue", "crimson"]):
            path = out / "runs" / f"{sp}_reference_{rate:g}_cracks.csv"
            if path.exists():
                b = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
                if len(b):
                    axis.scatter(b[:, 0], b[:, 1], s=5, c=colour, label=f"{rate:g} m/s")
        axis.set(aspect="equal", xlabel="x [mm]", ylabel="y [mm]", title=f"{sp.replace('_', '-')}: cracked facets")
        axis.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "kveton_rates.png", dpi=110)


def main():
    ap = study_arguments(__doc__, "kveton_dynamic_rates", ",".join(SPECIMENS))
    ap.add_argument("--laws", default=",".join(LAWS), help="facet laws: reference (rate independent), set1")
    study_main(ap, FIELDS, ("specimen", "law"), lambda r: (r["specimen"], r["law"], float(r["rate"])), plan,
               lambda t: {"specimen": t[0], "law": t[1], "rate": t[2]}, run_all, analyse)


if __name__ == "__main__":
    sys.exit(main())
