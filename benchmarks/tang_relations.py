#!/usr/bin/python3
"""Tang's micro-macro relations (6.1)-(6.9) reproduced: sweeps of one micro-parameter at a time about Table 5.1.

Each point is the real `mesocrack run` of scenes/uniaxial_2d.toml or uniaxial_3d.toml, single-threaded, at a
reduced resolution (--lr2, --lr3: L/R = W / R_mean with the 100 mm specimen width kept, as the accuracy study's
resolution sweep) for 3+ seeds (packing and bond strengths both follow the seed). Swept, the others at Table 5.1:
  modulus            E_c = Ē_c (grain and bond together, as Table 5.1 has them), 10-30 GPa      (6.1)
  stiffness_ratio    k_n/k_s = k̄_n/k̄_s together, 1-4                                           (6.2), (6.3)
  radius_multiplier  λ̄, 0.5-1                                                                  (6.4), (6.5)
  strength_ratio     τ̄_b,m/σ̄_b,m with σ̄_b kept, τ̄_b's spread scaled with its mean, 0.25-3     (6.6), (6.7)
  friction           μ, 0-1                                                                     (6.8), (6.9)
The platens keep their stiffness in proportion to the grains' (k_n ∝ E_c R in 3D, E_c in 2D), so that only the
material changes. The packing is the same for every point of a seed.

Output (--out, default out/tang_relations): results.csv (one row per run: E in the declared reading and from
both axial strains, ν, UCS), relations.md (for each relation and quantity: Tang's value and slope at the
reference point against ours, from a least-squares fit of Tang's own functional form to our means) and one
plot per relation (relation_6_K.png: our means ± one standard deviation over seeds as points, Tang's line).

  benchmarks/tang_relations.py --jobs 2                      # both dimensions, all sweeps (about 45 CPU minutes)
  benchmarks/tang_relations.py --dims 2 --only friction      # one sweep
  benchmarks/tang_relations.py --analyse                     # tables and plots from results.csv
"""
import csv
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from uniaxial_accuracy import (MEAN, geometry_2d, geometry_3d, mean_cv, ranks_done, result_files, run_appending,  # noqa: E402
                               study_arguments)

# Table 5.1: the reference point of every sweep.
REFERENCE = {
    2: {"modulus": 20e9, "stiffness_ratio": 2.0, "radius_multiplier": 1.0, "strength_ratio": 2.0, "friction": 0.5,
        "sigma": 18e6, "sigma_std": 2e6},
    3: {"modulus": 19e9, "stiffness_ratio": 1.4, "radius_multiplier": 1.0, "strength_ratio": 2.0, "friction": 0.5,
        "sigma": 27e6, "sigma_std": 4e6},
}
SWEEPS = {
    "modulus": [10e9, 15e9, 20e9, 25e9, 30e9],
    "stiffness_ratio": [1.0, 1.4, 2.0, 3.0, 4.0],
    "radius_multiplier": [0.5, 0.625, 0.75, 0.875, 1.0],
    "strength_ratio": [0.25, 0.5, 1.0, 1.5, 2.0, 3.0],
    "friction": [0.0, 0.25, 0.5, 0.75, 1.0],
}


def piecewise_6_6(r):
    """(6.6), PFC2D: σ_c [MPa] against τ̄/σ̄; constant beyond 1.5."""
    r = min(r, 1.5)
    return 28.13 * r + 1.05 if r <= 0.5 else -11.76 * r * r + 35.66 * r + 0.24


def piecewise_6_7(r):
    """(6.7), PFC3D; constant beyond 2.0."""
    r = min(r, 2.0)
    return 33.27 * r + 0.81 if r <= 0.5 else -9.12 * r * r + 38.13 * r + 0.72


# Tang's relations: (equation, dim, sweep, quantity, his function of the swept parameter, the functional form
# fitted to ours). Quantities: E [GPa] (6.1 only), E/E_c, nu, ucs [MPa]. The parameter of (6.1) is E_c in GPa.
RELATIONS = [
    ("6.1", 2, "modulus", "E", lambda x: 1.27 * x - 0.05, "linear"),
    ("6.1", 3, "modulus", "E", lambda x: 1.24 * x - 0.02, "linear"),
    ("6.2", 2, "stiffness_ratio", "E/Ec", lambda x: -0.42 * math.log(x) + 1.57, "log"),
    ("6.2", 2, "stiffness_ratio", "nu", lambda x: 0.11 * math.log(x) + 0.12, "log"),
    ("6.2", 2, "stiffness_ratio", "ucs", lambda x: -1.16 * x + 30.13, "linear"),
    ("6.3", 3, "stiffness_ratio", "E/Ec", lambda x: -0.39 * math.log(x) + 1.36, "log"),
    ("6.3", 3, "stiffness_ratio", "nu", lambda x: 0.11 * math.log(x) + 0.15, "log"),
    ("6.3", 3, "stiffness_ratio", "ucs", lambda x: 0.27 * x * x - 4.9 * x + 46.56, "quadratic"),
    ("6.4", 2, "radius_multiplier", "E/Ec", lambda x: 1.87 * x + 0.3, "linear"),
    ("6.4", 2, "radius_multiplier", "nu", lambda x: 0.20 * x ** -0.174, "power"),
    ("6.4", 2, "radius_multiplier", "ucs", lambda x: 37.31 * x + 5.95, "linear"),
    ("6.5", 3, "radius_multiplier", "E/Ec", lambda x: 0.64 * x * x + 0.22 * x + 0.23, "quadratic"),
    ("6.5", 3, "radius_multiplier", "nu", lambda x: 0.19 * x ** -0.71, "power"),
    ("6.5", 3, "radius_multiplier", "ucs", lambda x: 40 * x * x - 0.13 * x + 2.88, "quadratic"),
    ("6.6", 2, "strength_ratio", "ucs", piecewise_6_6, "piecewise"),
    ("6.7", 3, "strength_ratio", "ucs", piecewise_6_7, "piecewise"),
    ("6.8", 2, "friction", "E/Ec", lambda x: -0.2 * x * x + 0.44 * x + 1.1, "quadratic"),
    ("6.8", 2, "friction", "nu", lambda x: 0.07 * x * x - 0.13 * x + 0.26, "quadratic"),
    ("6.9", 3, "friction", "E/Ec", lambda x: -0.17 * x * x + 0.45 * x + 1, "quadratic"),
    ("6.9", 3, "friction", "nu", lambda x: 0.06 * x * x - 0.15 * x + 0.25, "quadratic"),
    ("6.9", 3, "friction", "ucs", lambda x: -8.86 * x * x + 19.11 * x + 33.5, "quadratic"),
]
SWEEP_LABEL = {"modulus": "E_c [GPa]", "stiffness_ratio": "k_n/k_s", "radius_multiplier": "λ̄",
               "strength_ratio": "τ̄_b,m/σ̄_b,m", "friction": "μ"}


def replace_key(overrides, key, value):
    """The overrides with key=value, an earlier setting of the key dropped."""
    return [o for o in overrides if not o.startswith(key + "=")] + [f"{key}={value}"]


def point_overrides(dim, lr, params):
    """--set strings for one point: the resolution's geometry, then the micro-parameters."""
    size = 0.1
    r_min = size / (lr * MEAN)
    ov = geometry_2d(size, 2 * size, r_min, 0.1) if dim == 2 else geometry_3d(size, r_min, 0.1)
    ref = REFERENCE[dim]
    ec = params["modulus"]
    # the platens keep the reference scene's ratio to the grains' normal stiffness (Tang 3.38)
    wall_kn = 4e10 * ec / 20e9 if dim == 2 else 2e8 * (r_min / 2e-3) * (ec / 19e9)
    for k in (0, 1):
        ov = replace_key(ov, f"walls[{k}].kn", f"{wall_kn:.6g}")
    ratio = params["strength_ratio"]
    ov += [
        f"contacts[0].modulus={ec:.6g}", f"contacts[0].bond_modulus={ec:.6g}",
        f"contacts[0].kn_ks_ratio={params['stiffness_ratio']:g}",
        f"contacts[0].bond_kn_ks_ratio={params['stiffness_ratio']:g}",
        f"contacts[0].bond_radius_multiplier={params['radius_multiplier']:g}",
        f"contacts[0].friction={params['friction']:g}",
        f"contacts[0].bond_shear_strength={ratio * ref['sigma']:.6g}",
        f"contacts[0].bond_shear_strength_std={ratio * ref['sigma_std']:.6g}",
    ]
    return ov


def point_key(dim, params, seed):
    ref = REFERENCE[dim]
    changed = [f"{k}{params[k]:g}" for k in SWEEPS if params[k] != ref[k]] or ["reference"]
    return f"{dim}d_{'_'.join(changed)}_s{seed}"


def plan(dims, only, seeds, lrs):
    """Unique runs (the reference point is shared by every sweep): (key, dim, params, seed, overrides)."""
    runs = {}
    for dim in dims:
        for sweep in only:
            for x in SWEEPS[sweep]:
                params = {k: v for k, v in REFERENCE[dim].items() if k in SWEEPS}
                params[sweep] = x
                for seed in range(1, seeds + 1):
                    key = point_key(dim, params, seed)
                    if key not in runs:
                        runs[key] = (key, dim, params, seed, point_overrides(dim, lrs[dim], params) + [f"seed={seed}"])
    return list(runs.values())


def fit(form, xs, ys):
    """Least-squares fit of Tang's functional form; returns f(x) and f'(x)."""
    xs, ys = np.asarray(xs, float), np.asarray(ys, float)
    if form == "linear":
        b, a = np.polyfit(xs, ys, 1)
        return (lambda x: a + b * x), (lambda x: b)
    if form == "quadratic":
        c2, c1, c0 = np.polyfit(xs, ys, 2)
        return (lambda x: c0 + c1 * x + c2 * x * x), (lambda x: c1 + 2 * c2 * x)
    if form == "log":
        b, a = np.polyfit(np.log(xs), ys, 1)
        return (lambda x: a + b * math.log(x)), (lambda x: b / x)
    if form == "power":
        b, la = np.polyfit(np.log(xs), np.log(ys), 1)
        return (lambda x: math.exp(la) * x ** b), (lambda x: b * math.exp(la) * x ** (b - 1))
    if form == "piecewise":
        # (6.6), (6.7): the first segment's slope (points up to 0.5); between the points, straight lines
        low = xs <= 0.5 + 1e-12
        b = np.polyfit(xs[low], ys[low], 1)[0] if low.sum() >= 2 else float("nan")
        return (lambda x: float(np.interp(x, xs, ys))), (lambda x: b)
    raise ValueError(form)


def derivative(f, x, h=1e-4):
    return (f(x + h) - f(x - h)) / (2 * h)


def quantity(row, q):
    if q == "E":
        return row["E"] * 1e-9
    if q == "E/Ec":
        return row["E"] / row["Ec"]
    if q == "ucs":
        return row["ucs"] * 1e-6
    return row[q]


def analyse(rows, out, lrs):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    lines = ["# Tang's micro-macro relations (6.1)-(6.9), ours beside his",
             "", f"Resolution: 2D L/R {lrs[2]:g}, 3D L/R {lrs[3]:g}; E and ν in the declared reading of the scenes "
             "(2D plane strain), secant 25-50 % of the peak. 'ours at ref.' is the mean ± standard deviation over "
             "the seeds at the reference point; the slopes are d(quantity)/d(parameter) there, ours from Tang's "
             "functional form fitted to our means ((6.6), (6.7): the slope of the first segment, 0-0.5, and our "
             "means joined by straight lines); slope/value is the relative slope at the reference.", "",
             "| relation | dim | parameter (ref.) | quantity | Tang at ref. | ours at ref. | Tang slope | ours slope |"
             " ours/Tang slope | Tang slope/value | ours slope/value |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    figs = {}
    for eq, dim, sweep, q, tang, form in RELATIONS:
        ref = REFERENCE[dim]
        groups = {}
        for r in rows:
            if r["dim"] != dim:
                continue
            params = {k: r[k] for k in SWEEPS}
            others = all(params[k] == ref[k] for k in SWEEPS if k != sweep)
            if others:
                groups.setdefault(params[sweep], []).append(quantity(r, q))
        if len(groups) < 3:
            continue
        scale = 1e-9 if sweep == "modulus" else 1.0        # (6.1) is in GPa
        xs = sorted(groups)
        px = [x * scale for x in xs]
        means = [mean_cv(groups[x])[0] for x in xs]
        sds = [abs(m) * mean_cv(groups[x])[1] for m, x in zip(means, xs)]
        f, df = fit(form, px, means)
        x0 = ref[sweep] * scale
        m0, cv0 = mean_cv(groups[ref[sweep]]) if ref[sweep] in groups else (f(x0), 0.0)
        # the piecewise relations are flat at the reference: their slope is the first segment's (0-0.5)
        x_slope = 0.25 if form == "piecewise" else x0
        t_slope, o_slope = derivative(tang, x_slope), df(x_slope)
        where = " on 0-0.5" if form == "piecewise" else ""
        # relative slopes (slope / value at the reference) compare trends when the reference values differ
        t_rel, o_rel = t_slope / tang(x0), o_slope / m0
        lines.append(f"| ({eq}) | {dim}D | {SWEEP_LABEL[sweep]} ({x0:g}) | {q} | {tang(x0):.3f} | "
                     f"{m0:.3f} ± {abs(m0) * cv0:.3f} | {t_slope:.3f}{where} | {o_slope:.3f}{where} | "
                     f"{o_slope / t_slope:.2f} | {t_rel:+.3f} | {o_rel:+.3f} |")
        figs.setdefault(eq, []).append((q, dim, sweep, px, means, sds, tang, f))
    ylabel = {"E": "E [GPa]", "E/Ec": "E / E_c", "nu": "ν", "ucs": "UCS [MPa]"}
    for eq, series in figs.items():
        panels = list(dict.fromkeys(q for q, *_ in series))
        fig, axes = plt.subplots(1, len(panels), figsize=(4.8 * len(panels), 4.2), squeeze=False)
        for q, dim, sweep, px, means, sds, tang, f in series:
            ax = axes[0][panels.index(q)]
            color = "tab:blue" if dim == 2 else "tab:red"
            ax.errorbar(px, means, yerr=sds, fmt="o", capsize=3, color=color,
                        label=f"mesocrack {dim}D (mean ± sd over seeds)")
            fine = np.linspace(min(px), max(px), 100)
            ax.plot(fine, [tang(x) for x in fine], "-", lw=1.2, color="k" if dim == 2 else "grey",
                    label=f"Tang ({eq}), {dim}D")
            ax.plot(fine, [f(x) for x in fine], "--", lw=0.8, color=color, label=f"Tang's form fitted to ours, {dim}D")
            ax.set_xlabel(SWEEP_LABEL[sweep])
            ax.set_ylabel(ylabel[q])
            ax.legend(fontsize=7)
        fig.suptitle(f"Tang ({eq})")
        fig.tight_layout()
        fig.savefig(out / f"relation_{eq.replace('.', '_')}.png", dpi=110)
        plt.close(fig)
    (out / "relations.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


FIELDS = ["key", "dim", "seed", *SWEEPS, "Ec", "E", "E_platens", "E_inside", "nu", "ucs", "particles", "cpu_s"]


def main():
    ap = study_arguments(__doc__, "tang_relations", ",".join(SWEEPS))
    ap.add_argument("--dims", default="2,3")
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--lr2", type=float, default=60, help="2D L/R (Table 5.1: 120)")
    ap.add_argument("--lr3", type=float, default=15, help="3D L/R (Table 5.1: 38)")
    a = ap.parse_args()
    if a.seeds < 3:
        sys.exit("--seeds: at least 3, for a spread per point")
    only = a.only.split(",")
    unknown = [s for s in only if s not in SWEEPS]
    if unknown:
        sys.exit(f"--only: unknown sweep(s) {unknown}; allowed: {', '.join(SWEEPS)}")
    lrs = {2: a.lr2, 3: a.lr3}
    out = Path(a.out)
    (out / "runs").mkdir(parents=True, exist_ok=True)
    csv_path = out / "results.csv"
    done = {}
    for path in result_files(csv_path):
        with open(path) as f:
            for r in csv.DictReader(f):
                for k in FIELDS[2:]:
                    r[k] = float(r[k]) if r.get(k) not in (None, "", "None") else None
                r["dim"], r["seed"] = int(r["dim"]), int(r["seed"])
                done[r["key"]] = r
    if not a.analyse:
        dims = [int(d) for d in a.dims.split(",")]
        todo = [p for p in plan(dims, only, a.seeds, lrs) if p[0] not in done]
        print(f"{len(todo)} runs to do ({len(done)} already in {csv_path})", flush=True)
        run_appending(a.mesocrack, out, a.jobs, csv_path, FIELDS, [
            (key, dim, ov, key, {"key": key, "dim": dim, "seed": seed, **params, "Ec": params["modulus"]})
            for key, dim, params, seed, ov in todo], done)
        ranks_done(csv_path)
    analyse(list(done.values()), out, lrs)


if __name__ == "__main__":
    sys.exit(main())
