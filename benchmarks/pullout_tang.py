#!/usr/bin/python3
"""Tang (2013) ch. 8: the FRP-to-concrete single-shear pull test, its rate, bonded-length and free-zone studies.

Runs, each single-threaded (--threads for more) through the real `mesocrack run` on scenes/pull_tang_2d.toml or
the --scene given with its geometry (--set overrides that move the bonded length's ends, the sheet's end, the
unglued free zone, the prism's length and the slip probe); --speed sets the bonded-length and free-zone studies'
grip speed (50 mm/s):
  rate     the reference (free zone 100 mm, bonded 50 mm) at grip speeds 200, 100, 50, 25 and 12.5 mm/s (the
           scene's own: 50 mm/s; the run's time limit stretches with 1/speed): capacity and slip at capacity
           against the slowest, with the CPU seconds of each run (the accuracy-versus-time method of
           benchmarks/uniaxial_accuracy.py); --damping sets the local damping (the scene's: 0.1), a row's key
  bonded   bonded lengths 25-300 mm (--bonded), free zone 100 mm: capacity against the energy solution
           P∞ = b_f √(2 G E_p t_p), for Table 8.1's G_f and for the G the bonds spent (G_bonds; beside it
           G_damping, what local damping took per bonded area, both to the run's end), and Chen & Teng's (2001)
           model with its effective bond length L_e = √(E_p t_p / √f'_c) [mm, MPa]
  free     free zones 0, 25, 50 and 100 mm, bonded 50 mm: the early wedge failure at zero free zone (Figs. 8.14-8.16)
Output (--out): results.csv (one row per run), pullout.md (the tables), bonded.png and, for the reference, its
report pictures (load-slip, strain profiles, cracks at 31/60/90/100 % of the capacity).

  benchmarks/pullout_tang.py --only rate --jobs 2
  benchmarks/pullout_tang.py --only rate --rates 200,100,50,25 --damping 0.7 --jobs 2
  benchmarks/pullout_tang.py --only bonded,free --jobs 2
  benchmarks/pullout_tang.py --scene scenes/pull_tang_softening_2d.toml --speed 100 --only rate,bonded \
      --rates 100,50 --bonded 25,100,150,200 --out benchmarks/results/pullout_tang_softening --jobs 2
  benchmarks/pullout_tang.py --scene scenes/pull_tang_softening_2d.toml --speed 100 --only bonded --bonded 300 \
      --threads 2 --out benchmarks/results/pullout_tang_softening
"""
import math
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from uniaxial_accuracy import ROOT, append_rows, study_arguments, study_main, timed_run  # noqa: E402

SCENE = ROOT / "scenes" / "pull_tang_2d.toml"
WIDTH, PRISM_WIDTH = 0.05, 0.08        # b_f, b_c [m]
EP_TP = 195.2e9 * 1.2e-3               # E_p t_p [N/m], Table 8.1
G_F = 525.1                            # the adhesive's mode-II fracture energy [N/m], Table 8.1
FC = 52.6                              # f'_c [MPa], Table 8.1
SPEED = 50e-3                          # the scene's grip speed [m/s]
DAMPING = 0.1                          # the scene's local damping
DURATION = 20e-3                       # the scene's time limit at SPEED [s]
TAIL = 8.4e-3                          # the prism beyond the bonded length's far end [m]
BONDED = [25, 50, 100, 150, 200, 300]  # mm
FREE = [0, 25, 50, 100]                # mm
RATES = "200,100,50,25,12.5"           # mm/s


def geometry(free, bonded):
    """--set lines for a free zone and a bonded length [m]: the bonded length [free, free + bonded], the sheet
    cut beyond it, the sheet's unglued bottom row up to it, the prism TAIL beyond it, the slip probe at its
    loaded end (the concrete's end 15 mm deep)."""
    end = free + bonded
    mm = lambda x: f'"{x * 1e3:.4f} mm"'  # noqa: E731
    return [f"pullout.bonded_from={mm(free)}", f"pullout.bonded_to={mm(end)}",
            f"specimen.hi=[{mm(end + TAIL)}, \"31.3 mm\"]",
            f"specimen.regions[0].box_hi=[{mm(end + TAIL + 2e-3)}, \"32 mm\"]",
            f"specimen.regions[1].box_hi=[{mm(free - 0.1e-3)}, \"30.5 mm\"]",
            f"specimen.cuts[0].box_lo=[{mm(end + 0.1e-3)}, \"30.2 mm\"]",
            f"specimen.cuts[0].box_hi=[{mm(end + TAIL + 2e-3)}, \"32 mm\"]",
            f"groups[1].box_hi=[{mm(end + TAIL + 2e-3)}, \"0.3 mm\"]",
            f"groups[3].box_lo=[{mm(free - 0.3e-3)}, \"14.9 mm\"]",
            f"groups[3].box_hi=[{mm(free + 0.3e-3)}, \"15.3 mm\"]",
            f"groups[4].box_lo=[{mm(free - 0.3e-3)}, \"30.2 mm\"]",
            f"groups[4].box_hi=[{mm(free + 0.3e-3)}, \"30.5 mm\"]"]


def speed(v, bonded=0.05, free=0.1):
    """--set lines for the grip at speed v [m/s]; the time limit stretches with 1/v and with the sheet's length
    (the grip must travel the free sheet's stretch and the debonding slip)."""
    length = (free + bonded) / 0.15
    return [f'groups[2].velocity=["{-v * 1e3:g} mm/s", 0]', f'run.duration="{DURATION * SPEED / v * length:g} s"']


def energy_solution(g=G_F):
    """P∞ = b_f √(2 G E_p t_p): the capacity of a long bond whose interface spends G per debonded area."""
    return WIDTH * math.sqrt(2 * g * EP_TP)


def plateau_and_reach(bonded, share=0.97):
    """The plateau of the capacity against the bonded length (the mean of the two longest bonds' capacities [kN])
    and the bonded length [mm] at which the capacity, linear between the runs, first reaches `share` of it."""
    plateau = sum(r["capacity_kN"] for r in bonded[-2:]) / 2
    for a, b in zip(bonded, bonded[1:]):
        if b["capacity_kN"] >= share * plateau > a["capacity_kN"]:
            t = (share * plateau - a["capacity_kN"]) / (b["capacity_kN"] - a["capacity_kN"])
            return plateau, a["bonded_mm"] + t * (b["bonded_mm"] - a["bonded_mm"])
    return plateau, bonded[0]["bonded_mm"] if bonded[0]["capacity_kN"] >= share * plateau else None


def chen_teng(bonded_mm):
    """Chen & Teng (2001): P_u = 0.427 β_w β_L √f'_c b_f L_e [N, mm, MPa], L_e = √(E_p t_p/√f'_c),
    β_L = 1 for L ≥ L_e, else sin(π L / (2 L_e)); β_w of (8.1)."""
    le = math.sqrt(EP_TP * 1e-3 / math.sqrt(FC))   # E_p t_p in N/mm = MPa·mm
    r = WIDTH / PRISM_WIDTH
    beta_w = math.sqrt((2 - r) / (1 + r))
    beta_l = 1.0 if bonded_mm >= le else math.sin(math.pi * bonded_mm / (2 * le))
    return 0.427 * beta_w * beta_l * math.sqrt(FC) * WIDTH * 1e3 * le, le


def plan(only, rates, damping, grip, bonded_mm):
    """The runs: the rate study at `rates` [m/s], the bonded-length (`bonded_mm`) and free-zone studies at `grip`."""
    todo = []
    if "rate" in only:
        for v in rates:
            todo.append((f"rate_{v * 1e3:g}_damping_{damping:g}",
                         geometry(0.1, 0.05) + speed(v) + [f"physics.local_damping={damping:g}"],
                         {"study": "rate", "free_mm": 100, "bonded_mm": 50, "speed": v, "damping": damping},
                         v == grip and damping == DAMPING))
    if "bonded" in only:
        for b in bonded_mm:
            if b != 50:
                todo.append((f"bonded_{b:g}", geometry(0.1, b * 1e-3) + speed(grip, b * 1e-3),
                             {"study": "bonded", "free_mm": 100, "bonded_mm": b, "speed": grip,
                              "damping": DAMPING}, False))
    if "free" in only:
        for z in FREE:
            if z != 100:
                todo.append((f"free_{z}", geometry(z * 1e-3, 0.05) + speed(grip, 0.05, z * 1e-3),
                             {"study": "free", "free_mm": z, "bonded_mm": 50, "speed": grip,
                              "damping": DAMPING}, z == 0))
    return sorted(todo, key=lambda t: (t[2]["speed"], -t[2]["free_mm"] - t[2]["bonded_mm"]))  # the longest first


FIELDS = ["study", "free_mm", "bonded_mm", "speed", "damping", "capacity_kN", "capacity_beta_w_kN",
          "slip_at_capacity_mm", "final_load_over_capacity", "mode", "adhesive_breaks", "concrete_breaks",
          "depth_p90_mm", "G_bonds", "G_damping", "worst_residual", "particles", "steps", "cpu_s"]


def row_of(s, known, cpu):
    p = s["pullout"] or {}
    f = p.get("failure") or {}
    e = p.get("energy") or {}
    depth = f.get("depth_p90")
    local = e.get("dissipated_local")
    return {**known, "capacity_kN": p["capacity"] * 1e-3, "capacity_beta_w_kN": p["capacity_beta_w"] * 1e-3,
            "slip_at_capacity_mm": p["slip_at_capacity"] * 1e3,
            "final_load_over_capacity": p["final_load_over_capacity"],
            "mode": f.get("mode"), "adhesive_breaks": f.get("adhesive_breaks"),
            "concrete_breaks": f.get("concrete_breaks"), "depth_p90_mm": depth * 1e3 if depth is not None else None,
            "G_bonds": e.get("G_bonds"),
            "G_damping": local / (known["bonded_mm"] * 1e-3) if local is not None else None,
            "worst_residual": e.get("worst_residual_over_work"),
            "particles": s["particles"], "steps": s["steps"], "cpu_s": cpu}


def run_all(exe, out, jobs, todo, csv_path, scene, threads):
    def one(item):
        key, ov, known, keep = item
        h5 = out / "runs" / f"{key}.h5"
        s, cpu, _ = timed_run(exe, scene, h5, ov, keep=keep, threads=threads)
        if keep:  # its report pictures are kept, the run itself is not
            subprocess.run([exe, "report", str(h5)], check=True,  # its pictures by /usr/bin/python3
                           capture_output=True)
            for f in h5.parent.glob(h5.stem + "*"):
                if f.name.startswith(h5.stem + "_pullout"):
                    f.replace(out / f.name)
                else:
                    f.unlink()
        return row_of(s, known, cpu)

    append_rows(csv_path, FIELDS, jobs, todo, one,
                lambda r: (f"{r['study']} free {r['free_mm']} bonded {r['bonded_mm']} mm, "
                           f"{r['speed'] * 1e3:g} mm/s: capacity {r['capacity_kN']:.2f} kN, {r['mode']}, "
                           f"{r['cpu_s']:.0f} CPU s"))


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


def analyse(rows, out, grip):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    p_inf = energy_solution()
    _, le = chen_teng(300)
    lines = ["# FRP-to-concrete single-shear pull test (Tang ch. 8)\n",
             f"Energy solution P∞ = b_f √(2 G_f E_p t_p) = **{p_inf * 1e-3:.2f} kN** (G_f {G_F} N/m, E_p t_p "
             f"{EP_TP:.4g} N/m, b_f {WIDTH * 1e3:g} mm); Chen & Teng's effective bond length L_e = **{le:.1f} mm**.\n"]
    ref = [r for r in rows if r["free_mm"] == 100 and r["bonded_mm"] == 50]
    for damping in sorted({r["damping"] for r in ref if r["study"] == "rate"}):
        rate = sorted([r for r in ref if r["study"] == "rate" and r["damping"] == damping], key=lambda r: -r["speed"])
        slow = rate[-1]
        lines += [f"\n### Grip speed, local damping {damping:g} (reference: free zone 100 mm, bonded 50 mm; against "
                  f"{slow['speed'] * 1e3:g} mm/s and half the speed)\n",
                  "| speed [mm/s] | capacity [kN] | against the slowest | against half the speed | slip at capacity "
                  "[mm] | failure | energy residual | steps | CPU s |", "|---|---|---|---|---|---|---|---|---|"]
        for r in rate:
            half = [h for h in rate if abs(h["speed"] - r["speed"] / 2) < 1e-9]
            lines.append(f"| {r['speed'] * 1e3:g} | {r['capacity_kN']:.3f} | "
                         f"{r['capacity_kN'] / slow['capacity_kN'] - 1:+.1%} | "
                         f"{fmt(r['capacity_kN'] / half[0]['capacity_kN'] - 1 if half else None, '+.1%')} | "
                         f"{r['slip_at_capacity_mm']:.4f} | {r['mode']} | {fmt(r['worst_residual'], '.2%')} | "
                         f"{r['steps']:.0f} | {r['cpu_s']:.0f} |")
    at = lambda study, k: sorted([r for r in rows if r["study"] in (study, "rate") and r["speed"] == grip  # noqa
                                  and r["damping"] == DAMPING
                                  and (r["free_mm"] == 100 if k == "bonded_mm" else r["bonded_mm"] == 50)],
                                 key=lambda r: r[k])
    bonded = at("bonded", "bonded_mm")
    if len(bonded) > 1:
        lines += ["\n### Bonded length (free zone 100 mm)\n",
                  "| bonded [mm] | capacity [kN] | × β_w [kN] | P / P∞ | Chen & Teng [kN] | G_bonds [N/m] | "
                  "b_f √(2 G_bonds E_p t_p) [kN] | G_damping [N/m] | failure | CPU s |",
                  "|---|---|---|---|---|---|---|---|---|---|"]
        for r in bonded:
            g, gd = r["G_bonds"], r["G_damping"]
            lines.append(f"| {r['bonded_mm']:g} | {r['capacity_kN']:.2f} | {r['capacity_beta_w_kN']:.2f} | "
                         f"{r['capacity_kN'] * 1e3 / p_inf:.2f} | {chen_teng(r['bonded_mm'])[0] * 1e-3:.2f} | "
                         f"{fmt(g, '.0f')} | {fmt(energy_solution(g) * 1e-3 if g else None, '.2f')} | "
                         f"{fmt(gd, '.0f')} | {r['mode']} | {r['cpu_s']:.0f} |")
        plateau, reach = plateau_and_reach(bonded)
        lines.append(f"\nPlateau (mean of the two longest bonds): {plateau:.2f} kN = {plateau * 1e3 / p_inf:.3f} P∞; "
                     f"97 % of it is reached at {fmt(reach, '.0f')} mm (linear between the runs), against Chen & "
                     f"Teng's L_e = {le:.0f} mm (their β_L reaches 97 % at "
                     f"{2 * le / math.pi * math.asin(0.97):.0f} mm).")
        fig, ax = plt.subplots(figsize=(6, 4))
        ax.plot([r["bonded_mm"] for r in bonded], [r["capacity_kN"] for r in bonded], "o-", label="mesocrack")
        ls = list(range(5, 301, 5))
        ax.plot(ls, [chen_teng(x)[0] * 1e-3 for x in ls], "--", label="Chen & Teng (2001), with β_w")
        ax.axhline(p_inf * 1e-3, color="0.5", ls=":", label="energy solution P∞")
        ax.axvline(le, color="0.7", ls="-.", lw=1, label=f"L_e = {le:.0f} mm")
        ax.set_xlabel("bonded length [mm]")
        ax.set_ylabel("capacity [kN]")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(out / "bonded.png", dpi=110)
    free = at("free", "free_mm")
    if len(free) > 1:
        lines += ["\n### Free zone (bonded 50 mm)\n",
                  "| free zone [mm] | capacity [kN] | failure | concrete breaks: depth p90 [mm] | CPU s |",
                  "|---|---|---|---|---|"]
        for r in free:
            lines.append(f"| {r['free_mm']:g} | {r['capacity_kN']:.2f} | {r['mode']} | "
                         f"{fmt(r['depth_p90_mm'], '.1f')} | {r['cpu_s']:.0f} |")
    (out / "pullout.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


def main():
    ap = study_arguments(__doc__, "pullout_tang", "rate,bonded,free")
    ap.add_argument("--rates", default=RATES, help="grip speeds of the rate study [mm/s], comma-separated")
    ap.add_argument("--damping", type=float, default=DAMPING, help="local damping of the rate study's runs")
    ap.add_argument("--scene", default=str(SCENE), help="the pull test scene (its geometry as pull_tang_2d.toml's)")
    ap.add_argument("--speed", type=float, default=SPEED * 1e3,
                    help="grip speed of the bonded-length and free-zone studies [mm/s]")
    ap.add_argument("--bonded", default=",".join(map(str, BONDED)), help="bonded lengths [mm], comma-separated")
    ap.add_argument("--threads", type=int, default=1,
                    help="threads of each run (the results do not depend on it; its CPU s counts every thread)")
    known = ap.parse_known_args()[0]
    scene, grip, threads = Path(known.scene), known.speed * 1e-3, known.threads
    study_main(ap, FIELDS, ("study", "mode"),
               lambda r: (r["study"], r["free_mm"], r["bonded_mm"], r["speed"], r["damping"]),
               lambda a: plan(set(a.only.split(",")), [float(r) * 1e-3 for r in a.rates.split(",")], a.damping,
                              grip, [float(b) for b in a.bonded.split(",")]),
               lambda t: t[2], lambda *args: run_all(*args, scene, threads), lambda rows, out: analyse(rows, out, grip))


if __name__ == "__main__":
    sys.exit(main())
