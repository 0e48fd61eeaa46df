"""Pictures of a mesocrack specimen, for app/report.py: the bodies (particles, or rigid cells as their polygons) by
phase, by out-of-balance force, the force chains of their contacts (with /contacts) and their bonds by phase pair,
and the crack log over them; a 3D specimen is shown by its section at mid-depth. Rigid cells: the crack pattern of
their damaged facets."""
import matplotlib

matplotlib.use("Agg")  # headless: no display on compute nodes or CI
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.cm import ScalarMappable  # noqa: E402
from matplotlib.collections import EllipseCollection, LineCollection, PolyCollection  # noqa: E402
from matplotlib.colors import ListedColormap, Normalize, to_rgba  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from report_plots import save, si_scale  # noqa: E402

MODE_COLOURS = {1: "tab:blue", 2: "tab:red"}
# Line styles of the cracks, one per phase pair.
PAIR_STYLES = ["-", "--", "-.", (0, (5, 1, 1, 1, 1, 1))]


def phase_name(names, p):
    return names[p] if 0 <= p < len(names) and names[p] else f"phase {p}"


def section(run):
    """What a picture of the specimen's bodies draws in its plane, as a dict: "rows" (the specimen's rows drawn), "x"
    (every body's position [N, D], the frame's when it has one), "plane" (the picture's axes: indices into x, and
    "names"), "limits", "when" (a description), and per item drawn its "phase" and "fmag" (|F| of the frame's
    out-of-balance force, or None). Particles are circles, "xy" [M, 2] and "r": 2D all discs; 3D the spheres cut by
    y = centre, in x-z. Rigid cells are polygons, "polygons" and "polygon_row" (the row of each; cell_polygons)."""
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
    cells = run.get("cells")
    if cells is not None and "face_cell" in cells:
        view = cell_polygons(run)
        view.update(x=x, when=when + view["when"], phase=phase[view["polygon_row"]],
                    fmag=fmag[view["polygon_row"]] if fmag is not None else None)
        return view
    # Limits from the whole specimen, so a 3D section shows where it lies in the specimen.
    plane = [0, 1] if run["dimension"] == 2 else [0, 2]
    limits = ((x[:, plane] - r[:, None]).min(axis=0), (x[:, plane] + r[:, None]).max(axis=0))
    if run["dimension"] == 2:
        return {"rows": np.arange(len(r)), "x": x, "xy": x, "r": r, "phase": phase, "fmag": fmag, "plane": plane,
                "names": ("x", "y"), "limits": limits, "when": when}
    lo, hi = (x[:, 1] - r).min(), (x[:, 1] + r).max()
    yc = 0.5 * (lo + hi)
    d = np.abs(x[:, 1] - yc)
    cut = d < r
    factor, unit = si_scale([yc], "m")
    return {"rows": np.flatnonzero(cut), "x": x, "xy": x[cut][:, plane], "r": np.sqrt(r[cut] ** 2 - d[cut] ** 2),
            "phase": phase[cut], "fmag": fmag[cut] if fmag is not None else None, "plane": plane,
            "names": ("x", "z"), "limits": limits, "when": when + f", section y = {yc * factor:.4g} {unit}"}


def cell_points(run):
    """The cells' corners where the frame moved them (/frames/cell_corner), else as built."""
    c, frame = run["cells"], run["frame"]
    moved = frame.get("cell_corner") if frame else None
    return moved if moved is not None and moved.shape == c["corner"].shape else c["corner"]


def cell_polygons(run):
    """The rigid cells as polygons in the picture plane x-y, the plane of cell_picture: "polygons" (each [k, 2]),
    "polygon_row" (its cell's row of the specimen), "rows" (the cells drawn), "plane", "names", "limits" and what
    "when" adds. 2D: each cell's outline. 3D: each cell's section at mid-thickness, its points in order round their
    mean (a Voronoi cell, clipped by the specimen's outline extruded along z, is convex)."""
    c = run["cells"]
    points = cell_points(run)
    lo, hi = points[:, :2].min(axis=0), points[:, :2].max(axis=0)
    view = {"plane": [0, 1], "names": ("x", "y"), "limits": (lo, hi), "when": ""}
    start, corner, cell = c["face_start"], c["face_corner"], c["face_cell"]
    if run["dimension"] == 2:
        view["polygons"] = [points[corner[a:b], :2] for a, b in zip(start[:-1], start[1:])]
        view["polygon_row"] = cell
    else:
        z = 0.5 * (points[:, 2].min() + points[:, 2].max())
        segments, face = mid_section(points, start, corner, z)
        owner = cell[face]
        order = np.argsort(owner, kind="stable")
        rows, first = np.unique(owner[order], return_index=True)
        view["polygons"] = []
        for ends in np.split(segments[order].reshape(-1, 2, 2), first[1:]):
            p = ends.reshape(-1, 2)
            turn = np.arctan2(*(p - p.mean(axis=0)).T[::-1])
            view["polygons"].append(p[np.argsort(turn)])
        view["polygon_row"] = rows
        factor, unit = si_scale([z], "m")
        view["when"] = f", section z = {z * factor:.4g} {unit}"
    view["rows"] = np.unique(view["polygon_row"])
    view["xy"], view["r"] = None, run["specimen"]["radius"][view["rows"]]
    return view


def set_limits(ax, limits, factor):
    ax.set_xlim(limits[0][0] * factor, limits[1][0] * factor)
    ax.set_ylim(limits[0][1] * factor, limits[1][1] * factor)
    ax.set_aspect("equal")


def draw_discs(ax, xy, r, limits, factor, edgecolors="0.2", **style):
    # One EllipseCollection in data units: fast for 50k discs, unlike one Circle patch each.
    coll = EllipseCollection(2 * r * factor, 2 * r * factor, np.zeros_like(r), units="xy",
                             offsets=xy * factor, offset_transform=ax.transData,
                             linewidths=0.3 if len(r) <= 2000 else 0, edgecolors=edgecolors, **style)
    ax.add_collection(coll)
    set_limits(ax, limits, factor)
    return coll


def draw_bodies(ax, view, factor, edgecolors="0.2", **style):
    """The bodies of a view (section): particles as discs, rigid cells as their polygons. Returns the collection,
    one item per entry of view["phase"]."""
    if "polygons" not in view:
        return draw_discs(ax, view["xy"], view["r"], view["limits"], factor, edgecolors=edgecolors, **style)
    coll = PolyCollection([p * factor for p in view["polygons"]], edgecolors=edgecolors,
                          linewidths=0.3 if len(view["polygons"]) <= 5000 else 0, **style)
    ax.add_collection(coll)
    set_limits(ax, view["limits"], factor)
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


def draw_phases(ax, run, view, factor):
    names = run["specimen"]["phase_names"]
    cmap = plt.get_cmap("tab10")
    draw_bodies(ax, view, factor, facecolors=cmap(view["phase"] % 10))
    draw_outlines(ax, run, factor)
    handles = [Patch(facecolor=cmap(p % 10), edgecolor="0.2", label=phase_name(names, p))
               for p in np.unique(view["phase"])]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small", title="phase")
    ax.set_title("phase", fontsize="medium")


def draw_forces(fig, ax, view, factor):
    fmag = view["fmag"]
    ffac, funit = si_scale(fmag, "N")
    # Each body's resultant (its contacts, gravity and damping: the out-of-balance force PFC users know), not a
    # contact force. Heavy-tailed: the colour scale is clipped at the 99.5th percentile so that more than a few hot
    # spots show.
    vmax = np.percentile(fmag, 99.5) * ffac if fmag.max() > 0 else 1.0
    coll = draw_bodies(ax, view, factor, cmap="inferno")
    coll.set_array(fmag * ffac)
    coll.set_clim(0, vmax)
    fig.colorbar(coll, ax=ax, label=f"|F| [{funit}]", shrink=0.8,
                 extend="max" if fmag.max() * ffac > vmax else "neither")
    body = "cell" if "polygons" in view else "particle"
    ax.set_title(f"out-of-balance force magnitude (each {body}'s resultant)", fontsize="medium")


# Force chains: compression dark, tension red; the largest |normal force| drawn CHAIN_WIDTH points wide.
CHAIN_COLOURS = {"compression": "0.1", "tension": "tab:red"}
CHAIN_WIDTH = 3.0


def chain_segments(run, view):
    """The frame's contacts (/contacts) whose two bodies the view draws: their lines from A's centre to B's
    (x_A + branch) in the picture plane [M, 2, 2], in metres, and their normal forces (positive in compression)."""
    con, x, plane = run["frame"]["contacts"], view["x"], view["plane"]
    a, b = con["pair"][:, 0], con["pair"][:, 1]
    drawn = np.zeros(len(x) + 1, bool)  # the last entry stands for rows outside the specimen
    drawn[view["rows"]] = True
    outside = lambda q: np.where((q >= 0) & (q < len(x)), q, len(x))
    keep = drawn[outside(a)] & drawn[outside(b)]
    start = x[a[keep]]
    segments = np.stack([start[:, plane], (start + con["branch"][keep])[:, plane]], axis=1)
    return segments, con["normal_force"][keep]


def draw_chains(run, ax, view, factor):
    """Force chains (Cundall & Strack's picture of a granular assembly): each contact of the frame a line between the
    centres of its bodies, as wide as its |normal force| against the largest, compression and tension apart."""
    draw_bodies(ax, view, factor, facecolors="0.95", edgecolors="0.8")
    segments, fn = chain_segments(run, view)
    largest = float(np.abs(fn).max()) if len(fn) else 0.0
    widths = CHAIN_WIDTH * np.abs(fn) / largest if largest > 0 else np.zeros(len(fn))
    order = np.argsort(np.abs(fn), kind="stable")  # the largest on top
    tension = fn < 0
    colours = np.where(tension[order, None], to_rgba(CHAIN_COLOURS["tension"]), to_rgba(CHAIN_COLOURS["compression"]))
    ax.add_collection(LineCollection(segments[order] * factor, colors=colours, linewidths=widths[order],
                                     capstyle="round"))
    set_limits(ax, view["limits"], factor)
    ff, fu = si_scale([largest], "N")
    per = "\n(per metre of thickness)" if run["dimension"] == 2 else ""
    handles = [Line2D([], [], color=CHAIN_COLOURS["compression"], lw=2, label=f"compression ({int((~tension).sum())})"),
               Line2D([], [], color=CHAIN_COLOURS["tension"], lw=2, label=f"tension ({int(tension.sum())})")]
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small", title_fontsize="small",
              title=f"line width ∝ |normal force|,\nlargest {largest * ff:.4g} {fu}{per}")
    where = ", both bodies in the section" if run["dimension"] == 3 else ""
    ax.set_title(f"force chains: contact normal forces{where}", fontsize="medium")


def phase_pairs(run, view, factor):
    """What bonds the view's bodies by phase pair: (segments [M, 2, 2], lower and higher phase of each, what they
    are), or None. Particles (2D): the lines between touching discs' centres. Cells: their contact facets."""
    phase = run["specimen"]["phase"]
    if "polygons" not in view:
        pairs = touching_pairs(view["xy"], view["r"])
        if len(pairs) == 0:
            return None
        segments, what = view["xy"][pairs] * factor, "bonds"
        a, b = view["phase"][pairs[:, 0]], view["phase"][pairs[:, 1]]
    else:
        c = run["cells"]
        if "facet_a" not in c:
            return None
        _, facets, which, _ = cell_picture(run, cell_points(run))
        contact = which < c["contacts"]
        segments, which = facets[contact] * factor, which[contact]
        a, b, what = phase[c["facet_a"][which]], phase[c["facet_b"][which]], "contact facets"
    return segments, np.minimum(a, b), np.maximum(a, b), what


def draw_bond_phases(ax, run, view, factor):
    """Tang Fig. 4.13: the bonds coloured by the phases they join (several phases)."""
    found = phase_pairs(run, view, factor)
    if found is None:
        return
    segments, lo, hi, what = found
    names = run["specimen"]["phase_names"]
    cmap = plt.get_cmap("Dark2")
    handles = []
    for k, (a, b) in enumerate(sorted(set(zip(lo.tolist(), hi.tolist())))):
        sel = (lo == a) & (hi == b)
        ax.add_collection(LineCollection(segments[sel], colors=[cmap(k % 8)], linewidths=0.6))
        label = f"{phase_name(names, a)}-{phase_name(names, b)} ({int(sel.sum())})"
        handles.append(Line2D([], [], color=cmap(k % 8), lw=1.5, label=label))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small", title=what)
    ax.set_title(f"{what} by phase pair", fontsize="medium")


def plot_specimen(run, stem, out_dir):
    if run["specimen"] is None or len(run["specimen"]["radius"]) == 0:
        return []
    kind = "specimen" if run["dimension"] == 2 else "slice"
    view = section(run)
    if view["fmag"] is not None and not (view["fmag"] > 0).any():
        view["fmag"] = None  # a specimen at rest (e.g. generated): nothing to colour by force
    cells = "polygons" in view
    chains = run["frame"] is not None and run["frame"].get("contacts") is not None
    # Specimens of several phases (mortar, aggregate …) also show their bonds by phase pair, as Tang's Fig. 4.13:
    # particles in 2D, up to 50 000 discs (the neighbour search is plain Python); cells by their contact facets.
    bond_panel = len(np.unique(view["phase"])) > 1 and (cells or (run["dimension"] == 2 and len(view["r"]) <= 50000))
    panels = 1 + (view["fmag"] is not None) + chains + bond_panel
    fig, axes = plt.subplots(1, panels, figsize=(6.5 * panels, 6), squeeze=False, constrained_layout=True)
    axes = axes.ravel()
    fig.suptitle(f"{stem}: {view['when']}", fontsize="medium")
    if len(view["phase"]) == 0:
        for ax in axes:
            ax.text(0.5, 0.5, "no body cut by the section", ha="center", transform=ax.transAxes)
        return [save(fig, out_dir, stem, kind)]
    factor, lunit = si_scale(np.abs(view["limits"]).ravel(), "m")
    for ax in axes:
        ax.set_xlabel(f"{view['names'][0]} [{lunit}]")
        ax.set_ylabel(f"{view['names'][1]} [{lunit}]")
    draw_phases(axes[0], run, view, factor)
    if view["fmag"] is not None:
        draw_forces(fig, axes[1], view, factor)
    if chains:
        draw_chains(run, axes[1 + (view["fmag"] is not None)], view, factor)
    if bond_panel:
        set_limits(axes[-1], view["limits"], factor)
        draw_bond_phases(axes[-1], run, view, factor)
    # More pixels for large specimens, so single discs stay visible when zooming in.
    return [save(fig, out_dir, stem, kind, dpi=200 if len(view["phase"]) > 10000 else 120)]


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


def logged_facets(cells, c, sel):
    """The contact facets joining the pairs of cells that the crack log's rows `sel` name (facet_a, facet_b)."""
    P = cells["contacts"]
    fa, fb = cells["facet_a"][:P], cells["facet_b"][:P]
    n = int(max(fa.max(initial=0), fb.max(initial=0), c["row_a"].max(initial=0), c["row_b"].max(initial=0))) + 1
    keys = np.minimum(fa, fb) * n + np.maximum(fa, fb)
    order = np.argsort(keys)
    a, b = c["row_a"][sel], c["row_b"][sel]
    known = (a >= 0) & (b >= 0)
    wanted = np.minimum(a, b)[known] * n + np.maximum(a, b)[known]
    if P == 0 or len(wanted) == 0:
        return np.zeros(0, np.int64)
    at = order[np.minimum(np.searchsorted(keys, wanted, sorter=order), P - 1)]
    return at[keys[at] == wanted]


def plot_cracks(run, stem, out_dir, until=None):
    """2D particles: every crack as a segment across its bond (perpendicular to the normal, as long as the smaller
    diameter), over the specimen; colour = mode, line style = phase pair; first yields of softening bonds
    dotted. 3D particles: crack positions projected on the x-z plane. Rigid cells: the facet between the two cells
    each crack names, over the cells (3D: the facets cut by the section at mid-thickness). `until` [s]: only those
    logged by then (<stem>_cracks_peak.png), drawn over the last frame."""
    c = run["cracks"]
    if c is None or run["specimen"] is None:
        return []
    if until is not None:
        c = {k: v[c["time"] <= until] for k, v in c.items()}
    view = section(run)
    limits, (ax0, ax1) = view["limits"], view["names"]
    cells = run["cells"] if "polygons" in view and "facet_a" in run["cells"] else None
    # The figure takes the specimen's shape (a beam is four times as long as deep), with room for the legend.
    aspect = (limits[1][1] - limits[0][1]) / max(limits[1][0] - limits[0][0], 1e-300)
    fig, ax = plt.subplots(figsize=(10, min(8, max(3, 6.5 * aspect + 1.2))) if aspect < 0.6 else (7, 6),
                           constrained_layout=True)
    factor, lunit = si_scale(np.abs(limits).ravel(), "m")
    if "polygons" in view:
        draw_bodies(ax, view, factor, facecolors="0.94", edgecolors="0.7")
        _, facets, which, _ = cell_picture(run, cell_points(run))
    elif run["dimension"] == 2:
        draw_bodies(ax, view, factor, facecolors="0.92")
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
                style = dash or PAIR_STYLES[k % len(PAIR_STYLES)]
                if cells is not None:
                    segments = facets[np.isin(which, logged_facets(cells, c, sel))] * factor
                elif run["dimension"] == 2:
                    segments = crack_segments(c, sel, factor)
                else:
                    p = c["position"][sel]
                    handles.append(ax.scatter(p[:, 0] * factor, p[:, 2] * factor, s=4 if kind == 0 else 1, c=colour,
                                              marker="o" if k == 0 else "x", label=label))
                    continue
                ax.add_collection(LineCollection(segments, colors=colour, linewidths=width * (1.5 if cells else 1),
                                                 linestyles=style))
                handles.append(Line2D([], [], color=colour, lw=width, ls=style, label=label))
    when = view["when"]
    if until is not None:
        tf, tu = si_scale([until], "s")
        when = f"cracks to the peak load (t = {until * tf:.4g} {tu}), over the last frame"
    if cells is not None and run["dimension"] == 3:
        when += " (cracks: the facets they name cut by the section)"
    elif run["dimension"] == 3:
        when += " (cracks: all, projected on the x-z plane)"
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize="small", title="cracks")
    else:
        ax.text(0.5, 0.5, "no bond has broken", ha="center", transform=ax.transAxes)
    breaks = int((c["kind"] == 0).sum())
    ax.set_title(f"{stem}: {breaks} broken {'facets' if cells is not None else 'bonds'}; {when}", fontsize="medium")
    return [save(fig, out_dir, stem, "cracks" if until is None else "cracks_peak",
                 dpi=200 if len(view["phase"]) > 10000 else 120)]


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


def cell_picture(run, points=None):
    """What the crack picture of cells draws in its plane: (the cells' outlines as segments, the facets' segments
    and each one's facet index, a description of the plane). 2D: the cells' outlines and the facets themselves. 3D:
    their section by the plane at mid-thickness (z): the shapes are outlines extruded along z, so the section shows
    the outline as a 2D run does, and a crack through the thickness crosses it as a line. `points`: the corners to
    draw them at (default: as built)."""
    c = run["cells"]
    points = c["corner"] if points is None else points
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
    if c is None or not c["frames"]:
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
