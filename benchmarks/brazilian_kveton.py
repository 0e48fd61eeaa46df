#!/usr/bin/python3
"""Květoň (2019) §9.4: the quasi-static Brazilian discs of rigid Voronoi cells beside Tab. 9.2.

Runs scenes/brazilian_{concrete,mortar}_{thin,thick}.toml (Tab. 9.1's parameters, D = 70 mm, T = 30 / 55 mm), each
single-threaded through the real `mesocrack run`, for several seeds of the node placement (--seeds, --mortar-seeds:
a mortar disc at l_min 2.36 mm has 4 600 / 8 500 cells and takes minutes to an hour, a concrete one seconds).
Each run: the peak load P and the splitting strength (9.2) with P₁ = P₂ = P, 2P / (π T D).
Output (--out): results.csv (one row per run) and brazilian.md (ours, mean ± standard deviation over the seeds,
beside Květoň's simulations and Jin et al.'s experiments of Tab. 9.2).

  benchmarks/brazilian_kveton.py --jobs 2
  benchmarks/brazilian_kveton.py --only concrete_thin,concrete_thick --seeds 1-10
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from uniaxial_accuracy import ROOT, append_rows, mean_cv, seed_list, study_arguments, study_main, timed_run  # noqa: E402

DIAMETER = 0.07
THICKNESS = {"thin": 0.03, "thick": 0.055}
# Tab. 9.2: peak [kN] and strength [MPa], Jin et al.'s experiments and Květoň's simulations (thin: his fit).
TAB_9_2 = {"concrete_thin": (8.71, 2.64, 8.71, 2.64), "concrete_thick": (15.71, 2.60, 15.24, 2.52),
           "mortar_thin": (11.44, 3.47, 11.44, 3.47), "mortar_thick": (20.26, 3.35, 23.01, 3.80)}
FIELDS = ["disc", "seed", "cells", "peak_kN", "strength_MPa", "steps", "cpu_s"]


def plan(a):
    todo = []
    for disc in a.only.split(","):
        if disc not in TAB_9_2:
            sys.exit(f"--only: '{disc}' is not one of {', '.join(TAB_9_2)}")
        for s in seed_list(a.mortar_seeds if disc.startswith("mortar") else a.seeds):
            todo.append((disc, s))
    return sorted(todo, key=lambda t: (not t[0].startswith("mortar"), t))  # the longest first


def run_all(exe, out, jobs, todo, csv_path):
    def one(item):
        disc, seed = item
        s, cpu, _ = timed_run(exe, ROOT / "scenes" / f"brazilian_{disc}.toml", out / "runs" / f"{disc}_{seed}.h5",
                              [f"seed={seed}"])
        peak = s["results"]["peak_load"]
        thickness = THICKNESS[disc.split("_")[1]]
        return {"disc": disc, "seed": seed, "cells": s["specimen"]["cells"], "peak_kN": peak * 1e-3,
                "strength_MPa": 2 * peak / (math.pi * thickness * DIAMETER) * 1e-6, "steps": s["steps"],
                "cpu_s": cpu}

    append_rows(csv_path, FIELDS, jobs, todo, one,
                lambda r: (f"{r['disc']} seed {r['seed']}: {r['cells']} cells, peak {r['peak_kN']:.2f} kN "
                           f"({r['strength_MPa']:.2f} MPa), {r['cpu_s']:.0f} CPU s"))


def analyse(rows, out):
    lines = ["| disc | cells | seeds | peak, ours [kN] | strength, ours [MPa] | Květoň [kN] | experiment [kN] | "
             "ours / Květoň | CPU s per run |", "|---|---|---|---|---|---|---|---|---|"]
    for disc, (exp_p, _, sim_p, _) in TAB_9_2.items():
        runs = [r for r in rows if r["disc"] == disc]
        if not runs:
            continue
        p, p_cv = mean_cv([r["peak_kN"] for r in runs])
        f, f_cv = mean_cv([r["strength_MPa"] for r in runs])
        cells = sum(r["cells"] for r in runs) / len(runs)
        cpu = sum(r["cpu_s"] for r in runs) / len(runs)
        spread = lambda m, cv: f"{m:.2f} ± {m * cv:.2f}" if len(runs) > 1 else f"{m:.2f}"  # noqa: E731
        fit = " (his fit)" if disc.endswith("thin") else ""
        lines.append(f"| {disc.replace('_', ' ')} | {cells:.0f} | {len(runs)} | {spread(p, p_cv)} | "
                     f"{spread(f, f_cv)} | {sim_p:.2f}{fit} | {exp_p:.2f} | {p / sim_p:.3f} | {cpu:.0f} |")
    (out / "brazilian.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


def main():
    ap = study_arguments(__doc__, "brazilian_kveton", ",".join(TAB_9_2))
    ap.add_argument("--seeds", default="1-6", help="node placements of the concrete discs: 1-6 or 1,3,5")
    ap.add_argument("--mortar-seeds", default="1", help="node placements of the mortar discs")
    study_main(ap, FIELDS, ("disc",), lambda r: (r["disc"], int(r["seed"])), plan, lambda t: {"disc": t[0], "seed": t[1]},
               run_all, analyse)


if __name__ == "__main__":
    sys.exit(main())
