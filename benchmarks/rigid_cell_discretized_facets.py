#!/usr/bin/python3
"""Simple against discretized facets (Květoň §3.3, Figs. 3.4 and 3.5), in 3D, at two cell sizes.

The facet law at each facet's centroid (simple) or at the centroids of the triangles its vertices make with it
(discretized: [rigid_cell] facet_integration), on the two specimens of the thesis's study:
  scenes/rigid_cell_tension_prism_3d.toml       100 × 100 × 40 mm pulled between fixed plates
  scenes/rigid_cell_four_point_bending_3d.toml  160 × 40 × 40 mm, supports 140 mm and loads 40 mm apart
each at l_min 8 mm (the thesis's coarsest: five cells through the 40 mm) and 4 mm, on several node placements
(--seeds; the same placements for both integrations, so that each pair differs by the integration only). The thesis
finds the tension prism moved more by l_min than by the integration, and the bent beam stronger with discretized
facets, the less so the finer the cells. Output (--out): discretized_facets.md, discretized_facets.png.

  benchmarks/rigid_cell_discretized_facets.py                 # 3 placements at 8 mm, 1 at 4 mm: about 30 min
"""
import argparse
import os
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
SCENES = {"tension": ROOT / "scenes" / "rigid_cell_tension_prism_3d.toml",
          "bending": ROOT / "scenes" / "rigid_cell_four_point_bending_3d.toml"}
INTEGRATIONS = ("simple", "discretized")


def run(exe, scene, h5, sets, limit):
    """One run on one thread: its CPU seconds, and whether --limit stopped it (Ctrl-C, which finishes the step under
    way and writes the file; a second one two minutes later if that step does not end)."""
    cmd = [exe, "run", str(scene), "-o", str(h5), "--threads", "1"]
    for s in sets:
        cmd += ["--set", s]
    log = open(Path(h5).with_suffix(".log"), "w")
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=log)
    start, limited, signals = time.time(), False, 0
    while True:  # wait4 reaps the run and gives its CPU time; Popen.wait would reap it first
        pid, status, usage = os.wait4(p.pid, os.WNOHANG)
        if pid:
            break
        if time.time() - start > limit + 120 * signals and signals < 2:
            limited, signals = True, signals + 1
            p.send_signal(signal.SIGINT)
        time.sleep(0.2)
    code = os.waitstatus_to_exitcode(status)
    if code != 0 and not limited:
        sys.exit(f"{' '.join(cmd)}: exit {code}\n{Path(log.name).read_text()}")
    return usage.ru_utime + usage.ru_stime, limited


def curve(h5, test):
    """Displacement [mm] and load [kN]: the pulled plate's, or the load points' and the supports' reactions."""
    with h5py.File(h5, "r") as f:
        h = f["history"]
        if test == "tension":
            u, load = h["group.right.disp_x"][:], h["group.right.reaction_x"][:]
        else:
            u = -h["group.load_left.disp_y"][:]
            load = h["group.left.reaction_y"][:] + h["group.right.reaction_y"][:]
        cells = int(f["specimen/x"].shape[0])
    return u * 1e3, load * 1e-3, cells


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=str(ROOT / "build" / "mesocrack"))
    p.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "rigid_cell_discretized_facets"))
    p.add_argument("--l-min", type=float, nargs="+", default=[8.0, 4.0], help="cell sizes [mm]")
    p.add_argument("--seeds", type=int, nargs="+", default=[3, 1], help="node placements at each cell size")
    p.add_argument("--limit", type=float, default=1200, help="wall seconds a run may take before it is stopped")
    a = p.parse_args()
    if len(a.seeds) != len(a.l_min):
        sys.exit("--seeds takes one count per --l-min")
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    jobs = [(test, l, seed, integ) for l, n in zip(a.l_min, a.seeds) for seed in range(1, n + 1)
            for test in SCENES for integ in INTEGRATIONS]
    jobs.sort(key=lambda j: j[1])  # the finest cells, the longest runs, first

    def one(job):
        test, l, seed, integ = job
        h5 = out / f"{test}_l{l:g}mm_s{seed}_{integ}.h5"
        cpu, limited = run(a.exe, SCENES[test], h5, [f"specimen.l_min={l:g} mm", f"seed={seed}",
                                                     f"rigid_cell.facet_integration={integ}"], a.limit)
        u, load, cells = curve(h5, test)
        stopped = f", stopped by --limit at {load[-1] / load.max():.2f} of its peak" if limited else ""
        print(f"{test} l_min {l:g} mm placement {seed} {integ}: peak {load.max():.3f} kN, {cpu:.0f} s{stopped}",
              flush=True)
        return job, {"u": u, "load": load, "cells": cells, "cpu": cpu, "limited": limited,
                     "left": load[-1] / load.max()}

    wall = time.time()
    with ThreadPoolExecutor(2) as pool:
        results = dict(pool.map(one, jobs))
    wall = time.time() - wall
    write_table(out, a, results, wall)
    plot(out, a, results)
    for pattern in ("*.h5", "*.xdmf", "*_history.csv", "*.log"):  # the runs: the table and the figure say what they gave
        for f in out.glob(pattern):
            f.unlink()


def write_table(out, a, results, wall):
    lines = ["# Simple against discretized facets (Květoň §3.3), 3D", "",
             "Written by `benchmarks/rigid_cell_discretized_facets.py`. Each row: the same node placements run with "
             "either integration (one thread per run); the peak's mean and range over the placements, the "
             "discretized/simple ratio of each placement's peaks (mean and range), and the CPU time per run.", "",
             "| test | l_min | cells | placements | peak simple [kN] | peak discretized [kN] | ratio disc./simple "
             "| CPU simple [s] | CPU disc. [s] |", "|---|---|---|---|---|---|---|---|---|"]
    for test in SCENES:
        for l, n in zip(a.l_min, a.seeds):
            rows = {i: [results[(test, l, s, i)] for s in range(1, n + 1)] for i in INTEGRATIONS}
            peaks = {i: np.array([r["load"].max() for r in rows[i]]) for i in INTEGRATIONS}
            ratio = peaks["discretized"] / peaks["simple"]
            cpu = {i: np.mean([r["cpu"] for r in rows[i]]) for i in INTEGRATIONS}
            cells = np.mean([r["cells"] for r in rows["simple"]])

            def spread(v):
                return f"{v.mean():.3f} ({v.min():.3f}–{v.max():.3f})"
            lines.append(f"| {test} | {l:g} mm | {cells:.0f} | {n} | {spread(peaks['simple'])} | "
                         f"{spread(peaks['discretized'])} | {spread(ratio)} | {cpu['simple']:.0f} | "
                         f"{cpu['discretized']:.0f} |")
    limited = [f"{t} l_min {l:g} mm placement {seed} {i} (at {r['left']:.2f} of its peak)"
               for (t, l, seed, i), r in sorted(results.items()) if r["limited"]]
    lines += ["", f"All runs: {wall / 60:.1f} min wall on two processes, each at most {a.limit:.0f} s."]
    if limited:
        lines.append("Stopped by that limit after their peak, their CPU time a lower bound: " + "; ".join(limited) + ".")
    lines.append("")
    (out / "discretized_facets.md").write_text("\n".join(lines))


def plot(out, a, results):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    colours = dict(zip(a.l_min, ("tab:blue", "tab:red", "tab:green", "tab:purple")))
    for ax, test in zip(axes, SCENES):
        for (t, l, seed, integ), r in sorted(results.items()):
            if t != test:
                continue
            ax.plot(r["u"], r["load"], color=colours[l], ls="-" if integ == "simple" else "--", lw=1,
                    label=f"l_min {l:g} mm, {integ}" if seed == 1 else None)
        ax.set_xlabel("pulled plate's displacement [mm]" if test == "tension" else "load points' deflection [mm]")
        ax.set_ylabel("load [kN]")
        ax.set_title("tension prism 100 × 100 × 40 mm" if test == "tension" else "four-point bending 160 × 40 × 40 mm")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "discretized_facets.png", dpi=120)


if __name__ == "__main__":
    main()
