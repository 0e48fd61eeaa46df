"""Pictures of a mesocrack specimen, for app/report.py: the particles by phase, by out-of-balance force and (2D) their
bonds by phase pair, and the crack log over them; a 3D specimen is shown by its section at mid-depth. Rigid cells:
the crack pattern of their damaged facets."""
import matplotlib

matplotlib.use("Agg")  # headless: no display on compute nodes or CI
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.cm import ScalarMappable  # noqa: E402
from matplotlib.collections import EllipseCollection, LineCollection, PolyCollection  # noqa: E402
from matplotlib.colors import ListedColormap, Normalize  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from report_plots import save, si_scale  # noqa: E402

MODE_COLOURS = {1: "tab:blue", 2: "tab:red"}
# Line styles of the cracks, one per phase pair.
PAIR_STYLES = ["-", "--", "-.", (0, (5, 1, 1, 1, 1, 1))]


def phase_name(names, p):
    return names[p] if 0 <= p < len(names) and names[p] else f"phase {p}"


def section(run):
    """Particles to draw as circles in a plane: (centres [M,2], radii, phase, |F| or None,
    axis names, plot limits, description). 2D: all discs. 3D: the spheres cut by y = centre."""
    spec, frame = run["specimen"], run["frame"]
    x = frame["x"] if frame and frame["x"].shape == spec["x"].shape else spec["x"]
    force = frame["force"] if frame and frame["force"] is not None and frame["force"].shape == x.shape else None
    fmag = np.linalg.norm(force, axis=1) if force is not None else None
    r, phase = spec["radius"], spec["phase"]
    if frame and x is frame["x"]:
        step = f", step {frame['step']}" if frame["step"] is not None else ""
        factor, unit = si_scale([frame["time"]], "s")
        when = f"t = {frame['time'] * factor:.4g} {unit}{step} (frame {frame['index'] + 1} of {frame['count']})"
    else:
        when = "initial specimen (no frames)"
    # Limits from the whole specimen, so a 3D section shows where it lies in the specimen.
    plane = [0, 1] if run["dimension"] == 2 else [0, 2]
    limits = ((x[:, plane] - r[:, None]).min(axis=0), (x[:, plane] + r[:, None]).max(axis=0))
    if run["dimension"] == 2:
        return x, r, phase, fmag, ("x", "y"), limits, when
    lo, hi = (x[:, 1] - r).min(), (x[:, 1] + r).max()
    yc = 0.5 * (lo + hi)
    d = np.abs(x[:, 1] - yc)
    cut = d < r
    rc = np.sqrt(r[cut] ** 2 - d[cut] ** 2)
    factor, unit = si_scale([yc], "m")
    when += f", section y = {yc * factor:.4g} {unit}"
    return (x[cut][:, plane], rc, phase[cut], fmag[cut] if fmag is not None else None, ("x", "z"), limits, when)


def set_limits(ax, limits, factor):
    ax.set_xlim(limits[0][0] * factor, limits[1][0] * factor)
    ax.set_ylim(limits[0][1] * factor, limits[1][1] * factor)
    ax.set_aspect("equal")


def draw_discs(ax, xy, r, limits, factor, **style):
    # One EllipseCollection in data units: fast for 50k discs, unlike one Circle patch each.
    coll = EllipseCollection(2 * r * factor, 2 * r * factor, np.zeros_like(r), units="xy",
                             offsets=xy * factor, offset_transform=ax.transData,
                             linewidths=0.3 if len(r) <= 2000 else 0, edgecolors="0.2", **style)
    ax.add_collection(coll)
    set_limits(ax, limits, factor)
    return coll


def draw_outlines(ax, run, factor):
    outlines = run["specimen"]["outlines"] if run["specimen"] else []
    if outlines:
        ax.add_collection(PolyCollection([o * factor for o in outlines], facecolors="none", edgecolors="0.1",
                                         linewidths=0.8))


def touching_pairs(xy, r, tol=1e-3):
    """Pairs (i, j) whose discs touch or nearly (gap ≤ tol · the smaller radius): the bonds of a bonded
    specimen, found on a grid of cells one largest diameter wide."""
    h = 2 * r.max() * (1 + tol)
    cells = {}
    keys = np.floor((xy - xy.min(axis=0)) / h).astype(np.int64)
    for i, (a, b) in enumerate(keys):
        cells.setdefault((a, b), []).append(i)
    pairs = []
    for (a, b), members in cells.items():
        near = [j for da in (-1, 0, 1) for db in (-1, 0, 1) for j in cells.get((a + da, b + db), ())]
        near = np.asarray(near)
        for i in members:
            cand = near[near > i]
            if len(cand) == 0:
                continue
            gap = np.linalg.norm(xy[cand] - xy[i], axis=1) - r[cand] - r[i]
            for j in cand[gap <= tol * np.minimum(r[cand], r[i])]:
                pairs.append((i, j))
    return np.asarray(pairs, dtype=np.int64).reshape(-1, 2)


def draw_phases(ax, run, xy, r, phase, limits, factor):
    names = run["specimen"]["phase_names"]
    cmap = plt.get_cmap("tab10")
    draw_discs(ax, xy, r, limits, factor, facecolors=cmap(phase % 10))
    draw_outlines(ax, run, factor)
    handles = [Patch(facecolor=cmap(p % 10), edgecolor="0.2", label=phase_name(names, p)) for p in np.unique(phase)]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small", title="phase")
    ax.set_title("phase", fontsize="medium")


def draw_forces(fig, ax, xy, r, fmag, limits, factor):
    ffac, funit = si_scale(fmag, "N")
    # Each particle's resultant (its contacts, gravity and damping: the out-of-balance force PFC users know), not a
    # contact force. Heavy-tailed: the colour scale is clipped at the 99.5th percentile so that more than a few hot
    # spots show.
    vmax = np.percentile(fmag, 99.5) * ffac if fmag.max() > 0 else 1.0
    coll = draw_discs(ax, xy, r, limits, factor, cmap="inferno")
    coll.set_array(fmag * ffac)
    coll.set_clim(0, vmax)
    fig.colorbar(coll, ax=ax, label=f"|F| [{funit}]", shrink=0.8,
                 extend="max" if fmag.max() * ffac > vmax else "neither")
    ax.set_title("out-of-balance force magnitude (each particle's resultant)", fontsize="medium")


def draw_bond_phases(ax, xy, r, phase, names, factor):
    """Tang Fig. 4.13: the bonds coloured by the phases they join (2D, several phases)."""
    pairs = touching_pairs(xy, r)
    if len(pairs) == 0:
        return
    lo, hi = np.minimum(phase[pairs[:, 0]], phase[pairs[:, 1]]), np.maximum(phase[pairs[:, 0]], phase[pairs[:, 1]])
    cmap = plt.get_cmap("Dark2")
    handles = []
    for k, (a, b) in enumerate(sorted(set(zip(lo.tolist(), hi.tolist())))):
        sel = (lo == a) & (hi == b)
        segs = np.stack([xy[pairs[sel, 0]], xy[pairs[sel, 1]]], axis=1) * factor
        ax.add_collection(LineCollection(segs, colors=[cmap(k % 8)], linewidths=0.6))
        label = f"{phase_name(names, a)}-{phase_name(names, b)} ({int(sel.sum())})"
        handles.append(Line2D([], [], color=cmap(k % 8), lw=1.5, label=label))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small", title="bonds")
    ax.set_title("bonds by phase pair", fontsize="medium")


def plot_specimen(run, stem, out_dir):
    if run["specimen"] is None or len(run["specimen"]["radius"]) == 0:
        return []
    kind = "specimen" if run["dimension"] == 2 else "slice"
    xy, r, phase, fmag, (ax0, ax1), limits, when = section(run)
    if fmag is not None and not (fmag > 0).any():
        fmag = None  # a specimen at rest (e.g. generated): nothing to colour by force
    # 2D specimens of several phases (mortar, aggregate …) also show their bonds by phase pair, as Tang's Fig.
    # 4.13; up to 50 000 discs (the neighbour search is plain Python).
    bond_panel = run["dimension"] == 2 and len(np.unique(phase)) > 1 and len(r) <= 50000
    panels = 1 + (fmag is not None) + bond_panel
    fig, axes = plt.subplots(1, panels, figsize=(6.5 * panels, 6), squeeze=False, constrained_layout=True)
    axes = axes.ravel()
    fig.suptitle(f"{stem}: {when}", fontsize="medium")
    if len(r) == 0:
        for ax in axes:
            ax.text(0.5, 0.5, "no particle cut by the section", ha="center", transform=ax.transAxes)
        return [save(fig, out_dir, stem, kind)]
    factor, lunit = si_scale(np.abs(limits).ravel(), "m")
    for ax in axes:
        ax.set_xlabel(f"{ax0} [{lunit}]")
        ax.set_ylabel(f"{ax1} [{lunit}]")
    draw_phases(axes[0], run, xy, r, phase, limits, factor)
    if fmag is not None:
        draw_forces(fig, axes[1], xy, r, fmag, limits, factor)
    if bond_panel:
        set_limits(axes[-1], limits, factor)
        draw_bond_phases(axes[-1], xy, r, phase, run["specimen"]["phase_names"], factor)
    # More pixels for large specimens, so single discs stay visible when zooming in.
    return [save(fig, out_dir, stem, kind, dpi=200 if len(r) > 10000 else 120)]


def crack_segments(c, sel, factor):
    """The 2D segments of the cracks selected by sel (plot_cracks says how they are drawn)."""
    p, n = c["position"][sel], c["normal"][sel]
    t = np.stack([-n[:, 1], n[:, 0]], axis=1) * (0.5 * c["size"][sel])[:, None]
    return np.stack([p - t, p + t], axis=1) * factor


def plot_cracks_at_peak(run, stem, out_dir):
    """A three-point bending run ([bending]): the cracks up to the peak load (Tang Figs. 7.7-7.8, first panel)."""
    h = run["history"]
    if "bending.load" not in h or "time" not in h or len(h["time"]["data"]) == 0:
        return []
    peak = int(np.argmax(h["bending.load"]["data"]))
    return plot_cracks(run, stem, out_dir, until=float(h["time"]["data"][peak]))


def plot_cracks(run, stem, out_dir, until=None):
    """2D: every crack as a segment across its bond (perpendicular to the normal, as long as the smaller
    diameter), over the specimen; colour = mode, line style = phase pair; first yields of softening bonds
    dotted. 3D: crack positions projected on the x-z plane. `until` [s]: only those logged by then
    (<stem>_cracks_peak.png), drawn over the last frame."""
    c = run["cracks"]
    if c is None or run["specimen"] is None:
        return []
    if until is not None:
        c = {k: v[c["time"] <= until] for k, v in c.items()}
    xy, r, _, _, (ax0, ax1), limits, when = section(run)
    # The figure takes the specimen's shape (a beam is four times as long as deep), with room for the legend.
    aspect = (limits[1][1] - limits[0][1]) / max(limits[1][0] - limits[0][0], 1e-300)
    fig, ax = plt.subplots(figsize=(10, min(8, max(3, 6.5 * aspect + 1.2))) if aspect < 0.6 else (7, 6),
                           constrained_layout=True)
    factor, lunit = si_scale(np.abs(limits).ravel(), "m")
    if run["dimension"] == 2:
        draw_discs(ax, xy, r, limits, factor, facecolors="0.92")
    else:
        set_limits(ax, limits, factor)
    ax.set_xlabel(f"{ax0} [{lunit}]")
    ax.set_ylabel(f"{ax1} [{lunit}]")
    draw_outlines(ax, run, factor)
    names = run["specimen"]["phase_names"]
    lo, hi = np.minimum(c["phase_a"], c["phase_b"]), np.maximum(c["phase_a"], c["phase_b"])
    pairs = sorted(set(zip(lo.tolist(), hi.tolist())))
    handles = []
    for kind, width, dash in ((1, 0.6, ":"), (0, 1.2, None)):
        for mode, colour in MODE_COLOURS.items():
            for k, (a, b) in enumerate(pairs):
                sel = (c["kind"] == kind) & (c["mode"] == mode) & (lo == a) & (hi == b)
                if not sel.any():
                    continue
                label = f"{'yield' if kind else 'break'}, {'tensile' if mode == 1 else 'shear'}"
                if len(pairs) > 1:
                    label += f", {phase_name(names, a)}-{phase_name(names, b)}"
                label += f" ({int(sel.sum())})"
                if run["dimension"] == 2:
                    style = dash or PAIR_STYLES[k % len(PAIR_STYLES)]
                    ax.add_collection(LineCollection(crack_segments(c, sel, factor), colors=colour, linewidths=width,
                                                     linestyles=style))
                    handles.append(Line2D([], [], color=colour, lw=width, ls=style, label=label))
                else:
                    p = c["position"][sel]
                    handles.append(ax.scatter(p[:, 0] * factor, p[:, 2] * factor, s=4 if kind == 0 else 1, c=colour,
                                              marker="o" if k == 0 else "x", label=label))
    if until is not None:
        tf, tu = si_scale([until], "s")
        when = f"cracks to the peak load (t = {until * tf:.4g} {tu}), over the last frame"
    if run["dimension"] == 3:
        when += " (cracks: all, projected on the x-z plane)"
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small", title="cracks")
    else:
        ax.text(0.5, 0.5, "no bond has broken", ha="center", transform=ax.transAxes)
    breaks = int((c["kind"] == 0).sum())
    ax.set_title(f"{stem}: {breaks} broken bonds; {when}", fontsize="medium")
    return [save(fig, out_dir, stem, "cracks" if until is None else "cracks_peak", dpi=200 if len(r) > 10000 else 120)]


# A facet counts as cracked in the crack picture from this damage on: it then carries at most half the stress its
# strain would give intact (Květoň (3.11)). The engine logs a break later, at 0.99 (RigidCellSystem::kCracked).
CRACK_DAMAGE = 0.5
# Damage from CRACK_DAMAGE (orange) to 1 (black), away from the colour map's white end, which the page would hide.
DAMAGE_COLOURS = ListedColormap(plt.get_cmap("inferno_r")(np.linspace(0.3, 1.0, 256)))


def polygon_edges(start, corner):
    """Each edge of polygons over points (polygon k: points corner[start[k]:start[k+1]]): first and second point
    index and the polygon's index, in polygon order."""
    count = np.diff(start)
    polygon = np.repeat(np.arange(len(count)), count)
    following = np.arange(len(corner)) + 1
    following[start[1:] - 1] = start[:-1]  # each polygon's last point closes it with its first
    return corner, corner[following], polygon


def mid_section(points, start, corner, z):
    """Where polygons cross the plane at height z: their segments in x-y [M, 2, 2] and which polygon each is. An
    edge crosses when its ends lie on both sides (a corner on the plane counts as above), so a closed polygon crosses
    an even number of times, a convex one (a Voronoi facet) twice."""
    a, b, polygon = polygon_edges(start, corner)
    za, zb = points[a, 2] - z, points[b, 2] - z
    cross = (za < 0) != (zb < 0)
    t = (za[cross] / (za[cross] - zb[cross]))[:, None]
    p = points[a[cross], :2] + t * (points[b[cross], :2] - points[a[cross], :2])
    return p.reshape(-1, 2, 2), polygon[cross][::2]


def cell_picture(run):
    """What the crack picture of cells draws in its plane: (the cells' outlines as segments, the facets' segments
    and each one's facet index, a description of the plane). 2D: the cells' outlines and the facets themselves. 3D:
    their section by the plane at mid-thickness (z): the shapes are outlines extruded along z, so the section shows
    the outline as a 2D run does, and a crack through the thickness crosses it as a line."""
    c = run["cells"]
    points = c["corner"]
    if run["dimension"] == 2:
        a, b, _ = polygon_edges(c["face_start"], c["face_corner"])
        outlines = np.stack([points[a], points[b]], axis=1)
        ends = c["facet_corner"][c["facet_start"][:-1, None] + np.arange(2)]
        return outlines, points[ends], np.arange(len(ends)), "the cells"
    z = 0.5 * (points[:, 2].min() + points[:, 2].max())
    outlines, _ = mid_section(points, c["face_start"], c["face_corner"], z)
    facets, which = mid_section(points, c["facet_start"], c["facet_corner"], z)
    factor, unit = si_scale([z], "m")
    return outlines, facets, which, f"the cells' section at mid-thickness, z = {z * factor:.4g} {unit}"


def draw_cracked_facets(ax, c, facets, which, frame, factor, width):
    """The facets of the picture (`facets`, each facet `which`) whose damage in the frame reached CRACK_DAMAGE,
    coloured by it, the most damaged on top. Returns which of the picture's facets those are."""
    contact = which < c["contacts"]
    damage = np.zeros(len(which))
    damage[contact] = frame["damage"][which[contact]]
    cracked = damage >= CRACK_DAMAGE
    order = np.argsort(damage[cracked])
    lines = LineCollection(facets[cracked][order] * factor, cmap=DAMAGE_COLOURS, norm=Normalize(CRACK_DAMAGE, 1.0),
                           linewidths=width)
    lines.set_array(damage[cracked][order])
    ax.add_collection(lines)
    return cracked


def frame_axes(ax, lo, hi, factor, unit):
    """The picture plane from lo to hi (x-y, in metres, shown in `unit` by `factor`), to scale."""
    ax.set_xlim(lo[0] * factor, hi[0] * factor)
    ax.set_ylim(lo[1] * factor, hi[1] * factor)
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{unit}]")
    ax.set_ylabel(f"y [{unit}]")


def plot_cells(run, stem, out_dir):
    """Rigid cells: the crack pattern, as the contact facets whose damage reached CRACK_DAMAGE coloured by their
    damage over the cells' outlines (faint), in the last frame and, beside it, the last frame by the peak of the load
    the scene plots."""
    c = run.get("cells")
    if c is None:
        return []
    outlines, facets, which, plane = cell_picture(run)
    lo, hi = c["corner"][:, :2].min(axis=0), c["corner"][:, :2].max(axis=0)
    factor, lunit = si_scale(np.abs([lo, hi]).ravel(), "m")
    panels = len(c["frames"])
    # Panels of the specimen's shape, some 6 inches tall and wide enough for their titles.
    width = np.clip(5.5 * (hi[0] - lo[0]) / max(hi[1] - lo[1], 1e-300), 3.0, 7.5)
    fig, axes = plt.subplots(1, panels, figsize=(1.3 + width * panels, 6.8), squeeze=False, layout="compressed")
    norm = Normalize(CRACK_DAMAGE, 1.0)
    for ax, frame in zip(axes.ravel(), c["frames"]):
        ax.add_collection(LineCollection(outlines * factor, colors="0.8", linewidths=0.4))
        cracked = draw_cracked_facets(ax, c, facets, which, frame, factor, 1.6)
        frame_axes(ax, lo, hi, factor, lunit)
        tf, tu = si_scale([frame["time"]], "s")
        when = (f"t = {frame['time'] * tf:.4g} {tu}, step {frame['step']} "
                f"(frame {frame['index'] + 1} of {frame['count']})")
        if frame["peak"] is not None:
            p = frame["peak"]
            pf, pu = si_scale([p["value"]], p["unit"])
            when = f"by the peak of {p['series']} ({p['value'] * pf:.4g} {pu}):\n" + when
        counts = f"{int((frame['damage'] >= CRACK_DAMAGE).sum())} of {c['contacts']} facets with D ≥ {CRACK_DAMAGE:g}"
        if run["dimension"] == 3:
            counts += f", {int(cracked.sum())} cut by the section"
        ax.set_title(f"{when}\n{counts}", fontsize="small")
    fig.colorbar(ScalarMappable(norm=norm, cmap=DAMAGE_COLOURS), ax=axes.ravel().tolist(), shrink=0.8,
                 label="facet damage D")
    fig.suptitle(f"{stem}: crack pattern, facets with D ≥ {CRACK_DAMAGE:g}\nover {plane}", fontsize="medium")
    return [save(fig, out_dir, stem, "cells", dpi=150)]
