#!/usr/bin/python3
"""What accuracy costs in time, for the virtual uniaxial compression test (Tang 2013 ch. 5).

Sweeps, each run single-threaded through the real `mesocrack run` on the reference scenes
(scenes/uniaxial_2d.toml, scenes/uniaxial_3d.toml) with --set overrides:
  rate        strain rate 0.01-100 /s (Tang §5.3): UCS and E versus rate beside the CEB dynamic increase factor (5.6)
  resolution  L/R = W / R_mean with the specimen fixed and R_min varied (Tang §5.4.1, Case II), >= 5 seeds each:
              mean and coefficient of variation
  timestep    the safety factor on the critical step (Tang 3.24)
  density     PFC density scaling (inertia times F, declared in [physics])
Each point records E, nu, UCS and the CPU seconds of its run (user + system of the child: the cost on one core,
robust to whatever else the machine is doing). The error of a point is measured against the finest/slowest
point of its sweep; for the resolution sweep it is the error a single specimen makes, sqrt(bias^2 + CV^2).

Output (in --out): results.csv (one row per run), accuracy.md (the tables), accuracy_vs_time.png (error versus
CPU seconds, all sweeps), rate_dif.png (DIF versus strain rate with CEB 5.6), resolution.png (mean and CV
versus L/R).

  benchmarks/uniaxial_accuracy.py                 # quick sets (about an hour of CPU; --jobs 2 halves the wait)
  benchmarks/uniaxial_accuracy.py --full          # Tang's full ranges (2D L/R to 240, 3D to 77): many hours
  benchmarks/uniaxial_accuracy.py --only rate --dims 2

On many cores or machines, any study of benchmarks/ that builds on this module's loops (run_appending,
append_rows) spreads its runs over the ranks of an Open MPI launch, run k on rank k mod N, then tabulates in a
plain run that merges the ranks' rows:
  mpirun -np 8 python3 benchmarks/uniaxial_accuracy.py --only resolution --jobs 1
  python3 benchmarks/uniaxial_accuracy.py --only resolution --analyse
"""
import argparse
import concurrent.futures as cf
import contextlib
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def launch_rank():
    """(rank, size) of this script in an Open MPI launch (mpirun -np N python3 ...), else (0, 1). The ranks never
    talk: each runs its share of the plan and appends its rows to its own results.rankR.csv. The launcher's
    variables are then taken out of the environment, so that the mesocrack runs this script starts are plain
    runs, not ranks of its launch."""
    rank, size = int(os.environ.get("OMPI_COMM_WORLD_RANK", 0)), int(os.environ.get("OMPI_COMM_WORLD_SIZE", 1))
    for k in [k for k in os.environ if k.startswith(("OMPI_", "PMIX_", "PMI_"))]:
        del os.environ[k]
    return rank, size


RANK, RANKS = launch_rank()


def rows_file(csv_path):
    """Where this process appends its rows: results.csv, or in a launch of several ranks its own file."""
    return csv_path if RANKS == 1 else csv_path.with_name(f"{csv_path.stem}.rank{RANK}{csv_path.suffix}")


@contextlib.contextmanager
def appending(path, fields):
    """A csv.DictWriter appending to `path`, which gets the header if it is new. A file written with other
    columns (a study that has since gained one) is first rewritten with `fields`, its rows' missing columns empty."""
    new = not path.exists()
    if not new:
        with open(path) as f:
            reader = csv.DictReader(f)
            rows = list(reader)
        if reader.fieldnames != fields:
            with open(path, "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=fields)
                w.writeheader()
                w.writerows({k: r.get(k, "") for k in fields} for r in rows)
    with open(path, "a", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        if new:
            w.writeheader()
        yield w, f


def rank_files(csv_path):
    """The rows files of the ranks of launches: results.rankR.csv beside results.csv."""
    return sorted(csv_path.parent.glob(f"{csv_path.stem}.rank*{csv_path.suffix}"))


def merge_rank_rows(csv_path):
    """Outside a launch: the rows the ranks of earlier launches appended to results.rankR.csv join
    results.csv (then the rank files go). Within one: nothing (the rank files are read beside it)."""
    if RANKS > 1:
        return
    for part in rank_files(csv_path):
        with open(part) as f:
            reader = csv.DictReader(f)
            rows = list(reader)
        if rows:
            with appending(csv_path, reader.fieldnames) as (w, _):
                w.writerows(rows)
        part.unlink()


def result_files(csv_path):
    """The files a study's rows are in: results.csv (with the rank files merged into it), and within a launch
    of several ranks also the rank files."""
    merge_rank_rows(csv_path)
    files = [csv_path] if csv_path.exists() else []
    if RANKS > 1:
        files += rank_files(csv_path)
    return files


def mine(items):
    """This rank's share of a study's runs: item k on rank k mod N (the same plan on every rank)."""
    return list(items)[RANK::RANKS]


def ranks_done(csv_path):
    """In a launch of several ranks, the end of a rank's share: the tables come from a plain run."""
    if RANKS > 1:
        print(f"rank {RANK} of {RANKS}: its runs are in {rows_file(csv_path)}; run the study again without mpirun "
              f"(--analyse) to merge the ranks' rows and tabulate them", flush=True)
        sys.exit(0)
RATIO = 1.66                          # R_max / R_min, Table 5.1
MEAN = (1 + RATIO) / 2                # R_mean / R_min


def mm(x):
    return f'"{x * 1e3:.6g} mm"'


def geometry_2d(width, height, r_min, rate):
    """Overrides of scenes/uniaxial_2d.toml for a width x height specimen, R_min, strain rate (5.5)."""
    v = rate * height / 2                     # each platen: the two close at rate * height
    ramp = 2e-4 / rate                        # 2 ms at 0.1 /s, as the reference; shorter in proportion above
    return [
        f"specimen.hi=[{mm(width)}, {mm(height)}]", f'specimen.radius_min={mm(r_min)}',
        f"walls[0].a=[{mm(-0.2 * width)}, 0]", f"walls[0].b=[{mm(1.2 * width)}, 0]",
        f"walls[1].a=[{mm(-0.2 * width)}, {mm(height)}]", f"walls[1].b=[{mm(1.2 * width)}, {mm(height)}]",
        f"walls[0].inside=[{mm(width / 2)}, {mm(height / 2)}]", f"walls[1].inside=[{mm(width / 2)}, {mm(height / 2)}]",
        f"walls[0].area={mm(width)}", f"walls[1].area={mm(width)}",
        f"walls[0].velocity=[0, {v:.6g}]", f"walls[1].velocity=[0, {-v:.6g}]",
        f"walls[0].ramp_time={ramp:.6g}", f"walls[1].ramp_time={ramp:.6g}", f"run.stop[0].after_time={ramp:.6g}",
        f"run.duration={0.05 / rate:.6g}",
        f"measure[0].centre=[{mm(width / 2)}, {mm(height / 2)}]", f"measure[0].radius={mm(0.4 * width)}",
        "output.frame_every=0", "output.history_every=50",
    ]


def geometry_3d(side, r_min, rate):
    """Overrides of scenes/uniaxial_3d.toml for a cube of this side."""
    v = rate * side / 2
    ramp = 2e-4 / rate
    c = mm(side / 2)
    # The platens keep the reference scene's ratio to the grains' own k_n = 4 R E_c (Tang 3.38), which grows
    # with R in 3D: a fixed platen stiffness would be softer than coarse grains and lower E by itself.
    kn = 2e8 * r_min / 2e-3
    return [
        f"walls[0].kn={kn:.6g}", f"walls[1].kn={kn:.6g}",
        f"specimen.hi=[{mm(side)}, {mm(side)}, {mm(side)}]", f"specimen.radius_min={mm(r_min)}",
        f"walls[0].centre=[{c}, {c}, 0]", f"walls[1].centre=[{c}, {c}, {mm(side)}]",
        f"walls[0].size=[{mm(1.4 * side)}, {mm(1.4 * side)}]", f"walls[1].size=[{mm(1.4 * side)}, {mm(1.4 * side)}]",
        f"walls[0].area={side * side:.6g}", f"walls[1].area={side * side:.6g}",
        f"walls[0].velocity=[0, 0, {v:.6g}]", f"walls[1].velocity=[0, 0, {-v:.6g}]",
        f"walls[0].ramp_time={ramp:.6g}", f"walls[1].ramp_time={ramp:.6g}", f"run.stop[0].after_time={ramp:.6g}",
        f"run.duration={0.05 / rate:.6g}",
        f"measure[0].centre=[{c}, {c}, {c}]", f"measure[0].radius={mm(0.4 * side)}",
        "output.frame_every=0", "output.history_every=50",
    ]


def geometry(dim, lr, rate, size):
    """Case II of Tang §5.4.1: the specimen keeps its size, R_min follows L/R = W / R_mean."""
    r_min = size / (lr * MEAN)
    return geometry_2d(size, 2 * size, r_min, rate) if dim == 2 else geometry_3d(size, r_min, rate)


def plan(full, dims, only, seeds):
    """(study, dim, label, x, seed, overrides) for every run."""
    runs = []
    for dim in dims:
        size = 0.1                                    # W = 100 mm (2D: 100 x 200 mm), 3D: 100 mm cube
        if full:
            lrs = [20, 40, 60, 80, 120, 160, 240] if dim == 2 else [10, 20, 31, 39, 51, 62, 77]
            rates = [0.01, 0.03, 0.1, 0.3, 1, 3, 10, 30, 100]
            lr_rate = 120 if dim == 2 else 38   # also the timestep and density sweeps
        else:
            lrs = [20, 30, 40, 60, 80, 120] if dim == 2 else [10, 15, 20, 25]
            rates = [0.01, 0.03, 0.1, 0.3, 1, 3, 10, 30, 100]
            lr_rate = 40 if dim == 2 else 15
        if "rate" in only:
            for r in rates:
                runs.append(("rate", dim, f"{r:g} /s", r, 1, geometry(dim, lr_rate, r, size)))
        if "resolution" in only:
            for lr in lrs:
                for s in range(1, seeds + 1):
                    runs.append(("resolution", dim, f"L/R {lr}", lr, s, geometry(dim, lr, 0.1, size) + [f"seed={s}"]))
        if "timestep" in only:
            for f in [0.1, 0.2, 0.4, 0.6, 0.8, 0.95]:
                runs.append(("timestep", dim, f"safety {f:g}", f, 1,
                             geometry(dim, lr_rate, 0.1, size) + [f"timestep.safety={f:g}"]))
        if "density" in only:
            for f in [1, 10, 100, 1000, 10000]:
                runs.append(("density", dim, f"F {f:g}", f, 1,
                             geometry(dim, lr_rate, 0.1, size) + [f"physics.density_scaling={f:g}"]))
    return runs


def timed_run(exe, scene, h5, overrides, keep=False, threads=1):
    """`mesocrack run scene -o h5` on `threads` threads (one by default) with --set overrides; its summary (JSON as
    a dict), and the CPU seconds (user + system of the child, summed over its threads: robust to whatever else the
    machine is doing) and wall seconds it took. The output files are deleted unless `keep`: the numbers are in the
    summary."""
    cmd = [exe, "run", str(scene), "-o", str(h5), "--threads", str(threads)]
    for o in overrides:
        cmd += ["--set", o]
    t0 = time.monotonic()
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                         env={**os.environ, "OMP_NUM_THREADS": str(threads)})
    _, status, usage = os.wait4(p.pid, 0)
    err = p.stderr.read().decode()
    code = os.waitstatus_to_exitcode(status)
    wall = time.monotonic() - t0
    if code != 0:
        raise RuntimeError(f"{h5.stem}: exit {code}: {err[-2000:]}")
    s = json.loads(subprocess.run([exe, "summary", str(h5)], capture_output=True, check=True, text=True).stdout)
    if not keep:
        for f in h5.parent.glob(h5.stem + "*"):
            f.unlink()
    return s, usage.ru_utime + usage.ru_stime, wall


def study_arguments(doc, out_name, only):
    """The options every study shares: the binary, the output folder, the runs at once, the sweeps, re-analysis."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesocrack", default=str(ROOT / "build" / "mesocrack"))
    ap.add_argument("--out", default=str(ROOT / "out" / out_name))
    ap.add_argument("--jobs", type=int, default=1, help="runs at once (each on one thread)")
    ap.add_argument("--only", default=only)
    ap.add_argument("--analyse", action="store_true", help="only redraw tables and plots from results.csv")
    return ap


def run_one(exe, out, key, dim, overrides):
    s, cpu, wall = timed_run(exe, ROOT / "scenes" / f"uniaxial_{dim}d.toml", out / "runs" / f"{key}.h5", overrides)
    u = s["uniaxial"] or {}
    return {"E": u.get("E"), "E_platens": u.get("E_platens"), "E_inside": u.get("E_inside"), "nu": u.get("nu"),
            "ucs": u.get("ucs"), "init_ratio": u.get("crack_initiation_ratio"),
            "particles": s["particles"], "steps": s["steps"],
            "cpu_s": cpu, "wall_s": wall}


def run_appending(exe, out, jobs, csv_path, fields, todo, done):
    """Runs todo's (run key, dim, overrides, done key, known columns) at `jobs` at once, appending each row to
    csv_path as its run ends (the rest of its columns from run_one) and to `done`, so an interrupted study goes
    on where it stopped."""
    with appending(rows_file(csv_path), fields) as (w, f), cf.ThreadPoolExecutor(jobs) as pool:
        futs = {pool.submit(run_one, exe, out, key, dim, ov): (key, done_key, known)
                for key, dim, ov, done_key, known in mine(todo)}
        for fut in cf.as_completed(futs):
            key, done_key, known = futs[fut]
            res = fut.result()
            r = {**known, **{k: res.get(k) for k in fields if k not in known}}
            w.writerow(r)
            f.flush()
            done[done_key] = r
            print(f"{key}: E {r['E'] * 1e-9:.2f} GPa, nu {r['nu']:.3f}, UCS {r['ucs'] * 1e-6:.2f} MPa, "
                  f"{r['cpu_s']:.1f} CPU s", flush=True)


def append_rows(csv_path, fields, jobs, items, one, line):
    """Runs one(item) for every item, `jobs` at once, and appends the row (a dict of `fields`) each returns to
    csv_path as it ends, printing line(row): a study's loop, so that an interrupted study goes on where it
    stopped (its driver skips the rows already there)."""
    with appending(rows_file(csv_path), fields) as (w, f), cf.ThreadPoolExecutor(jobs) as pool:
        for fut in cf.as_completed([pool.submit(one, t) for t in mine(items)]):
            r = fut.result()
            w.writerow(r)
            f.flush()
            print(line(r), flush=True)


def read_rows(csv_path, fields, texts):
    """The rows of a study's results.csv: the `texts` columns as strings, the others as floats (None if empty or
    missing: a column the study gained after the row was written)."""
    rows = []
    for path in result_files(csv_path):
        with open(path) as f:
            for r in csv.DictReader(f):
                rows.append({k: (r.get(k) if k in texts else float(r[k]) if r.get(k) not in (None, "", "None")
                                 else None) for k in fields})
    return rows


def study_main(ap, fields, texts, key, plan, known, run_all, analyse):
    """A study's driver: parse ap; unless --analyse, run the plan(args) items whose key(known(item)) is not yet
    a row of --out's results.csv (key(row) for the rows), by run_all(exe, out, jobs, items, csv_path); then
    analyse(rows, out)."""
    a = ap.parse_args()
    out = Path(a.out)
    (out / "runs").mkdir(parents=True, exist_ok=True)
    csv_path = out / "results.csv"
    if not a.analyse:
        if not shutil.which(a.mesocrack) and not Path(a.mesocrack).exists():
            sys.exit(f"{a.mesocrack}: not found (build first: make demo, or give --mesocrack)")
        done = {key(r) for r in read_rows(csv_path, fields, texts)}
        todo = [t for t in plan(a) if key(known(t)) not in done]
        print(f"{len(todo)} runs to do ({len(done)} already in {csv_path})", flush=True)
        run_all(a.mesocrack, out, a.jobs, todo, csv_path)
        ranks_done(csv_path)
    analyse(read_rows(csv_path, fields, texts), out)


def seed_list(text):
    """"1-6" or "1,3,5": the seeds a study's --seeds names."""
    out = []
    for part in text.split(","):
        lo, _, hi = part.partition("-")
        out += list(range(int(lo), int(hi or lo) + 1))
    return out


def mean_cv(xs):
    xs = [x for x in xs if x is not None]
    m = sum(xs) / len(xs)
    sd = math.sqrt(sum((x - m) ** 2 for x in xs) / (len(xs) - 1)) if len(xs) > 1 else 0.0
    return m, sd / abs(m)


def ceb_dif(rate, f_cs_mpa):
    """CEB dynamic increase factor of compressive strength, Tang (5.6), static rate 30e-6 /s, f_co = 10 MPa.
    As printed, (5.6) drops the static rate from the upper branch and garbles log gamma_s; CEB-FIP 1990 has
    gamma_s (rate / rate_s)^(1/3) with log gamma_s = 6.156 alpha - 2, which joins the lower branch at 30 /s."""
    alpha = 1 / (5 + 9 * f_cs_mpa / 10)
    gamma = 10 ** (6.156 * alpha - 2)
    return (rate / 30e-6) ** (1.026 * alpha) if rate <= 30 else gamma * (rate / 30e-6) ** (1 / 3)


def by_setting(rows):
    """The runs of a sweep grouped by their setting x."""
    groups = {}
    for r in rows:
        groups.setdefault(r["x"], []).append(r)
    return groups


def strain_source_table(by):
    """E from the platens' gap against E from the inside of the specimen (Tang §5.4.1's L/R dependence): the
    axial-strain definition whose E depends least on L/R measures the material, not the platen contacts."""
    lines = []
    for dim in (2, 3):
        groups = by_setting([r for r in by.get(("resolution", dim), []) if r.get("E_inside") is not None])
        if not groups:
            continue
        xs = sorted(groups)
        lines.append(f"\n### axial strain from the platens or from inside, {dim}D (E, secant 25-50 %)\n")
        lines.append("| L/R | runs | E platens [GPa] | CV | E inside [GPa] | CV | inside / platens |")
        lines.append("|---|---|---|---|---|---|---|")
        for x in xs:
            (ep, cvp), (ei, cvi) = (mean_cv([r[q] for r in groups[x]]) for q in ("E_platens", "E_inside"))
            lines.append(f"| {x:g} | {len(groups[x])} | {ep * 1e-9:.2f} | {cvp:.1%} | {ei * 1e-9:.2f} | {cvi:.1%} | "
                         f"{ei / ep:.3f} |")
        lo, hi = xs[0], xs[-1]
        for q in ("E_platens", "E_inside"):
            a, b = (mean_cv([r[q] for r in groups[x]])[0] for x in (lo, hi))
            lines.append(f"\n{q}: {b / a - 1:+.1%} from L/R {lo:g} to {hi:g}")
    return lines


def analyse(rows, out):
    """Tables (markdown) and plots from results rows."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lines = []
    points = []   # (study, dim, label, cpu_s, err_E, err_ucs) for the accuracy-versus-time plot
    by = {}
    for r in rows:
        by.setdefault((r["study"], r["dim"]), []).append(r)
    for (study, dim), rs in sorted(by.items()):
        groups = by_setting(rs)
        xs = sorted(groups)
        ref_x = max(xs) if study == "resolution" else min(xs)  # the finest L/R; the slowest rate, smallest step or F
        ref = {q: mean_cv([g[q] for g in groups[ref_x]])[0] for q in ("E", "nu", "ucs")}
        lines.append(f"\n### {study}, {dim}D (reference: {groups[ref_x][0]['label']})\n")
        lines.append("| setting | particles | runs | E [GPa] | CV E | nu | CV nu | UCS [MPa] | CV UCS | err E | err nu | err UCS | CPU s / run |")
        lines.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for x in xs:
            g = groups[x]
            (e, cve), (nu, cvn), (u, cvu) = (mean_cv([r[q] for r in g]) for q in ("E", "nu", "ucs"))
            cpu = sum(r["cpu_s"] for r in g) / len(g)
            # a single run's expected error: the bias of the mean and the scatter of one draw
            err = {q: math.hypot(m / ref[q] - 1, cv) for q, m, cv in (("E", e, cve), ("nu", nu, cvn), ("ucs", u, cvu))}
            lines.append(f"| {g[0]['label']} | {int(g[0]['particles'])} | {len(g)} | {e * 1e-9:.2f} | {cve:.1%} | {nu:.3f} | "
                         f"{cvn:.1%} | {u * 1e-6:.2f} | {cvu:.1%} | {err['E']:.1%} | {err['nu']:.1%} | {err['ucs']:.1%} | {cpu:.1f} |")
            if x != ref_x:
                points.append((study, dim, g[0]["label"], cpu, err["E"], err["ucs"]))
    lines += strain_source_table(by)
    md = out / "accuracy.md"
    md.write_text("# What accuracy costs in time (uniaxial compression)\n" + "\n".join(lines) + "\n")
    print("\n".join(lines))

    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    marks = {"rate": "o", "resolution": "s", "timestep": "^", "density": "D"}
    for ax, k, name in ((axes[0], 4, "E"), (axes[1], 5, "UCS")):
        for study in marks:
            for dim, color in ((2, "tab:blue"), (3, "tab:red")):
                p = [q for q in points if q[0] == study and q[1] == dim]
                if p:
                    ax.loglog([q[3] for q in p], [max(q[k], 1e-4) for q in p], marks[study], color=color,
                              label=f"{study} {dim}D", alpha=0.8)
        for level in (0.01, 0.05):
            ax.axhline(level, color="grey", lw=0.6, ls="--")
        ax.set_xlabel("CPU seconds per run (one core)")
        ax.set_ylabel(f"error of {name} against the finest / slowest run")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(out / "accuracy_vs_time.png", dpi=110)

    for dim in (2, 3):
        rs = by.get(("rate", dim))
        if not rs:
            continue
        rs = sorted(rs, key=lambda r: r["x"])
        base = rs[0]
        f_cs = base["ucs"] * 1e-6
        fig, ax = plt.subplots(figsize=(6, 4.5))
        rates = [r["x"] for r in rs]
        ax.semilogx(rates, [r["ucs"] / base["ucs"] for r in rs], "o-", label="UCS / UCS(0.01 /s), mesocrack")
        ax.semilogx(rates, [r["E"] / base["E"] for r in rs], "s--", label="E / E(0.01 /s), mesocrack")
        fine = [10 ** (k / 20) for k in range(-40, 41)]
        ax.semilogx(fine, [ceb_dif(r, f_cs) / ceb_dif(rates[0], f_cs) for r in fine], "k-", lw=1,
                    label="CEB DIF (5.6), normalised at 0.01 /s")
        ax.set_xlabel("strain rate [1/s]")
        ax.set_ylabel("increase factor")
        ax.set_title(f"Rate dependence, {dim}D")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(out / f"rate_dif_{dim}d.png", dpi=110)

    for dim in (2, 3):
        groups = by_setting(by.get(("resolution", dim), []))
        if not groups:
            continue
        xs = sorted(groups)
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
        for q, scale, unit, ax in (("E_platens", 1e-9, "E [GPa]", axes[0]), ("E_inside", 1e-9, "E [GPa]", axes[0]),
                                   ("ucs", 1e-6, "UCS [MPa]", axes[1])):
            vals = {x: [r[q] for r in groups[x] if r.get(q) is not None] for x in xs}
            xq = [x for x in xs if vals[x]]
            if not xq:
                continue
            ms = [mean_cv(vals[x]) for x in xq]
            ax.errorbar(xq, [m * scale for m, _ in ms], yerr=[m * cv * scale for m, cv in ms], fmt="o-", capsize=3,
                        label={"E_platens": "axial strain from the platens", "E_inside": "axial strain inside"}.get(q))
            ax.set_xlabel("L/R")
            ax.set_ylabel(unit + " (mean ± std over seeds)")
        axes[0].legend(fontsize=8)
        fig.suptitle(f"Resolution, {dim}D (Tang Figs. 5.9-5.12)")
        fig.tight_layout()
        fig.savefig(out / f"resolution_{dim}d.png", dpi=110)


def main():
    ap = study_arguments(__doc__, "accuracy", "rate,resolution,timestep,density")
    ap.add_argument("--full", action="store_true", help="Tang's full ranges (hours)")
    ap.add_argument("--dims", default="2,3")
    ap.add_argument("--seeds", type=int, default=5, help="realizations per point of the resolution sweep")
    a = ap.parse_args()
    out = Path(a.out)
    (out / "runs").mkdir(parents=True, exist_ok=True)
    csv_path = out / "results.csv"
    fields = ["study", "dim", "label", "x", "seed", "E", "E_platens", "E_inside", "nu", "ucs", "init_ratio", "particles", "steps", "cpu_s", "wall_s"]
    done = {}
    for path in result_files(csv_path):
        with open(path) as f:
            reader = csv.DictReader(f)
            # an older file (fewer columns) can be analysed, not appended to
            if not a.analyse and reader.fieldnames != fields:
                sys.exit(f"{path}: its columns {reader.fieldnames} are not this script's {fields}; give another --out")
            for r in reader:
                for k in fields[3:]:
                    r[k] = float(r[k]) if r.get(k) not in (None, "", "None") else None
                r["dim"] = int(r["dim"])
                done[(r["study"], r["dim"], r["label"], int(r["seed"]))] = r
    if not a.analyse:
        only = set(a.only.split(","))
        dims = [int(d) for d in a.dims.split(",")]
        todo = [p for p in plan(a.full, dims, only, a.seeds) if (p[0], p[1], p[2], p[4]) not in done]
        print(f"{len(todo)} runs to do ({len(done)} already in {csv_path})", flush=True)
        run_appending(a.mesocrack, out, a.jobs, csv_path, fields, [
            (f"{study}_{dim}d_{label.replace(' ', '').replace('/', '')}_s{seed}", dim, ov, (study, dim, label, seed),
             {"study": study, "dim": dim, "label": label, "x": x, "seed": seed})
            for study, dim, label, x, seed, ov in todo], done)
        ranks_done(csv_path)
    analyse(list(done.values()), out)


if __name__ == "__main__":
    sys.exit(main())
