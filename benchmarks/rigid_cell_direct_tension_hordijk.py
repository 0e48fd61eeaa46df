#!/usr/bin/python3
"""The rigid-cell family calibrated from a concrete's class, then its direct tension softening against Hordijk's.

For each cell size l_min: `mesocrack calibrate scenes/rigid_cell_calibration_tension_2d.toml --target class=C30/37
--set specimen.l_min=...` (E, ν in elastic runs; f_t and G_F in full runs to 1 % of the peak), then the calibrated
scene run again. Only the peak stress and the energy dissipated are fitted: the shape of the post-peak σ(w) is
the model's, compared with Hordijk's (1991) curve σ/f_t = (1 + (c₁w/w_c)³) e^(−c₂w/w_c) − (w/w_c)(1 + c₁³) e^(−c₂),
c₁ = 3, c₂ = 6.93, w_c = 5.136 G_F/f_t, the opening w being the plate's travel less the elastic stretch σL/E.
The table says how the facets' G_t found depends on l_min (the crack's tortuosity and the damage beside it).
Output (--out): hordijk.md and hordijk.png, with the calibrated scenes and runs beside them.

  benchmarks/rigid_cell_direct_tension_hordijk.py
  benchmarks/rigid_cell_direct_tension_hordijk.py --l-min 2 1.5 1 --target class=C40/50
"""
import argparse
import re
import resource
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
SCENE = ROOT / "scenes" / "rigid_cell_calibration_tension_2d.toml"
WIDTH, STRETCH = 0.02, 0.038  # the section's width [m]; the length between the plates' cells [m]
C1, C2, WC = 3.0, 6.93, 5.136  # Hordijk (1991); w_c = 5.136 G_F/f_t


def hordijk(w, wc):
    r = np.asarray(w) / wc
    return np.where(r < 1, (1 + (C1 * r) ** 3) * np.exp(-C2 * r) - r * (1 + C1 ** 3) * np.exp(-C2), 0.0)


def children_cpu():
    u = resource.getrusage(resource.RUSAGE_CHILDREN)
    return u.ru_utime + u.ru_stime


def calibrate(exe, out, l_min, target):
    scene = out / f"calibrated_{l_min:g}mm.toml"
    cpu, wall = children_cpu(), time.time()
    r = subprocess.run([exe, "calibrate", str(SCENE), "--target", target, "--set", f"specimen.l_min={l_min} mm",
                        "-o", str(scene), "--threads", "1"], capture_output=True, text=True)
    cost = (children_cpu() - cpu, time.time() - wall)
    if r.returncode != 0:
        sys.exit(f"calibrate at l_min {l_min} mm: exit {r.returncode}\n{r.stderr}")
    iterations = int(re.search(r"converged after (\d+) iterations", r.stderr).group(1))
    knobs = {}  # the --set lines calibrate prints: contacts[0].modulus=3.37e+10 Pa ...
    for line in r.stdout.splitlines():
        key, value = line.split("=", 1)
        knobs[key.split(".")[-1]] = float(value.split()[0])
    return scene, iterations, knobs, cost


def compare(exe, scene, out, l_min, modulus):
    h5 = out / f"run_{l_min:g}mm.h5"
    subprocess.run([exe, "run", str(scene), "-o", str(h5), "--threads", "1"], check=True, capture_output=True)
    with h5py.File(h5, "r") as f:
        h = f["history"]
        s, u = h["section.y_20mm"][:], h["group.top.disp_y"][:]
        g = h["energy.dissipated"][-1] / WIDTH
        cells = int(f["specimen/x"].shape[0])
    k = int(np.argmax(s))
    w = u - s * STRETCH / modulus
    w = w[k:] - w[k]
    sigma = s[k:]
    ft = s[k]
    diff = sigma / ft - hordijk(w, WC * g / ft)
    energy = float(np.sum(0.5 * (sigma[1:] + sigma[:-1]) * np.diff(w)))
    return {"cells": cells, "ft": ft, "gf": g, "rms": float(np.sqrt(np.mean(diff ** 2))),
            "most": float(np.max(np.abs(diff))), "energy": energy, "curve": (w, sigma)}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=str(ROOT / "build" / "mesocrack"))
    p.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "rigid_cell_direct_tension_hordijk"))
    p.add_argument("--l-min", type=float, nargs="+", default=[2.0, 1.5, 1.0], help="cell sizes [mm]")
    p.add_argument("--target", default="class=C30/37")
    a = p.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    concrete = subprocess.run([a.exe, "concrete", a.target.split("class=")[1].split(",")[0]], check=True,
                              capture_output=True, text=True).stdout if "class=" in a.target else ""
    modulus = float(re.search(r'"E_ci": ([0-9.e+]+)', concrete).group(1)) if concrete else float("nan")
    rows, curves = [], []
    for l_min in a.l_min:
        scene, iterations, knobs, (cpu, wall) = calibrate(a.exe, out, l_min, a.target)
        c = compare(a.exe, scene, out, l_min, modulus)
        rows.append(f"| {l_min:g} | {c['cells']} | {iterations} | {knobs['modulus'] * 1e-9:.4g} | "
                    f"{knobs['poisson_ratio']:.3f} | {knobs['tensile_strength'] * 1e-6:.3f} | "
                    f"{knobs['fracture_energy']:.1f} | {c['ft'] * 1e-6:.3f} | {c['gf']:.1f} | {c['energy']:.1f} | "
                    f"{c['rms']:.3f} | {c['most']:.3f} | {cpu:.1f} |")
        curves.append((l_min, c))
    lines = [f"# Rigid cells calibrated to `{a.target}`, direct tension against Hordijk's softening", "",
             f"`{SCENE.relative_to(ROOT)}` (20 × 40 mm, fixed platens, 2D), one thread. Fitted: E, ν (elastic runs), "
             "f_t and G_F (full runs); predicted: the post-peak shape, compared with Hordijk's curve for the f_t "
             "and G_F the run reads.", "",
             "| l_min [mm] | cells | runs | facets' nominal E [GPa] | nominal ν | facets' f_t [MPa] | facets' G_t "
             "[N/m] | f_t [MPa] | G_F [N/m] | ∫σ dw [N/m] | RMS σ/f_t − Hordijk | largest | calibrate CPU [s] |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|", *rows, ""]
    (out / "hordijk.md").write_text("\n".join(lines))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    for l_min, c in curves:
        w, s = c["curve"]
        ax.plot(w * 1e3, s / c["ft"], label=f"rigid cells, l_min {l_min:g} mm")
    w = np.linspace(0, WC * curves[0][1]["gf"] / curves[0][1]["ft"], 200)
    ax.plot(w * 1e3, hordijk(w, w[-1]), "k--", label="Hordijk (1991)")
    ax.set_xlabel("opening w [mm]")
    ax.set_ylabel("σ / f_t")
    ax.legend(fontsize="small")
    fig.savefig(out / "hordijk.png", dpi=120)
    print("\n".join(lines))


if __name__ == "__main__":
    main()
