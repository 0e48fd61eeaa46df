#!/usr/bin/python3
"""Tang (2013) ch. 7: the notched three-phase concrete beam in three-point bending under CMOD control.

Runs, each single-threaded through the real `mesocrack run` on scenes/bending_tang_softening_2d.toml and
scenes/bending_tang_brittle_2d.toml (--set overrides):
  scenes  the four beams of Tang §7.2: aggregate 40 % and 60 % (`mesostructure.fraction`, one packing) with
          softening or brittle mortar; a table (peak load per 100 mm, CMOD at the peak, G_F by RILEM and by the
          bonds, tortuosity, broken bonds per phase pair at the peak and at the end) beside independent estimates
          (the elastic net-section first-crack load and the cohesive-hinge peak for the mortar's E, f_t and G_F);
          the load-CMOD curves of the four in one plot; the crack pictures at the peak and at the end (report)
  mortar  the softening beam without aggregate (fraction 0): its bonds must dissipate the mortar's G_F (Table 7.1,
          170.4 N/m) over the ligament within 10 %
  rate    the softening 40 % beam at servo rates 40, 20, 5, 2.5 and 1.25 mm/s (10 mm/s: the scenes' own run): peak load
          and G_F against the slowest rate, with the CPU seconds of each run (the accuracy-versus-time method of
          benchmarks/uniaxial_accuracy.py)
  layouts the softening beams at 40 % and 60 % on other seeds (packing, aggregate layout and bond strengths): whether
          the scenes' differences between the two fractions are a trend or one layout's chance
Output (--out): results.csv (one row per run), bending.md (the tables), load_cmod.png, rate.png and, for the kept
runs, their report pictures.

  benchmarks/bending_tang.py --jobs 2                      # everything: about 5 CPU hours (a beam: 10-12 min)
  benchmarks/bending_tang.py --only scenes,mortar --jobs 2
"""
import subprocess
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from uniaxial_accuracy import ROOT, append_rows, study_arguments, study_main, timed_run  # noqa: E402

THICKNESS = 0.1                  # m, Tang's beam; the discs have unit thickness and summary scales to this
SPAN, LIGAMENT = 0.3, 0.09
MORTAR = {"E": 35e9, "ft": 3.2e6, "GF": 170.4}   # Table 7.1
RATES = "40,20,5,2.5,1.25"                       # mm/s of the servo gauge (the scenes' own, 10 mm/s, from "scenes")
SCENE_RATE = 10e-3
SEEDS = [8, 9, 10]                              # the layouts beside the scenes' seed 7
FRACTIONS = [0.4, 0.6]
MORTAR_RATE = 10e-3


def net_section_load(ft, h=LIGAMENT, t=THICKNESS, s=SPAN):
    """The load at which the elastic bending stress of the net section, 6M/(t h²) with M = P S / 4, reaches f_t."""
    return 2 * ft * t * h * h / (3 * s)


def hinge_peak(E, ft, GF, h=LIGAMENT, t=THICKNESS, s=SPAN, zeta=0.5):
    """Peak load of Olesen's (2001) cohesive hinge with a linear softening law σ = f_t (1 - w/w_c), w_c = 2 G_F/f_t:
    the ligament h as a hinge of length ζh whose plane ends rotate by φ each; a fibre at depth y (from the top)
    lengthens by δ = 2φ (y - y0), elastic (σ = E δ / (ζh)) up to f_t, beyond it cracked with δ = σ ζh/E + w. The
    neutral depth y0 balances the normal force; M = ∫σ y dy t, and P = 4 M / S. Solved on 2000 fibres."""
    L = zeta * h
    wc = 2 * GF / ft
    y = (np.arange(2000) + 0.5) * h / 2000
    dy = h / 2000

    def stress(delta):
        sig = E * delta / L
        cracked = sig > ft
        soft = (delta - wc) / (L / E - wc / ft)        # δ = σ L/E + w_c (1 - σ/f_t)
        return np.where(cracked, np.clip(soft, 0, ft), sig)

    best = 0.0
    for phi in np.logspace(-7, -2, 600):
        lo, hi = 0.0, h
        for _ in range(80):                             # the normal force falls as the neutral axis goes down
            y0 = 0.5 * (lo + hi)
            n = stress(2 * phi * (y - y0)).sum()
            lo, hi = (y0, hi) if n > 0 else (lo, y0)
        sig = stress(2 * phi * (y - y0))
        best = max(best, 4 * (sig * y).sum() * dy * t / s)
    return best


def servo(rate):
    """--set lines for the servo at `rate` [m/s]: the scenes' servo (10 mm/s, gain 2000 /s, advancing at up to three
    times the rate, backing off at up to the rate) slowed as a whole, its gain with the rate, so that only the time
    scale of the test changes; the run's time limit (0.1 s at 10 mm/s) stretches with it, so that every rate ends
    where the scenes do, at an underside opening of 0.3 mm."""
    s = rate / SCENE_RATE
    return [f'walls[2].rate="{rate * 1e3:g} mm/s"', f'walls[2].gain="{2000 * s:g} /s"',
            f'walls[2].max_speed="{3 * rate * 1e3:g} mm/s"', f'walls[2].retreat_speed="{rate * 1e3:g} mm/s"',
            f'run.duration="{0.1 / s:g} s"']


def plan(only, rates):
    """(key, scene, overrides, row fields known before the run, keep the run for pictures)."""
    todo = []
    if "scenes" in only:
        for mortar in ("softening", "brittle"):
            for f in FRACTIONS:
                todo.append((f"{mortar}_{round(f * 100)}", mortar, [f"mesostructure.fraction={f}"],
                             {"study": "scenes", "mortar": mortar, "fraction": f, "rate": SCENE_RATE, "seed": 7},
                             True))
    if "mortar" in only:
        # Until the ligament has nearly parted (an underside opening of 0.8 mm; half an hour of CPU at the scenes'
        # rate); its curve keeps the bonds' dissipation against the opening, to see it level off.
        todo.append(("mortar_only", "softening", ["mesostructure.fraction=0", "run.stop[0].above=0.8e-3",
                                                  *servo(MORTAR_RATE)],
                     {"study": "mortar", "mortar": "softening", "fraction": 0.0, "rate": MORTAR_RATE, "seed": 7},
                     True))
    if "rate" in only:
        for r in rates:
            todo.append((f"rate_{r * 1e3:g}", "softening", servo(r),
                         {"study": "rate", "mortar": "softening", "fraction": 0.4, "rate": r, "seed": 7}, False))
    if "layouts" in only:
        for seed in SEEDS:
            for f in FRACTIONS:
                todo.append((f"layout_{seed}_{round(f * 100)}", "softening", [f"mesostructure.fraction={f}",
                                                                               f"seed={seed}"],
                             {"study": "layouts", "mortar": "softening", "fraction": f, "rate": SCENE_RATE,
                              "seed": seed}, False))
    return sorted(todo, key=lambda t: t[3]["rate"] if t[3]["study"] != "mortar" else 0)  # the longest first


FIELDS = ["study", "mortar", "fraction", "rate", "seed", "peak_kN", "cmod_peak_um", "deflection_peak_um", "G_F", "G_F_bonds",
          "tortuosity", "crack_height_over_ligament", "final_load_over_peak", "worst_residual",
          "mm_breaks_peak", "itz_breaks_peak", "agg_breaks_peak", "yields_peak",
          "mm_breaks_end", "itz_breaks_end", "agg_breaks_end", "yields_end", "mm_yields_end", "itz_yields_end",
          "particles", "steps", "cpu_s"]


def breaks(block, pair):
    c = (block or {}).get(pair) or {}
    return (c.get("tensile_breaks") or 0) + (c.get("shear_breaks") or 0)


def row_of(summary, known, cpu):
    b = summary["bending"] or {}
    e = b.get("energy") or {}
    path = b.get("crack_path") or {}
    peak, end = b.get("cracks_at_peak"), b.get("cracks_final")
    yields = lambda blk: sum((c.get("first_yields") or 0) for c in (blk or {}).values())  # noqa: E731
    return {**known, "peak_kN": b["peak_load"] * 1e-3, "cmod_peak_um": b["cmod_at_peak"] * 1e6,
            "deflection_peak_um": b["deflection_at_peak"] * 1e6, "G_F": b["G_F"], "G_F_bonds": e.get("G_F_bonds"),
            "tortuosity": path.get("tortuosity"), "crack_height_over_ligament": path.get("height_over_ligament"),
            "final_load_over_peak": b["final_load_over_peak"], "worst_residual": e.get("worst_residual_over_work"),
            "mm_breaks_peak": breaks(peak, "mortar-mortar"), "itz_breaks_peak": breaks(peak, "mortar-aggregate"),
            "agg_breaks_peak": breaks(peak, "aggregate-aggregate"), "yields_peak": yields(peak),
            "mm_breaks_end": breaks(end, "mortar-mortar"), "itz_breaks_end": breaks(end, "mortar-aggregate"),
            "agg_breaks_end": breaks(end, "aggregate-aggregate"), "yields_end": yields(end),
            "mm_yields_end": ((end or {}).get("mortar-mortar") or {}).get("first_yields"),
            "itz_yields_end": ((end or {}).get("mortar-aggregate") or {}).get("first_yields"),
            "particles": summary["particles"], "steps": summary["steps"], "cpu_s": cpu}


def run_all(exe, out, jobs, todo, csv_path):
    def one(item):
        key, mortar, ov, known, keep = item
        h5 = out / "runs" / f"{key}.h5"
        s, cpu, _ = timed_run(exe, ROOT / "scenes" / f"bending_tang_{mortar}_2d.toml", h5, ov, keep=keep)
        if keep:
            curve(h5, out / f"{key}_curve.csv")
            subprocess.run([exe, "report", str(h5)], check=True,  # its pictures by /usr/bin/python3
                           capture_output=True)
            for f in h5.parent.glob(h5.stem + "*"):  # the crack pictures at the peak and at the end are kept
                if f.name in (h5.stem + "_cracks.png", h5.stem + "_cracks_peak.png"):
                    f.replace(out / f.name)
                else:
                    f.unlink()
        return row_of(s, known, cpu)

    append_rows(csv_path, FIELDS, jobs, todo, one,
                lambda r: (f"{r['study']} {r['mortar']} {r['fraction']:g} {r['rate'] * 1e3:g} mm/s: "
                           f"peak {r['peak_kN']:.2f} kN, G_F {r['G_F']:.1f} N/m, {r['cpu_s']:.0f} CPU s"))


def curve(h5, path):
    """The load-CMOD and load-deflection curves of a kept run, as CSV (the plot of the four is drawn from them)."""
    import h5py
    with h5py.File(h5, "r") as f:
        h = f["history"]
        cols = {"time": h["time"][:], "cmod": h["bending.cmod"][:], "deflection": h["bending.deflection"][:],
                "load_kN": h["bending.load"][:] * THICKNESS * 1e-3, "underside": h["underside"][:],
                "G_bonds": h["energy.dissipated_bonds"][:] / LIGAMENT}  # N/m: the bonds' dissipation per ligament
    np.savetxt(path, np.column_stack(list(cols.values())), delimiter=",", header=",".join(cols), comments="")


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


def layouts_table(rows):
    """The softening beams at 40 % and 60 % for every seed run (the scenes' seed 7 and the layouts study's), and the
    mean: does the 60 % beam crack more through the ITZ, whatever the layout?"""
    soft = sorted([r for r in rows if r["mortar"] == "softening" and r["study"] in ("scenes", "layouts")],
                  key=lambda r: (r["seed"], r["fraction"]))
    if len({r["seed"] for r in soft}) < 2:
        return []
    share = lambda r: r["itz_breaks_end"] / max(r["mm_breaks_end"] + r["itz_breaks_end"] + r["agg_breaks_end"], 1)  # noqa
    out = ["\n### Layouts (softening mortar; seed = packing, aggregate layout and bond strengths)\n",
           "| seed | aggregate | peak [kN] | G_F [N/m] | tortuosity | breaks at end M-M / ITZ / A-A | ITZ share | "
           "yields at end M-M / ITZ |", "|---|---|---|---|---|---|---|---|"]
    for r in soft:
        out.append(f"| {r['seed']:.0f} | {r['fraction']:.0%} | {r['peak_kN']:.2f} | {r['G_F']:.1f} | "
                   f"{fmt(r['tortuosity'], '.2f')} | {r['mm_breaks_end']:.0f} / {r['itz_breaks_end']:.0f} / "
                   f"{r['agg_breaks_end']:.0f} | {share(r):.0%} | "
                   f"{fmt(r['mm_yields_end'], '.0f')} / {fmt(r['itz_yields_end'], '.0f')} |")
    for f in FRACTIONS:
        g = [r for r in soft if r["fraction"] == f]
        mean = lambda q: np.mean([q(r) for r in g])  # noqa: E731
        out.append(f"| mean of {len(g)} | {f:.0%} | {mean(lambda r: r['peak_kN']):.2f} | {mean(lambda r: r['G_F']):.1f} "
                   f"| {mean(lambda r: r['tortuosity'] or 0):.2f} | {mean(lambda r: r['mm_breaks_end']):.1f} / "
                   f"{mean(lambda r: r['itz_breaks_end']):.1f} / {mean(lambda r: r['agg_breaks_end']):.1f} | "
                   f"{mean(share):.0%} | {mean(lambda r: r['mm_yields_end'] or 0):.0f} / "
                   f"{mean(lambda r: r['itz_yields_end'] or 0):.0f} |")
    return out


def analyse(rows, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    lines = ["# Three-point bending of the notched three-phase beam (Tang ch. 7)\n"]
    p_net = net_section_load(MORTAR["ft"])
    p_hinge = hinge_peak(MORTAR["E"], MORTAR["ft"], MORTAR["GF"])
    lines += [f"Independent estimates for the mortar's E, f_t, G_F (Table 7.1), span {SPAN * 1e3:g} mm, ligament "
              f"{LIGAMENT * 1e3:g} mm, thickness {THICKNESS * 1e3:g} mm: elastic net-section first-crack load "
              f"**{p_net * 1e-3:.2f} kN**; cohesive hinge (Olesen 2001, linear softening, hinge 0.5 h) peak "
              f"**{p_hinge * 1e-3:.2f} kN**.\n"]
    scenes = sorted([r for r in rows if r["study"] == "scenes"], key=lambda r: (r["mortar"], r["fraction"]))
    if scenes:
        lines += ["| mortar | aggregate | peak [kN] | CMOD at peak [µm] | G_F RILEM [N/m] | G_F bonds [N/m] | "
                  "tortuosity | crack height / ligament | breaks at peak M-M / ITZ / A-A | breaks at end M-M / ITZ / A-A "
                  "| ITZ share of breaks at end | energy residual | CPU s |", "|" + "---|" * 13]
        for r in scenes:
            tot = r["mm_breaks_end"] + r["itz_breaks_end"] + r["agg_breaks_end"]
            lines.append(
                f"| {r['mortar']} | {r['fraction']:.0%} | {r['peak_kN']:.2f} | {r['cmod_peak_um']:.1f} | "
                f"{r['G_F']:.1f} | {fmt(r['G_F_bonds'], '.1f')} | {fmt(r['tortuosity'], '.2f')} | "
                f"{fmt(r['crack_height_over_ligament'], '.2f')} | {r['mm_breaks_peak']:.0f} / {r['itz_breaks_peak']:.0f} / "
                f"{r['agg_breaks_peak']:.0f} | {r['mm_breaks_end']:.0f} / {r['itz_breaks_end']:.0f} / "
                f"{r['agg_breaks_end']:.0f} | {r['itz_breaks_end'] / max(tot, 1):.0%} | {fmt(r['worst_residual'], '.2%')} | "
                f"{r['cpu_s']:.0f} |")
    for r in rows:
        if r["study"] == "mortar":
            lines.append(f"\nMortar alone (no aggregate): G_F by the bonds {fmt(r['G_F_bonds'], '.1f')} N/m against "
                         f"Table 7.1's {MORTAR['GF']} N/m ({(r['G_F_bonds'] or 0) / MORTAR['GF'] - 1:+.1%}); RILEM "
                         f"G_F {r['G_F']:.1f} N/m; peak {r['peak_kN']:.2f} kN (hinge {p_hinge * 1e-3:.2f} kN); "
                         f"{r['cpu_s']:.0f} CPU s.")
    # The scenes' softening 40 % beam is the rate study's point at the scenes' own rate.
    lines += layouts_table(rows)
    rate = sorted([r for r in rows if r["study"] == "rate" or (r["study"] == "scenes" and r["mortar"] == "softening"
                                                               and r["fraction"] == 0.4)], key=lambda r: -r["rate"])
    if rate:
        ref = rate[-1]
        lines += [f"\n### Servo rate (softening mortar, 40 %; reference {ref['rate'] * 1e3:g} mm/s)\n",
                  "| rate [mm/s] | peak [kN] | err peak | G_F [N/m] | err G_F | steps | CPU s |", "|---|---|---|---|---|---|---|"]
        for r in rate:
            lines.append(f"| {r['rate'] * 1e3:g} | {r['peak_kN']:.3f} | {r['peak_kN'] / ref['peak_kN'] - 1:+.1%} | "
                         f"{r['G_F']:.1f} | {r['G_F'] / ref['G_F'] - 1:+.1%} | {r['steps']:.0f} | {r['cpu_s']:.0f} |")
        fig, ax = plt.subplots(figsize=(6, 4))
        for q, lab in (("peak_kN", "peak load"), ("G_F", "G_F")):
            ax.plot([r["cpu_s"] for r in rate[:-1]], [abs(r[q] / ref[q] - 1) * 100 for r in rate[:-1]], "o-",
                    label=lab)
            for r in rate[:-1]:
                ax.annotate(f"{r['rate'] * 1e3:g} mm/s", (r["cpu_s"], abs(r[q] / ref[q] - 1) * 100), fontsize=7)
        ax.axhline(2, color="0.5", ls=":", lw=1)
        ax.set_xlabel("CPU seconds per run")
        ax.set_ylabel(f"|error| against {ref['rate'] * 1e3:g} mm/s [%]")
        ax.legend()
        fig.tight_layout()
        fig.savefig(out / "rate.png", dpi=110)
    (out / "bending.md").write_text("\n".join(lines) + "\n")
    curves = sorted(c for c in out.glob("*_curve.csv") if not c.name.startswith("mortar"))
    if curves:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for c in curves:
            d = np.genfromtxt(c, delimiter=",", names=True)
            ax.plot(d["cmod"] * 1e3, d["load_kN"], label=c.stem.replace("_curve", "").replace("_", " ") + " %")
        ax.axhline(p_hinge * 1e-3, color="0.4", ls="--", lw=1, label="cohesive hinge, mortar")
        ax.axhline(p_net * 1e-3, color="0.6", ls=":", lw=1, label="net-section first crack, mortar")
        ax.set_xlabel("CMOD [mm]")
        ax.set_ylabel("load [kN per 100 mm]")
        ax.set_title("Tang Fig. 7.5: load-CMOD of the four beams")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(out / "load_cmod.png", dpi=110)
    print("\n".join(lines))


def main():
    ap = study_arguments(__doc__, "bending_tang", "scenes,mortar,rate,layouts")
    ap.add_argument("--rates", default=RATES, help="servo rates of the rate study [mm/s], comma-separated")
    study_main(ap, FIELDS, ("study", "mortar"),
               lambda r: (r["study"], r["mortar"], r["fraction"], r["rate"], r["seed"]),
               lambda a: plan(set(a.only.split(",")), [float(r) * 1e-3 for r in a.rates.split(",")]),
               lambda t: t[3], run_all, analyse)


if __name__ == "__main__":
    sys.exit(main())
