#!/usr/bin/python3
"""One mesostructure, two models: a Brazilian disc of three-phase concrete through the explicit bonded-particle
model and the rigid-cell model, side by side.

Runs scenes/brazilian_meso_explicit_2d.toml (bonded discs, explicit central differences) and
scenes/brazilian_meso_rigid_cell_2d.toml (rigid Voronoi cells, static secant iteration) with the same seed: the same
aggregates (the same grading laid in the same square domain by the same draws), each phase with the same
macroscopic properties (Tang's Table 7.1). Each runs single-threaded through the real `mesocrack run`; then
`mesocrack report` draws each one's cracks. Output (--out): two_families.md (peak load, splitting strength 2P/(πD),
travel at the peak, cracks, CPU and wall time of each) and two_families.png (both load–displacement curves and both
crack patterns), with each run's .h5 and report PNGs beside them.

  benchmarks/brazilian_two_families.py
  benchmarks/brazilian_two_families.py --seed 5 --out out/two_families_5
"""
import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from uniaxial_accuracy import ROOT, timed_run  # noqa: E402

DIAMETER = 0.07  # [m], both scenes
# family: scene, the history of the load [N per m of thickness], that of the plates' approach and its sign, and the
# picture of its cracks `report` draws (the bonds broken; the facets by their damage).
FAMILIES = {
    "explicit (bonded particles)": ("brazilian_meso_explicit_2d", "group.bottom.reaction_y", "closure", 1, "cracks"),
    "rigid cells": ("brazilian_meso_rigid_cell_2d", "group.bottom.reaction_y", "group.top.disp_y", -1, "cells"),
}


def run_family(exe, out, seed, scene, load, travel, sign, picture):
    h5 = out / f"{scene}.h5"
    summary, cpu, wall = timed_run(exe, ROOT / "scenes" / f"{scene}.toml", h5, [f"seed={seed}"], keep=True)
    subprocess.run([exe, "report", str(h5)], check=True, capture_output=True)
    with h5py.File(h5, "r") as f:
        h = f["history"]
        p, u = h[load][:], sign * h[travel][:]
        kind = f["cracks/kind"][:] if "cracks" in f else np.zeros(0)
    i = int(np.argmax(p))
    spec = summary["specimen"]
    bodies = spec.get("cells") or summary["particles"]
    return {"scene": scene, "bodies": int(bodies), "steps": int(summary["steps"]), "peak": p[i],
            "travel_at_peak": u[i], "strength": 2 * p[i] / (math.pi * DIAMETER), "breaks": int((kind == 0).sum()),
            "aggregates": int(spec.get("aggregates", 0)), "cpu": cpu, "wall": wall, "curve": (u, p),
            "cracks_png": out / f"{scene}_{picture}.png"}


def table(runs):
    lines = ["| model | bodies | aggregates | steps | peak [kN/m] | 2P/(πD) [MPa] | travel at peak [µm] | broken "
             "bonds / cracked facets | CPU [s] | wall [s] |", "|---|---|---|---|---|---|---|---|---|---|"]
    for name, r in runs.items():
        lines.append(f"| {name} | {r['bodies']} | {r['aggregates']} | {r['steps']} | {r['peak'] * 1e-3:.1f} | "
                     f"{r['strength'] * 1e-6:.2f} | {r['travel_at_peak'] * 1e6:.1f} | {r['breaks']} | {r['cpu']:.1f} | "
                     f"{r['wall']:.1f} |")
    return lines


def figure(runs, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig = plt.figure(figsize=(13, 21))
    grid = fig.add_gridspec(3, 1, height_ratios=[1, 1.4, 1.2])
    ax = fig.add_subplot(grid[0])
    for name, r in runs.items():
        u, p = r["curve"]
        ax.plot(u * 1e6, p * 1e-3, label=f"{name}: {r['cpu']:.0f} CPU s")
    ax.set(xlabel="plates' approach [µm]", ylabel="load [kN per m of thickness]",
           title="Brazilian disc, D = 70 mm, three-phase concrete, one mesostructure")
    ax.legend()
    for k, (name, r) in enumerate(runs.items()):
        sub = fig.add_subplot(grid[1 + k])
        if r["cracks_png"].exists():
            sub.imshow(plt.imread(r["cracks_png"]))
        sub.set_axis_off()
        sub.set_title(name)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesocrack", default=str(ROOT / "build" / "mesocrack"))
    ap.add_argument("--out", default=str(ROOT / "out" / "brazilian_two_families"))
    ap.add_argument("--seed", type=int, default=3, help="the mesostructure (aggregates) and both specimens")
    a = ap.parse_args()
    if not Path(a.mesocrack).exists():
        sys.exit(f"{a.mesocrack}: not found (build first: make demo, or give --mesocrack)")
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    runs = {}
    for name, family in FAMILIES.items():
        print(f"{name}: {family[0]} ...", flush=True)
        runs[name] = run_family(a.mesocrack, out, a.seed, *family)
    lines = table(runs)
    figure(runs, out / "two_families.png")
    text = [f"# One mesostructure (seed {a.seed}), two models", ""] + lines + [
        "", "![curves and crack patterns](two_families.png)", ""]
    (out / "two_families.md").write_text("\n".join(text))
    (out / "two_families.json").write_text(json.dumps(
        {n: {k: v for k, v in r.items() if k not in ("curve", "cracks_png")} for n, r in runs.items()}, indent=1))
    print("\n".join(lines))
    print(f"-> {out / 'two_families.md'}, {out / 'two_families.png'}")


if __name__ == "__main__":
    sys.exit(main())
