"""The fibres of a rigid-cell specimen (Květoň Part II), for app/report.py: the crack pattern with the fibres that
bridge it, and beside it the load against the displacement the scene plots and how many fibres bridge, have been
pulled out and have broken."""
import matplotlib

matplotlib.use("Agg")  # headless: no display on compute nodes or CI
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.cm import ScalarMappable  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.colors import Normalize  # noqa: E402

from report_plots import save, si_scale, with_unit  # noqa: E402
from report_specimen import CRACK_DAMAGE, cell_picture, draw_cracked_facets, frame_axes  # noqa: E402

# RigidCellSystem's FibreState: 0 idle, 1 bridging, 2 pulled out, 3 ruptured.
BRIDGING, PULLED_OUT, RUPTURED = 1, 2, 3
# More bridging fibres than this are drawn as an even sample of them (every k-th), which the title says: tens of
# thousands of lines hide the cracks they cross.
MOST_DRAWN = 4000
COUNTS = (("fibres.bridging", "bridging"), ("fibres.pulled_out", "pulled out"), ("fibres.ruptured", "broken"))


def draw_pattern(ax, run, frame):
    """The cracked facets over the cells' outlines, and the bridging fibres projected on the picture plane by their
    force. Returns the force's colour scale and what the title says of the fibres."""
    c = run["cells"]
    fibres = c["fibres"]
    outlines, facets, which, plane = cell_picture(run)
    lo, hi = c["corner"][:, :2].min(axis=0), c["corner"][:, :2].max(axis=0)
    factor, lunit = si_scale(np.abs([lo, hi]).ravel(), "m")
    ax.add_collection(LineCollection(outlines * factor, colors="0.88", linewidths=0.3))
    state, force = frame["fibre_state"], frame["fibre_force"]
    bridging = np.flatnonzero(state == BRIDGING)
    every = max(1, -(-len(bridging) // MOST_DRAWN))
    shown = bridging[::every]
    fnorm = Normalize(0.0, max(float(force[bridging].max()) if len(bridging) else 0.0, 1e-300))
    segments = np.stack([fibres["a"][shown, :2], fibres["b"][shown, :2]], axis=1) * factor
    lines = LineCollection(segments, cmap="Blues", norm=fnorm, linewidths=0.5, alpha=0.7)
    lines.set_array(force[shown])
    ax.add_collection(lines)
    draw_cracked_facets(ax, c, facets, which, frame, factor, 1.8)
    frame_axes(ax, lo, hi, factor, lunit)
    drawn = f"{len(bridging)} bridging" + (f" (every {every}th drawn)" if every > 1 else "")
    said = (f"fibres: {drawn}, {int((state == PULLED_OUT).sum())} pulled out, {int((state == RUPTURED).sum())} "
            f"broken, of {len(state)}")
    tf, tu = si_scale([frame["time"]], "s")
    ax.set_title(f"t = {frame['time'] * tf:.4g} {tu}, step {frame['step']}: cracks (D ≥ {CRACK_DAMAGE:g}) over "
                 f"{plane}\n{said}", fontsize="small")
    return fnorm


def draw_curves(ax_load, ax_count, run):
    """The scene's first x-y pair (load against displacement), and the fibre counts against the same x (or time)."""
    hist = run["history"]
    if "time" not in hist:  # a generated specimen: no run, no histories
        for ax in (ax_load, ax_count):
            ax.text(0.5, 0.5, "no histories (a specimen not yet run)", ha="center", va="center", transform=ax.transAxes)
        return
    pairs = [(x, y) for x, y in run["xy_plots"] if x in hist and y in hist]
    xs = hist[pairs[0][0]] if pairs else hist["time"]
    fx, ux = si_scale(xs["data"], xs["unit"])
    xlabel = with_unit(xs["label"] or (pairs[0][0] if pairs else "time"), ux)
    if pairs:
        ys = hist[pairs[0][1]]
        fy, uy = si_scale(ys["data"], ys["unit"])
        ax_load.plot(xs["data"] * fx, ys["data"] * fy, lw=1.3, marker=".", ms=3)
        ax_load.set_ylabel(with_unit(ys["label"] or pairs[0][1], uy))
        ax_load.set_title(f"{pairs[0][1]} vs {pairs[0][0]}", fontsize="medium")
    else:
        ax_load.text(0.5, 0.5, "no x-y plot declared\n([output] xy_plots)", ha="center", va="center",
                     transform=ax_load.transAxes)
    ax_load.grid(alpha=0.3)
    for name, label in COUNTS:
        if name in hist:
            ax_count.plot(xs["data"] * fx, hist[name]["data"], lw=1.2, label=label)
    ax_count.set_xlabel(xlabel)
    ax_count.set_ylabel("fibres")
    ax_count.legend(fontsize="small")
    ax_count.grid(alpha=0.3)


def plot_fibres(run, stem, out_dir):
    c = run.get("cells")
    if c is None or "fibres" not in c or run["dimension"] != 3:
        return []
    frame = c["frames"][-1]
    fig = plt.figure(figsize=(14, 6.2), layout="constrained")
    left, right = fig.subfigures(1, 2, width_ratios=[1.5, 1])
    ax = left.subplots()
    fnorm = draw_pattern(ax, run, frame)
    left.colorbar(ScalarMappable(norm=fnorm, cmap="Blues"), ax=ax, shrink=0.7, label="fibre force [N]")
    ax_load, ax_count = right.subplots(2, 1, sharex=True)
    draw_curves(ax_load, ax_count, run)
    fig.suptitle(f"{stem}: cracks and the fibres bridging them (frame {frame['index'] + 1} of {frame['count']})",
                 fontsize="medium")
    return [save(fig, out_dir, stem, "fibres", dpi=130)]
