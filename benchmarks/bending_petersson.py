#!/usr/bin/python3
"""Petersson's notched beam as rigid cells, calibrated on direct tension at the beam's l_min, then predicted.

1. `mesocrack calibrate scenes/rigid_cell_calibration_tension_2d.toml --target E=30GPa,nu=0.2,ft=3.33MPa,Gf=137N/m`
   on the prism scaled to the beam's l_min (20 × 40 mm at 2 mm: 25 × 50 mm at 2.5 mm, the plates, the strain box,
   the section and the pull with it), so that the cells per width stay as the scene has them.
2. `scenes/bending_petersson_rigid_cell_2d.toml` with the calibrated facets, and once at face value: load against
   the deflection under the notch, beside the two points code_aster's validation case SSNP166 checks (a cohesive
   crack along the ligament, E 30 GPa, ν 0.18, f_t 3.33 MPa, G_F 137 N/m; astest/ssnp166a.comm). Those are a
   model's answers, not Petersson's measurements, which the sources found show only as a figure.
Output (--out): petersson.md, petersson.png, the calibrated scene and the runs.

  benchmarks/bending_petersson.py            # l_min 2.5 mm over the ligament, 10 mm beyond
"""
import argparse
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import h5py
import numpy as np

from bending_gregoire_size_effect import calibrate, mm, platen_sets, run

ROOT = Path(__file__).resolve().parent.parent
BEAM = ROOT / "scenes" / "bending_petersson_rigid_cell_2d.toml"
CONCRETE = {"E": 30e9, "nu": 0.2, "ft": 3.33e6, "Gf": 137.0}  # as SSNP166 models Petersson's concrete
THICKNESS = 0.05  # [m]; 2D reactions are per metre of thickness
# code_aster SSNP166 (astest/ssnp166a.comm, TEST_TABLE): deflection [mm], load [N] of its cohesive-crack model.
SSNP166 = np.array([[0.365, 774.0], [0.607, 598.0]])
PRISM_L_MIN = 0.002  # the calibration scene's l_min [m]


def scaled_prism(l_min):
    """--set lines scaling the calibration prism by l_min / 2 mm (its groups in the scene's order)."""
    k = l_min / PRISM_L_MIN
    w, h = 0.02 * k, 0.04 * k

    def pair(x, y):
        return f"[{x:.9g},{y:.9g}]"
    return [f"specimen.size={pair(w, h)}", f"groups[0].box_hi={pair(w, 0.002 * k)}",
            f"groups[1].box_lo={pair(0, h - 0.002 * k)}", f"groups[1].box_hi={pair(w, h)}",
            f"groups[1].velocity={pair(0, 0.001 * k)}", f"rigid_cell.strain.box_lo={pair(0, h / 4)}",
            f"rigid_cell.strain.box_hi={pair(w, 3 * h / 4)}", f"rigid_cell.sections.at=[{h / 2:.9g}]"]


def read_beam(h5):
    with h5py.File(h5, "r") as f:
        h = f["history"]
        load = (h["group.left.reaction_y"][:] + h["group.right.reaction_y"][:]) * THICKNESS
        deflection = -h["group.mouth.disp_y"][:]
        cells = int(f["specimen/x"].shape[0])
    return deflection, load, cells


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--exe", default=str(ROOT / "build" / "mesocrack"))
    p.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "bending_petersson"))
    p.add_argument("--l-min", type=float, default=2.5, help="cell size over the ligament [mm]")
    p.add_argument("--l-max", type=float, default=10.0, help="cell size far from it [mm]")
    p.add_argument("--platens", choices=("fixed", "rotating"), default="fixed", help="the tension prism's platens")
    a = p.parse_args()
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    l_min, l_max = a.l_min * 1e-3, a.l_max * 1e-3
    c = CONCRETE
    target = f"E={c['E']:g}Pa,nu={c['nu']:g},ft={c['ft']:g}Pa,Gf={c['Gf']:g}N/m"
    wall0 = time.time()
    knobs, cal_runs = calibrate(a.exe, out, l_min, target, scaled_prism(l_min) + platen_sets(a.platens))
    cal_wall = time.time() - wall0
    cells = [f"specimen.l_min={mm(l_min)}", f"specimen.l_max={mm(l_max)}"]
    jobs = [("calibrated", knobs), ("face_value", [])]

    def one(job):
        name, facet = job
        h5 = out / f"{name}.h5"
        return name, h5, run(a.exe, BEAM, h5, cells + facet)

    with ThreadPoolExecutor(2) as pool:
        done = list(pool.map(one, jobs))
    rows, curves = [], {}
    for name, h5, (cpu, wall) in done:
        deflection, load, n = read_beam(h5)
        k = int(np.argmax(load))
        at = np.interp(SSNP166[:, 0] * 1e-3, deflection, load)
        rows.append(f"| {name.replace('_', ' ')} | {n} | {load[k]:.0f} | {deflection[k] * 1e3:.3f} | "
                    + " | ".join(f"{v:.0f} ({v / r - 1:+.1%})" for v, r in zip(at, SSNP166[:, 1])) + f" | {cpu:.0f} |")
        curves[name] = (deflection, load)
    lines = [f"# Petersson's notched beam, rigid cells (l_min {a.l_min:g} mm over the ligament, {a.l_max:g} mm beyond)",
             "", f"Concrete (as code_aster SSNP166 models it): E {c['E'] * 1e-9:g} GPa, ν {c['nu']:g}, f_t "
             f"{c['ft'] * 1e-6:g} MPa, G_F {c['Gf']:g} N/m. Calibrated on the tension prism scaled to l_min "
             f"({a.platens} platens) in "
             f"{cal_runs} runs ({cal_wall:.0f} s): " + ", ".join(f"`{k}`" for k in knobs) + ".", "",
             "| facets | cells | peak F [N] | deflection at peak [mm] | "
             + " | ".join(f"F at {d:g} mm (SSNP166 {f:.0f} N)" for d, f in SSNP166) + " | CPU [s] |",
             "|---|---|---|---|" + "---|" * len(SSNP166) + "---|", *rows, "",
             "SSNP166's points are a cohesive-crack model's answers (the reference values are its computed ones "
             "rounded), not Petersson's measurements.", ""]
    (out / "petersson.md").write_text("\n".join(lines) + "\n")
    plot(out, curves)
    print("\n".join(lines))


def plot(out, curves):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    for name, style in (("calibrated", "C0-"), ("face_value", "C3--")):
        deflection, load = curves[name]
        ax.plot(deflection * 1e3, load, style, label=f"rigid cells, facets {name.replace('_', ' ')}")
    ax.plot(SSNP166[:, 0], SSNP166[:, 1], "ks", label="code_aster SSNP166 (cohesive crack)")
    ax.set_xlabel("deflection under the notch [mm]")
    ax.set_ylabel("load F [N]")
    ax.set_title("Petersson's beam, 200 × 50 mm, span 2 m")
    ax.legend(fontsize="small")
    fig.savefig(out / "petersson.png", dpi=120)


if __name__ == "__main__":
    main()
