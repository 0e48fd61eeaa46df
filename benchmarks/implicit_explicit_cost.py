#!/usr/bin/python3
"""What implicit stepping buys in time at equal accuracy: the rigid-cell model under Newmark (Květoň ch. 8) and
under central differences (rigid_cell/central_difference.hpp) on the same specimens, single-threaded through the
real `mesocrack run`.

  - spalling: scenes/spalling_kveton.toml (wave 3, the Tab. 9.3 reference, with damage): a wave problem. The
    error is that of the rear face's velocity against the finest explicit run (0.025 µs): its peak, and the RMS of
    its history over the run, both over the peak.
  - cantilever: scenes/cantilever_dynamic_kveton.toml over one period of its swing (elastic): a structural one,
    whose response lives in its lowest mode. The error is that of the end's deflection history against the finest
    Newmark run (trapezoidal rule, 0.0125 ms), over its largest value.
Newmark runs at the thesis's β 0.3, γ 0.55 (spalling) or the trapezoidal rule (cantilever, Květoň §8.3);
the explicit ones at steps up to 0.9 of their critical one.
Output (--out): results.csv, runs/<run>.csv (the history read), implicit_explicit.md, implicit_explicit.png.

  benchmarks/implicit_explicit_cost.py
"""
import re
import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from uniaxial_accuracy import ROOT, append_rows, study_arguments, study_main, timed_run  # noqa: E402

# case: scene, the history compared, how long [s], the Newmark (β, γ), Newmark steps, explicit steps [s].
CASES = {
    "spalling": ("spalling_kveton", "group.rear.velocity_z", 200e-6, (0.3, 0.55),
                 [0.05e-6, 0.1e-6, 0.2e-6, 0.4e-6, 0.8e-6], [0.025e-6, 0.1e-6, 0.4e-6, 0.8e-6]),
    "cantilever": ("cantilever_dynamic_kveton", "group.end.disp_y", 3.4e-3, (0.25, 0.5),
                   [0.0125e-3, 0.025e-3, 0.05e-3, 0.1e-3, 0.2e-3], [0.39e-6]),
}
REFERENCE = {"spalling": ("central_difference", 0.025e-6), "cantilever": ("newmark", 0.0125e-3)}
FIELDS = ["case", "scheme", "dt_us", "steps", "peak_error", "rms_error", "cpu_s"]


def plan(a):
    todo = []
    for case in a.only.split(","):
        if case not in CASES:
            sys.exit(f"--only: '{case}' is not one of {', '.join(CASES)}")
        todo += [(case, "newmark", dt) for dt in CASES[case][4]]
        todo += [(case, "central_difference", dt) for dt in CASES[case][5]]
    return todo


def scene_for(out, case, scheme):
    """The scene with its scheme; under central differences without Newmark's β, γ."""
    path = ROOT / "scenes" / f"{CASES[case][0]}.toml"
    text = re.sub(r"^(beta|gamma) = .*\n", "", path.read_text(), flags=re.M)
    text = re.sub(r"^scheme = .*\n", "", text, flags=re.M)
    text = text.replace("[rigid_cell.dynamics]\n", f'[rigid_cell.dynamics]\nscheme = "{scheme}"\n')
    if scheme == "newmark":
        beta, gamma = CASES[case][3]
        text = text.replace("[rigid_cell.dynamics]\n", f"[rigid_cell.dynamics]\nbeta = {beta}\ngamma = {gamma}\n")
    written = out / "runs" / f"{case}_{scheme}.toml"
    written.write_text(text)
    return written


def name(case, scheme, dt):
    return f"{case}_{scheme}_{dt * 1e9:.0f}ns"


def run_all(exe, out, jobs, todo, csv_path):
    def one(item):
        case, scheme, dt = item
        scene, history, duration = CASES[case][:3]
        steps = int(round(duration / dt))
        h5 = out / "runs" / f"{name(case, scheme, dt)}.h5"
        sets = [f"timestep.fixed={dt}", f"run.steps={steps}", "run.duration=0", "output.frame_every=100000000",
                f"output.history_every={max(1, int(round(steps * 1e-3)))}"]
        s, cpu, _ = timed_run(exe, scene_for(out, case, scheme), h5, sets, keep=True)
        with h5py.File(h5, "r") as f:
            t, y = f["history"]["time"][:], f["history"][history][:]
        for g in h5.parent.glob(h5.stem + ".*"):
            g.unlink()
        (h5.parent / f"{h5.stem}_history.csv").unlink()
        np.savetxt(out / "runs" / f"{h5.stem}.csv", np.c_[t, y], delimiter=",", fmt="%.9g", header="t,y", comments="")
        return {"case": case, "scheme": scheme, "dt_us": dt * 1e6, "steps": s["steps"], "peak_error": float("nan"),
                "rms_error": float("nan"), "cpu_s": cpu}

    append_rows(csv_path, FIELDS, jobs, todo, one,
                lambda r: f"{r['case']} {r['scheme']} {r['dt_us']:g} µs: {r['steps']:.0f} steps, {r['cpu_s']:.1f} CPU s")


def errors(out, case, scheme, dt):
    """Peak and RMS error of a run's history against the case's reference, over the reference's largest value."""
    ref = np.loadtxt(out / "runs" / f"{name(case, *REFERENCE[case])}.csv", delimiter=",", skiprows=1)
    run = np.loadtxt(out / "runs" / f"{name(case, scheme, dt)}.csv", delimiter=",", skiprows=1)
    y = np.interp(ref[:, 0], run[:, 0], run[:, 1])
    scale = np.abs(ref[:, 1]).max()
    peak = (np.abs(y).max() - scale) / scale
    return peak, float(np.sqrt(np.mean((y - ref[:, 1]) ** 2)) / scale)


def analyse(rows, out):
    lines = ["| case | scheme | Δt [µs] | steps | peak error | RMS error of the history | CPU s |",
             "|---|---|---|---|---|---|---|"]
    for r in sorted(rows, key=lambda r: (r["case"], r["scheme"], r["dt_us"])):
        peak, rms = errors(out, r["case"], r["scheme"], r["dt_us"] * 1e-6)
        r["peak_error"], r["rms_error"] = peak, rms
        ref = "reference" if (r["scheme"], round(r["dt_us"] * 1e-6, 12)) == (REFERENCE[r["case"]][0],
                                                                            round(REFERENCE[r["case"]][1], 12)) else ""
        lines.append(f"| {r['case']} | {r['scheme'].replace('_', ' ')} | {r['dt_us']:g} | {r['steps']:.0f} | "
                     f"{peak * 100:+.2f} % | {rms * 100:.2f} % {ref} | {r['cpu_s']:.1f} |")
    (out / "implicit_explicit.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, len(CASES), figsize=(11, 4.5))
    for axis, case in zip(ax, CASES):
        for scheme, marker in [("newmark", "o-"), ("central_difference", "s-")]:
            rs = sorted((r for r in rows if r["case"] == case and r["scheme"] == scheme), key=lambda r: r["cpu_s"])
            rs = [r for r in rs if r["rms_error"] > 0]
            axis.plot([r["cpu_s"] for r in rs], [r["rms_error"] * 100 for r in rs], marker, label=scheme)
        axis.set(xscale="log", yscale="log", xlabel="CPU s", ylabel="RMS error of the history [%]", title=case)
        axis.legend()
    fig.tight_layout()
    fig.savefig(out / "implicit_explicit.png", dpi=110)


def main():
    ap = study_arguments(__doc__, "implicit_explicit_cost", ",".join(CASES))
    study_main(ap, FIELDS, ("case", "scheme"), lambda r: (r["case"], r["scheme"], round(float(r["dt_us"]), 6)),
               plan, lambda t: {"case": t[0], "scheme": t[1], "dt_us": t[2] * 1e6}, run_all, analyse)


if __name__ == "__main__":
    sys.exit(main())
