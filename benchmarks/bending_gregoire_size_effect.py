#!/usr/bin/python3
"""Rigid cells calibrated on direct tension, then predicting notched beams: Grégoire et al. (2013) and a size series.

1. `mesocrack calibrate scenes/rigid_cell_calibration_tension_2d.toml --target E=37GPa,nu=0.2,ft=3.9MPa,Gf=143.2N/m
   --set specimen.l_min=...`: the facets' E, ν, f_t, G_t found on the 20 × 40 mm tension prism (fixed platens).
   These are the values pypd's model of the test uses (mark-hobbs/pypd examples/half_notched_beam.py); nothing
   below is fitted on a beam.
2. `scenes/bending_gregoire_rigid_cell_2d.toml` (D = 50 mm: 175 × 50 mm, span 125 mm, notch D/2, 50 mm thick,
   CMOD control) with the calibrated facets, and once with the concrete's values at face value: load against CMOD
   beside the test's two curves (pypd examples/data/half_notched_beam.csv, decimated into TEST_BAND below).
3. Geometrically similar beams of depth D (length 3.5 D, span 2.5 D, notch D/2; the notch's width, the plates'
   height and the cells over the ligament stay the same size; the cells coarsen from D/5 + 5 l_min either side of
   the notch, where the beam stays elastic, to D/12 or l_max), the nominal strength σ_N = 3 F S / (2 b D²)
   against D, and Bažant's
   size-effect law σ_N = B f_t / sqrt(1 + D/D₀) fitted by least squares on 1/σ_N² = (1 + D/D₀)/(B f_t)²;
   D₀ against the concrete's l_ch = E G_F / f_t².
Output (--out): gregoire.md, gregoire.png, the calibrated scene and the runs.

  benchmarks/bending_gregoire_size_effect.py                # l_min 2 mm, l_max 8 mm, D = 25, 50, 100, 200 mm
  benchmarks/bending_gregoire_size_effect.py --sizes 50 --no-face-value
  benchmarks/bending_gregoire_size_effect.py --sizes 50 --integration discretized   # Květoň §3.3's facets
"""
import argparse
import os
import re
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parent.parent
PRISM = ROOT / "scenes" / "rigid_cell_calibration_tension_2d.toml"
BEAM = ROOT / "scenes" / "bending_gregoire_rigid_cell_2d.toml"
CONCRETE = {"E": 37e9, "nu": 0.2, "ft": 3.9e6, "Gf": 143.2}  # as pypd models Grégoire et al.'s concrete
THICKNESS = 0.05  # b [m]; 2D reactions are per metre of thickness
NOTCH_WIDTH = 0.002  # [m], not given in the sources found
# Grégoire et al. (2013), D = 50 mm, half-notched: CMOD [mm], the two test curves' load [N] (pypd's csv, nearest
# row to each CMOD). Peaks 932.8 N at CMOD 0.018 mm and 1113.9 N at 0.023 mm.
TEST_BAND = np.array([
    [0.005, 365.5, 427.0], [0.010, 679.0, 746.6], [0.015, 893.6, 959.5], [0.018, 932.0, 1058.9],
    [0.023, 863.2, 1113.9], [0.030, 789.2, 1018.9], [0.040, 714.1, 976.2], [0.050, 636.8, 896.7],
    [0.075, 453.6, 708.4], [0.100, 379.9, 644.0], [0.150, 256.4, 527.8], [0.200, 169.6, 411.5]])
TEST_PEAKS = (932.8, 1113.9)


def mm(x):
    return f"{x * 1e3:.6g} mm"


def box(name, i, lo, hi):
    return [f"groups[{i}].box_lo=[{lo[0]:.9g},{lo[1]:.9g}]", f"groups[{i}].box_hi=[{hi[0]:.9g},{hi[1]:.9g}]"]


def beam_geometry(depth, l_min, l_max):
    """--set lines of a beam of depth D similar to the scene's D = 50 mm (groups in the scene's order): cells l_min
    apart over the ligament and D/5 + 5 l_min to either side, coarsening beyond to D/12 (at most l_max)."""
    d, s = depth, depth / 0.05
    mid, half = 1.75 * d, NOTCH_WIDTH / 2
    xs = [0, mid - half, mid - half, mid + half, mid + half, 3.5 * d, 3.5 * d, 0]
    ys = [0, 0, d / 2, d / 2, 0, 0, d, d]
    fine, coarse = 0.2 * d + 5 * l_min, min(l_max, max(l_min, d / 12))
    sets = [f"specimen.l_min={mm(l_min)}", f"specimen.l_max={mm(coarse)}", f"specimen.fine_lo=[{mid - fine:.9g},0]",
            f"specimen.fine_hi=[{mid + fine:.9g},{d:.9g}]",
            "specimen.vertices_x=[" + ",".join(f"{x:.9g}" for x in xs) + "]",
            "specimen.vertices_y=[" + ",".join(f"{y:.9g}" for y in ys) + "]"]
    # A plate 2 l high and 3 l wide holds a node wherever the cells are l apart (a saturated placement leaves no
    # point of it farther than l from a node, and none lies within l/2 of the surface); at least 4 × 2.5 mm.
    plates = [("left", 0.5 * d, 0, coarse), ("right", 3.0 * d, 0, coarse), ("load", mid, None, l_min),
              ("mouth_left", mid - 0.01 * s, 0, l_min), ("mouth_right", mid + 0.01 * s, 0, l_min)]
    for i, (name, x, y, l) in enumerate(plates):
        height, width = max(0.0025, 2 * l), max(0.004 * s, 3 * l)
        y = d - height if y is None else y
        sets += box(name, i, (x - width / 2, y), (x + width / 2, y + height))
    # CMOD steps and the end of the record grow with D: the opening at the peak does (0.5 µm steps at D = 50 mm)
    sets += [f"rigid_cell.opening_control.rate={s:.6g} mm/s", f"run.stop[0].above={2e-4 * s:.6g}",
             f"run.steps={int(1000 * max(1.0, s))}"]
    return sets


def run(exe, scene, out_h5, sets):
    cmd = [exe, "run", str(scene), "-o", str(out_h5), "--threads", "1"]
    for s in sets:
        cmd += ["--set", s]
    wall = time.time()
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _, status, usage = os.wait4(p.pid, 0)
    err = p.stderr.read()
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"{' '.join(cmd)}: exit {os.waitstatus_to_exitcode(status)}\n{err}")
    return usage.ru_utime + usage.ru_stime, time.time() - wall


def read_beam(h5):
    with h5py.File(h5, "r") as f:
        h = f["history"]
        load = (h["group.left.reaction_y"][:] + h["group.right.reaction_y"][:]) * THICKNESS
        cmod = h["cmod"][:]
        cells = int(f["specimen/x"].shape[0])
    return cmod, load, cells


def platen_sets(platens):
    """--set lines of the tension prism's platens: fixed (the scene's), or free to turn (translations held)."""
    return [] if platens == "fixed" else ["groups[0].fix=x y", "groups[1].fix=x y"]


def calibrate(exe, out, l_min, target, sets=()):
    """The facets' --set lines calibrate finds on the tension prism at l_min (sets: more changes to the prism)."""
    scene = out / f"calibrated_{l_min * 1e3:g}mm.toml"
    cmd = [exe, "calibrate", str(PRISM), "--target", target, "--set", f"specimen.l_min={mm(l_min)}"]
    for s in sets:
        cmd += ["--set", s]
    r = subprocess.run(cmd + ["-o", str(scene), "--threads", "1"], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"calibrate: exit {r.returncode}\n{r.stderr}")
    runs = int(re.search(r"converged after (\d+) iterations", r.stderr).group(1))
    return [line for line in r.stdout.split("\n") if line.startswith("contacts[")], runs


def band_verdict(cmod, load):
    """The predicted load at the band's CMODs, and how far outside the band it lies (0 inside), in N."""
    at = np.interp(TEST_BAND[:, 0] * 1e-3, cmod, load, right=np.nan)
    outside = np.maximum(TEST_BAND[:, 1] - at, 0) + np.maximum(at - TEST_BAND[:, 2], 0)
    return at, outside


def size_effect_fit(depths, sigma):
    """Bažant's law through 1/σ_N² = a + c D: B f_t = a^(-1/2), D₀ = a/c."""
    c, a = np.polyfit(depths, 1 / np.asarray(sigma) ** 2, 1)
    return 1 / np.sqrt(a), a / c


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=str(ROOT / "build" / "mesocrack"))
    p.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "bending_gregoire_size_effect"))
    p.add_argument("--l-min", type=float, default=2.0, help="cell size over the ligament [mm]")
    p.add_argument("--l-max", type=float, default=8.0, help="cell size far from it, at most [mm] (D/12 if less)")
    p.add_argument("--sizes", type=float, nargs="+", default=[25, 50, 100, 200], help="depths D [mm]")
    p.add_argument("--no-face-value", action="store_true", help="skip the D = 50 mm beam with uncalibrated facets")
    p.add_argument("--jobs", type=int, default=2, help="runs at once, one thread each")
    p.add_argument("--platens", choices=("fixed", "rotating"), default="fixed", help="the tension prism's platens")
    p.add_argument("--integration", choices=("simple", "discretized"), default="simple",
                   help="the facets' integration (Květoň §3.3), in the prism and the beams alike")
    a = p.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    l_min = a.l_min * 1e-3
    c = CONCRETE
    target = f"E={c['E']:g}Pa,nu={c['nu']:g},ft={c['ft']:g}Pa,Gf={c['Gf']:g}N/m"
    cpu0 = time.process_time()
    integration = [f"rigid_cell.facet_integration={a.integration}"]
    knobs, cal_runs = calibrate(a.exe, out, l_min, target, platen_sets(a.platens) + integration)
    jobs = [(f"D{d:g}", d * 1e-3, knobs) for d in a.sizes]
    if not a.no_face_value:
        jobs.append(("D50_face_value", 0.05, []))

    def one(job):
        name, depth, facet = job
        h5 = out / f"{name}.h5"
        cost = run(a.exe, BEAM, h5, beam_geometry(depth, l_min, a.l_max * 1e-3) + facet + integration)
        return name, depth, h5, cost

    with ThreadPoolExecutor(a.jobs) as pool:
        done = list(pool.map(one, jobs))
    rows, series, curves = [], [], {}
    for name, depth, h5, (cpu, wall) in done:
        cmod, load, cells = read_beam(h5)
        k = int(np.argmax(load))
        sigma = 1.5 * load[k] * 2.5 * depth / (THICKNESS * depth ** 2)
        rows.append(f"| {name} | {depth * 1e3:g} | {cells} | {load[k]:.0f} | {cmod[k] * 1e3:.4f} | "
                    f"{sigma * 1e-6:.3f} | {sigma / c['ft']:.3f} | {cpu:.0f} |")
        curves[name] = (cmod, load)
        if name != "D50_face_value":
            series.append((depth, sigma))
    lines = [f"# Rigid cells calibrated on direct tension, predicting notched beams (l_min {a.l_min:g} mm over the "
             f"ligament, D/12 or at most {a.l_max:g} mm far from it)", "",
             f"Concrete (as pypd models Grégoire et al. 2013): E {c['E'] * 1e-9:g} GPa, ν {c['nu']:g}, "
             f"f_t {c['ft'] * 1e-6:g} MPa, G_F {c['Gf']:g} N/m; l_ch = E G_F/f_t² = "
             f"{c['E'] * c['Gf'] / c['ft'] ** 2 * 1e3:.0f} mm. Calibrated on `{PRISM.relative_to(ROOT)}` ({a.platens} "
             f"platens, {a.integration} facets in the prism and the beams) in "
             f"{cal_runs} runs: " + ", ".join(f"`{k}`" for k in knobs) + ".", "",
             "| beam | D [mm] | cells | peak F [N] | CMOD at peak [mm] | σ_N = 3FS/(2bD²) [MPa] | σ_N/f_t | "
             "CPU [s] |", "|---|---|---|---|---|---|---|---|", *rows, "",
             f"Test (D = 50 mm): peaks {TEST_PEAKS[0]:.0f} and {TEST_PEAKS[1]:.0f} N.", ""]
    if "D50" in curves:
        at, outside = band_verdict(*curves["D50"])
        lines += ["| CMOD [mm] | test low [N] | test high [N] | predicted [N] | outside the band [N] |",
                  "|---|---|---|---|---|"]
        lines += [f"| {b[0]:.3f} | {b[1]:.0f} | {b[2]:.0f} | {p_:.0f} | {o:.0f} |"
                  for b, p_, o in zip(TEST_BAND, at, outside)]
        lines.append("")
    fit = None
    if len(series) >= 3:
        depths, sigma = map(np.array, zip(*sorted(series)))
        bft, d0 = size_effect_fit(depths, sigma)
        model = bft / np.sqrt(1 + depths / d0)
        fit = (depths, sigma, bft, d0)
        lines += [f"Bažant's law fitted to the {len(depths)} beams: B f_t = {bft * 1e-6:.3f} MPa (B = "
                  f"{bft / c['ft']:.3f}), D₀ = {d0 * 1e3:.0f} mm = {d0 / (c['E'] * c['Gf'] / c['ft'] ** 2):.2f} "
                  f"l_ch; largest misfit {np.max(np.abs(sigma / model - 1)) * 100:.1f} % of σ_N.", ""]
    lines.append(f"Total CPU of the study {time.process_time() - cpu0 + sum(r[3][0] for r in done):.0f} s.")
    (out / "gregoire.md").write_text("\n".join(lines) + "\n")
    plot(out, curves, fit, c)
    print("\n".join(lines))


def plot(out, curves, fit, c):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2 if fit else 1, figsize=(11 if fit else 6, 4), constrained_layout=True,
                             squeeze=False)
    ax = axes[0][0]
    ax.fill_between(TEST_BAND[:, 0], TEST_BAND[:, 1], TEST_BAND[:, 2], color="0.8", label="test (Grégoire 2013)")
    for name, style in (("D50", "C0-"), ("D50_face_value", "C3--")):
        if name in curves:
            cmod, load = curves[name]
            label = "rigid cells, calibrated" if name == "D50" else "rigid cells, facets at face value"
            ax.plot(cmod * 1e3, load, style, label=label)
    ax.set_xlabel("CMOD [mm]")
    ax.set_ylabel("load F [N]")
    ax.set_xlim(0, 0.2)
    ax.set_title("D = 50 mm, half-notched")
    ax.legend(fontsize="small")
    if fit:
        depths, sigma, bft, d0 = fit
        ax = axes[0][1]
        d = np.geomspace(depths.min() / 2, depths.max() * 2, 100)
        ax.loglog(depths * 1e3, sigma / c["ft"], "C0o", label="rigid cells")
        ax.loglog(d * 1e3, bft / np.sqrt(1 + d / d0) / c["ft"], "k-", label="Bažant's law, fitted")
        ax.loglog(d * 1e3, bft / np.sqrt(d / d0) / c["ft"], "k:", label="LEFM asymptote")
        ax.axvline(d0 * 1e3, color="0.5", lw=0.8)
        ax.set_xlabel("D [mm]")
        ax.set_ylabel("σ_N / f_t")
        ax.legend(fontsize="small")
    fig.savefig(out / "gregoire.png", dpi=120)


if __name__ == "__main__":
    main()
