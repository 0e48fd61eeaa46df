#!/usr/bin/python3
"""Check of app/report.py on small synthetic mesocrack-1 files (2D/3D, with and without frames,
with an xy_plots attribute) plus the error cases. Run: /usr/bin/python3 tests/report_plots.py
Set REPORT_PLOTS_KEEP=DIR to keep the files and PNGs in DIR for a look."""
import contextlib
import hashlib
import io
import os
import subprocess
import sys
import tempfile
import zlib

import h5py
import numpy as np
from matplotlib.colors import to_rgba

APP = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "app")
REPORT = os.path.join(APP, "report.py")
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
results = []


def check(name, ok, detail=""):
    results.append((name, bool(ok), detail))


def fixed(s):
    """Fixed-length string, as the engine writes attributes (h5py would write variable-length)."""
    return np.bytes_(s.encode("utf-8"))


def series(g, name, data, unit, label=None):
    d = g.create_dataset(name, data=np.asarray(data, dtype=float))
    d.attrs.create("unit", fixed(unit))
    if label:
        d.attrs["label"] = label  # variable-length: both kinds must be read


def make_run(path, dim, n, frames=3, history=True, xy=None, seed=1, cracks=0):
    rng = np.random.default_rng(seed)
    with h5py.File(path, "w") as f:
        f.attrs.create("format", fixed("mesocrack-1"))
        f.attrs["dimension"] = np.int64(dim)
        f.attrs.create("scene_file", fixed(f"scenes/synthetic_{dim}d.toml"))
        f.create_dataset("scene", data=fixed("[scene]\nname = 'synthetic'\n"))
        # Particles on a jittered grid inside a 20 mm box.
        side = int(np.ceil(n ** (1 / dim)))
        grid = np.stack(np.meshgrid(*[np.arange(side)] * dim, indexing="ij"), -1).reshape(-1, dim)[:n]
        x = (grid + 0.5 + 0.05 * rng.standard_normal((n, dim))) * (0.02 / side)
        r = (0.02 / side) * rng.uniform(0.35, 0.5, n)
        phase = np.where(grid[:, 0] == 0, 2, rng.uniform(size=n) < 0.3)  # 0 mortar, 1 aggregate, 2 platen
        sp = f.create_group("specimen")
        sp["x"], sp["radius"], sp["phase"] = x, r, phase.astype(np.int32)
        sp["id"] = np.arange(n, dtype=np.int64) + 100
        sp.attrs.create("phase_names", fixed("mortar,aggregate,platen"))
        if cracks:
            # Cracks between random pairs, as the engine logs them (ids, not indices).
            a = rng.integers(0, n, cracks)
            b = (a + 1) % n
            c = f.create_group("cracks")
            nrm = rng.standard_normal((cracks, dim))
            c["position"] = 0.5 * (x[a] + x[b])
            c["normal"] = nrm / np.linalg.norm(nrm, axis=1)[:, None]
            c["mode"] = rng.integers(1, 3, cracks).astype(np.int64)
            c["kind"] = (rng.uniform(size=cracks) < 0.2).astype(np.int64)
            c["phase_a"], c["phase_b"] = phase[a].astype(np.int64), phase[b].astype(np.int64)
            c["id_a"], c["id_b"] = a + 100, b + 100
            c["step"] = np.arange(cracks, dtype=np.int64)
            c["time"] = np.linspace(0, 1e-3, cracks)
        if history:
            h = f.create_group("history")
            S = 300
            t = np.linspace(0, 2.5e-3, S)
            s = t / t[-1]
            series(h, "time", t, "s")
            series(h, "step", np.arange(S) * 10, "-")
            work = 0.8 * s ** 2
            series(h, "energy.boundary_work", work, "J")
            series(h, "energy.kinetic", 0.05 * np.sin(8 * s) ** 2, "J")
            series(h, "energy.strain", 0.6 * s ** 2 - 0.05 * np.sin(8 * s) ** 2, "J")
            series(h, "energy.dissipated_contacts", 0.15 * s ** 2, "J")
            series(h, "energy.dissipated_local", 0.05 * s ** 2, "J")
            series(h, "energy.body_work", 0 * s, "J")
            series(h, "energy.residual", 1e-4 * rng.standard_normal(S).cumsum() / S ** 0.5, "J")
            for c in "xyz"[:dim]:
                series(h, f"wall.top.force_{c}", (2e4 if c == "y" else 50) * s * (1 + 0.01 * rng.standard_normal(S)),
                       "N")
            series(h, "wall.top.stress", 30e6 * s, "Pa")
            series(h, "wall.top.disp_y", -2e-5 * s, "m")
            series(h, "measure.box.stress_xx", 5e6 * s, "Pa")
            series(h, "measure.box.stress_yy", 30e6 * s, "Pa", label="σ_yy")
            series(h, "measure.box.stress_xy", 1e5 * np.sin(5 * s), "Pa")
            series(h, "measure.box.strain_xx", 3e-4 * s, "-")
            series(h, "measure.box.strain_yy", -1e-3 * s, "-")
            series(h, "measure.box.porosity", 0.18 + 0.01 * s, "-")
            series(h, "measure.box.coordination", 4.1 - 0.3 * s, "-")
            series(h, "contacts", np.round(2 * n * (1 - 0.1 * s)), "-")
            series(h, "dt", np.full(S, 2e-8), "s")
            series(h, "axial_strain", 1e-3 * s, "-", label="axial strain")
            series(h, "axial_stress", 30e6 * np.sin(np.pi * s * 0.8), "Pa", label="axial stress")
            if xy:
                h.attrs.create("xy_plots", fixed(xy))
        if frames:
            fr = f.create_group("frames")
            fr["time"] = np.linspace(0, 2.5e-3, frames)
            fr["step"] = np.arange(frames, dtype=np.int64) * 100
            xs = np.stack([x + 1e-5 * k * rng.standard_normal(x.shape) for k in range(frames)]).reshape(frames, -1)
            fr["x"] = xs
            fr["v"] = np.zeros_like(xs)
            fr["force"] = (rng.lognormal(2, 0.8, (frames, n, 1))
                           * rng.standard_normal((frames, n, dim))).reshape(frames, -1)
        f.create_group("checkpoint")


def add_cells(path, dim, shape):
    """Rigid cells as the engine writes them (README, "Output", /specimen/cells), replacing the particles: a grid of
    cubic cells 5 mm wide whose facets across the plane x = middle crack over the frames (the others stay intact)."""
    h = 5e-3
    index = np.arange(np.prod(shape)).reshape(shape)
    square = [(0, 0), (1, 0), (1, 1), (0, 1)]  # counter-clockwise
    offsets = np.array([c + (0,) * (dim - 2) for c in square] + ([c + (1,) for c in square] if dim == 3 else []))
    corner, faces, face_cell, facets, facet_a, facet_b, crossing = [], [], [], [], [], [], []

    def side(cell, axis, upper):
        """Corners of the cell's side normal to axis (its only side in 2D is its outline)."""
        on = np.nonzero(offsets[:, axis] == upper)[0] if dim == 3 else np.arange(4)
        return list(cell * len(offsets) + on)

    for cell, ijk in enumerate(np.ndindex(*shape)):
        corner.extend((np.array(ijk) + offsets) * h)
        for axis in range(dim) if dim == 3 else [0]:
            for upper in (0, 1):
                faces.append(side(cell, axis, upper))
                face_cell.append(cell)
    contacts, surface = [], []
    for ijk in np.ndindex(*shape):
        for axis in range(dim):
            nxt = list(ijk)
            nxt[axis] += 1
            a = index[ijk]
            # A 2D facet is the side's two ends: the corners of the outline with offset 1 along axis.
            ends = [a * 4 + q for q in range(4) if square[q][axis] == 1] if dim == 2 else side(a, axis, 1)
            if nxt[axis] < shape[axis]:
                contacts.append((ends, a, index[tuple(nxt)], axis == 0 and ijk[0] == shape[0] // 2 - 1))
            else:
                surface.append((ends, a, -1, False))
    for ends, a, b, cracks in contacts + surface:
        facets.append(ends), facet_a.append(a), facet_b.append(b), crossing.append(cracks)
    corner = np.array(corner)
    with h5py.File(path, "r+") as f:
        F = f["frames/time"].shape[0]
        sp = f["specimen"]
        for k in ("x", "radius", "phase", "id"):
            del sp[k]
        sp["x"] = np.array([(np.array(ijk) + 0.5) * h for ijk in np.ndindex(*shape)])
        sp["radius"] = np.full(index.size, h / 2)
        sp["phase"] = np.zeros(index.size, np.int32)
        sp["id"] = np.arange(index.size, dtype=np.int64)
        g = sp.create_group("cells")
        g.attrs["contacts"] = np.int64(len(contacts))
        g["corner"] = corner
        for name, polygons in (("facet", facets), ("face", faces)):
            g[f"{name}_start"] = np.concatenate([[0], np.cumsum([len(q) for q in polygons])]).astype(np.int64)
            g[f"{name}_corner"] = np.concatenate(polygons).astype(np.int64)
        g["facet_a"], g["facet_b"] = np.array(facet_a, np.int64), np.array(facet_b, np.int64)
        g["face_cell"] = np.array(face_cell, np.int64)
        fr = f["frames"]
        fr["cell_corner"] = np.tile(corner.ravel(), (F, 1))
        crack = np.array(crossing[:len(contacts)], float)
        fr["damage"] = np.outer(np.linspace(0, 1, F), crack) + 0.3 * (1 - crack)
        for k in ("x", "v", "force"):
            del fr[k]
            fr[k] = np.tile(sp["x"][()].ravel(), (F, 1))


def set_scene(path, text):
    with h5py.File(path, "r+") as f:
        del f["scene"]
        f.create_dataset("scene", data=fixed(text))


def add_cell_cracks(path, kind):
    """A crack log naming each contact facet that add_cells cracks (damage 1 in the last frame), as the engine logs it:
    the two cells' ids (here not their rows), the facet's centroid, mode tensile."""
    with h5py.File(path, "r+") as f:
        D = int(f.attrs["dimension"])
        sp, g = f["specimen"], f["specimen/cells"]
        P = int(g.attrs["contacts"])
        cracked = np.flatnonzero(f["frames/damage"][-1][:P] > 0.9)
        corner, start, ends = g["corner"][()], g["facet_start"][()], g["facet_corner"][()]
        rows = sp["x"].shape[0]
        del sp["id"]
        sp["id"] = 1000 + np.arange(rows, dtype=np.int64)[::-1]
        ids = sp["id"][()]
        n = len(cracked)
        c = f.create_group("cracks")
        c["position"] = np.array([corner[ends[start[k]:start[k + 1]]].mean(axis=0) for k in cracked])
        c["normal"] = np.tile(np.eye(D)[0], (n, 1))
        c["mode"], c["kind"] = np.ones(n, np.int64), np.full(n, kind, np.int64)
        c["phase_a"], c["phase_b"] = np.zeros(n, np.int64), np.zeros(n, np.int64)
        c["id_a"], c["id_b"] = ids[g["facet_a"][()][cracked]], ids[g["facet_b"][()][cracked]]
        c["step"] = np.arange(n, dtype=np.int64)
        c["time"] = np.linspace(0, f["frames/time"][-1], n)
    return cracked


def add_contacts(path, seed=2, frame_count=True):
    """Each frame's contacts as the engine writes them (README, "Output", /contacts): pairs of particles, normal
    forces of both signs (positive in compression) with one largest in magnitude, fewer contacts in later frames, the
    branch x_B - x_A of the frame. Without frame_count, a frame's rows end where the next frame's begin."""
    rng = np.random.default_rng(seed)
    with h5py.File(path, "r+") as f:
        D = int(f.attrs["dimension"])
        X = f["frames/x"][()]
        F, N = X.shape[0], X.shape[1] // D
        tables = {k: [] for k in ("pair", "normal_force", "shear_force", "bonded", "branch")}
        first, count = [], []
        for k in range(F):
            x = X[k].reshape(N, D)
            m = 2 * N - 37 * k
            a = rng.integers(0, N, m)
            b = (a + rng.integers(1, 40, m)) % N
            fn = 1e3 * rng.standard_normal(m) + 300
            fn[rng.integers(m)] = 3 * np.abs(fn).max()
            first.append(sum(len(q) for q in tables["normal_force"]))
            count.append(m)
            tables["pair"].append(np.stack([a, b], axis=1))
            tables["normal_force"].append(fn)
            tables["shear_force"].append(np.abs(0.3 * fn))
            tables["bonded"].append((rng.uniform(size=m) < 0.7).astype(np.int64))
            tables["branch"].append(x[b] - x[a])
        g = f.create_group("contacts")
        units = {"pair": "-", "normal_force": "N", "shear_force": "N", "bonded": "-", "branch": "m"}
        for name, parts in tables.items():
            d = g.create_dataset(name, data=np.concatenate(parts))
            d.attrs.create("unit", fixed(units[name]))
        g["frame_first"] = np.array(first, np.int64)
        if frame_count:
            g["frame_count"] = np.array(count, np.int64)


def last_contacts(path):
    """The last frame's contacts read straight from the file: pair, normal force, branch, and the frame's x [N, D]."""
    with h5py.File(path, "r") as f:
        D = int(f.attrs["dimension"])
        g = f["contacts"]
        a = int(g["frame_first"][-1])
        x = f["frames/x"][-1].reshape(-1, D)
        return g["pair"][a:], g["normal_force"][a:], g["branch"][a:], x


# A Brazilian disc of rigid cells (Květoň §9.4) and one of particles (a packing: the disc inscribed in its box).
BRAZILIAN_CELLS = """[specimen]
kind = "voronoi_cells"
shape = "disc"
centre = ["35 mm", "35 mm"]
radius = "35 mm"
l_min = "2.5 mm"

[[summary]]
name = "peak_load"
of = "group.bottom.reaction_y"
reduce = "max"
"""
BRAZILIAN_PACKING = """[specimen]
kind = "packing"
shape = "disc"
lo = [0, 0]
hi = ["20 mm", 0.02]
radius_min = "1 mm"
radius_ratio = 1.2
"""


def add_disc_load(path, peak):
    """The plates' reaction and approach of a Brazilian disc, its reaction peaking at `peak` [N per metre]."""
    with h5py.File(path, "r+") as f:
        h = f["history"]
        s = np.linspace(0, 1, h["time"].shape[0])
        series(h, "group.bottom.reaction_y", peak * np.sin(0.8 * np.pi * s) / np.sin(0.8 * np.pi * s).max(), "N")
        series(h, "group.top.disp_y", -4e-5 * s, "m")
        h.attrs.create("xy_plots", fixed("group.top.disp_y:group.bottom.reaction_y"))
        return float(np.abs(h["group.bottom.reaction_y"][()]).max())


PULL_SCENE = """[pullout]
frp_phase = "aggregate"
width = "50 mm"
bonded_from = "5 mm"
bonded_to = 0.015
frp_modulus = "195.2 GPa"
frp_thickness = "1.2 mm"
load_levels = ["4 kN", "8 kN", "12 kN", "14 kN"]
"""


def run_report(path, *extra):
    return subprocess.run([sys.executable, REPORT, path, *extra], capture_output=True, text=True, timeout=300)


def digest(path):
    return hashlib.sha256(open(path, "rb").read()).hexdigest()


def check_pngs(case, p, expected):
    """report ran fine, printed exactly the expected paths, and each is a real, non-trivial PNG."""
    check(f"{case}: exit 0", p.returncode == 0, p.stderr.strip())
    printed = p.stdout.split()
    check(f"{case}: printed paths", sorted(map(os.path.basename, printed)) == sorted(expected),
          f"got {printed}, expected {expected}")
    for path in printed:
        ok = os.path.isfile(path) and os.path.getsize(path) > 5000 and open(path, "rb").read(8) == PNG_MAGIC
        check(f"{case}: {os.path.basename(path)} is a PNG > 5 kB", ok,
              f"size {os.path.getsize(path) if os.path.exists(path) else 'missing'}")


def png_description(path):
    """The PNG's Description text chunk, or None: tEXt (Latin-1), or iTXt (UTF-8, maybe compressed), which the
    writer takes for text beyond Latin-1 (π, ř)."""
    data = open(path, "rb").read()
    at = 8
    while at + 8 <= len(data):
        size = int.from_bytes(data[at:at + 4], "big")
        kind, body = data[at + 4:at + 8], data[at + 8:at + 8 + size]
        key, _, value = body.partition(b"\0")
        if key == b"Description" and kind == b"tEXt":
            return value.decode("latin-1")
        if key == b"Description" and kind == b"iTXt":
            compressed, value = value[0], value[2:]
            value = value.split(b"\0", 2)[2]  # after the language tag and the translated keyword
            return (zlib.decompress(value) if compressed else value).decode("utf-8")
        at += 12 + size
    return None


def report_figures(path, out_dir):
    """app/report.py run in this process on the file: its exit status and {kind: figure} of every PNG it wrote (each
    saved as the command saves it, then kept for a look at what it holds)."""
    sys.path.insert(0, APP)
    import report
    import report_fibres
    import report_plots
    import report_pullout
    import report_specimen
    modules = (report_plots, report_specimen, report_pullout, report_fibres)
    real = [m.save for m in modules]
    figures = {}

    def keep(fig, out_dir, stem, kind, dpi=120):
        figures[kind] = fig
        return real[0](fig, out_dir, stem, kind, dpi)

    for m in modules:
        m.save = keep
    try:
        with contextlib.redirect_stdout(io.StringIO()):
            status = report.main([path, "--out-dir", out_dir])
    finally:
        for m, f in zip(modules, real):
            m.save = f
    return status, figures


def legends(fig):
    """The figure's legends, its axes' and its own, each with its window extent and the figure's (pixels)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    found = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None] + list(fig.legends)
    return [(lg, lg.get_window_extent(renderer), fig.bbox) for lg in found]


def check_legends_inside(case, figures, at_least=()):
    """Every legend of every figure lies inside the figure (nothing of it cut off at the edge); the kinds in
    at_least have one."""
    for kind, fig in figures.items():
        found = legends(fig)
        out = [(tuple(np.round(e.extents, 1)), tuple(np.round(b.extents, 1))) for _, e, b in found
               if e.x0 < b.x0 - 1 or e.y0 < b.y0 - 1 or e.x1 > b.x1 + 1 or e.y1 > b.y1 + 1]
        check(f"{case}: {kind}.png's {len(found)} legends lie inside the figure", not out,
              f"legend extents beyond the figure's: {out}")
        if kind in at_least:
            check(f"{case}: {kind}.png has a legend", found)


def collections(fig, kind):
    return [c for ax in fig.axes for c in ax.collections if type(c).__name__ == kind]


def axes_titled(fig, start):
    return [ax for ax in fig.axes if ax.get_title().startswith(start)]


def check_cells_drawn_as_polygons(case, figures, polygons, cracked_ends=None):
    """Rigid cells: the specimen picture draws each cell as its polygon, no disc anywhere; the crack picture draws
    the facets the crack log names (their ends in mm, any order), as lines."""
    kind = "specimen" if "specimen" in figures else "slice"
    fig = figures[kind]
    check(f"{case}: {kind}.png draws no disc", not collections(fig, "EllipseCollection"))
    drawn = [len(c.get_paths()) for c in fig.axes[0].collections if type(c).__name__ == "PolyCollection"]
    check(f"{case}: {kind}.png's phase panel draws the {polygons} cell polygons", drawn == [polygons], str(drawn))
    if cracked_ends is None:
        return
    fig = figures["cracks"]
    check(f"{case}: cracks.png draws no disc", not collections(fig, "EllipseCollection"))
    segments = [seg for c in collections(fig, "LineCollection") for seg in c.get_segments()]
    got = sorted(tuple(np.round(np.sort(np.asarray(q), axis=0).ravel(), 6)) for q in segments)
    want = sorted(tuple(np.round(np.sort(np.asarray(q), axis=0).ravel(), 6)) for q in cracked_ends)
    check(f"{case}: cracks.png draws the {len(want)} logged facets", got == want,
          f"{len(got)} segments, e.g. {got[:2]}; expected e.g. {want[:2]}")


def check_splitting_strength(case, figures, png, P, D, t=1.0):
    """A Brazilian disc's load plot marks the peak P and states f_st = 2P/(πDt), as does its PNG's Description."""
    f_st = 2 * P / (np.pi * D * t)
    said = f"f_st = 2P/(πDt) = {f_st * 1e-6:.3g} MPa"
    ax = [a for a in figures["xy"].axes if a.get_title().startswith("group.bottom.reaction_y")]
    texts = [x.get_text() for x in ax[0].get_legend().get_texts()] if ax and ax[0].get_legend() else []
    check(f"{case}: load plot states {said}", any(said in x for x in texts), str(texts))
    peak = [ln for ln in ax[0].lines if ln.get_label().startswith("peak P")] if ax else []
    check(f"{case}: load plot marks the peak P = {P * 1e-3:.4g} kN", len(peak) == 1 and
          abs(peak[0].get_ydata()[0] - P * 1e-3) < 1e-9 * P, str([ln.get_ydata() for ln in peak]))
    note = png_description(png) or ""
    check(f"{case}: xy.png's Description states {said}", said in note and "per metre of thickness" in note, note)


def check_force_chains(case, figures, path, in_slice=None):
    """The specimen picture's force-chain panel: one line per contact of the last frame whose particles it draws,
    the widest (3 pt) the largest |normal force|, tension red and compression not, and its legend saying what the
    width means."""
    kind = "specimen" if "specimen" in figures else "slice"
    fig = figures[kind]
    panels = axes_titled(fig, "force chains")
    check(f"{case}: {kind}.png has a force-chain panel", len(panels) == 1, str([a.get_title() for a in fig.axes]))
    check(f"{case}: {kind}.png's other force panel is the out-of-balance force",
          len(axes_titled(fig, "out-of-balance force")) == 1, str([a.get_title() for a in fig.axes]))
    if len(panels) != 1:
        return
    ax = panels[0]
    pair, fn, branch, x = last_contacts(path)
    keep = np.ones(len(fn), bool) if in_slice is None else in_slice[pair[:, 0]] & in_slice[pair[:, 1]]
    lines = [c for c in ax.collections if type(c).__name__ == "LineCollection"]
    segments = lines[0].get_segments() if len(lines) == 1 else []
    check(f"{case}: force chains draw the {int(keep.sum())} contacts of the last frame"
          + (" in the slice" if in_slice is not None else ""), len(segments) == keep.sum() and len(lines) == 1,
          f"{len(lines)} line collections, {len(segments)} segments")
    if len(segments) != keep.sum() or keep.sum() == 0:
        return
    widths = np.broadcast_to(lines[0].get_linewidths(), (len(segments),))
    big = np.flatnonzero(keep)[np.argmax(np.abs(fn[keep]))]
    plane = [0, 1] if x.shape[1] == 2 else [0, 2]
    want = np.stack([x[pair[big, 0]][plane], (x[pair[big, 0]] + branch[big])[plane]]) * 1e3  # mm
    widest = np.asarray(segments[int(np.argmax(widths))])
    check(f"{case}: the widest chain line (3 pt) is the largest |normal force|",
          np.allclose(widest, want) and abs(widths.max() - 3.0) < 1e-9, f"{widest} vs {want}, width {widths.max()}")
    red = np.all(np.isclose(lines[0].get_colors(), to_rgba("tab:red")), axis=1)
    red = np.broadcast_to(red, (len(segments),))
    check(f"{case}: tension chains red, compression not", red.sum() == (fn[keep] < 0).sum() and red.sum() > 0,
          f"{red.sum()} red, {(fn[keep] < 0).sum()} in tension")
    title = ax.get_legend().get_title().get_text() if ax.get_legend() else ""
    words = ["line width ∝ |normal force|", "largest"] + (["per metre of thickness"] if x.shape[1] == 2 else [])
    check(f"{case}: chain legend says what the width means", all(w in title for w in words), title)


def check_error(case, p, path, words):
    lines = p.stderr.strip().splitlines()
    check(f"{case}: exit 3 (a file error)", p.returncode == 3, f"exit {p.returncode}")
    check(f"{case}: one-line message naming the file",
          len(lines) == 1 and path in lines[0] and all(w in lines[0] for w in words) and "Traceback" not in p.stderr,
          repr(p.stderr))


def check_compression_curve_reads_left_to_right_with_its_strength_and_modulus_marked():
    """A uniaxial compression run's strain and stress are negative: the x-y plot draws their magnitudes (left to
    right, upwards), marks the strength at the curve's peak and E's secant as `summary` reads them."""
    sys.path.insert(0, APP)
    import report_plots
    figures = []
    real = report_plots.save
    report_plots.save = lambda fig, out_dir, stem, kind, dpi=120: figures.append(fig) or kind
    strain = -np.linspace(0, 2e-3, 201)
    stress = np.where(-strain < 1e-3, 30e9 * strain, -30e6 - 10e9 * (strain + 1e-3))  # peak 30 MPa at 1e-3
    run = {"dimension": 3, "xy_plots": [("strain.axial", "wall.top.stress")],
           "history": {"strain.axial": {"data": strain, "unit": "-", "label": None},
                       "wall.top.stress": {"data": stress, "unit": "Pa", "label": None}},
           "summary": {"uniaxial": {"ucs": 30e6, "E_platens": 30e9, "E": 30e9, "peak_passed": True}},
           "uniaxial_pair": ("strain.axial", "wall.top.stress")}
    try:
        report_plots.plot_xy(run, "c", ".")
    finally:
        report_plots.save = real
    ax = figures[0].axes[0]
    curve = ax.lines[0].get_xydata()
    check("compression curve: drawn as magnitudes, left to right and upwards",
          curve[-1, 0] > 0 and curve[100, 1] > 0 and ax.get_xlabel().startswith("−"), ax.get_xlabel())
    labels = [l.get_label() for l in ax.lines]
    check("compression curve: UCS marked at the peak", "UCS 30 MPa" in labels and
          tuple(ax.lines[1].get_xydata()[0]) == (1e-3, 30.0), str(labels))
    slope = np.diff(ax.lines[2].get_ydata()) / np.diff(ax.lines[2].get_xdata())
    check("compression curve: E's secant along the elastic curve (30 GPa in MPa per unit strain)",
          abs(slope[0] - 30e3) < 1e-6 * 30e3, str(slope))


def check_splitting_strength_of_3d_discs():
    """3D: the disc's thickness from the scene, t of a cylinder of cells, the box's depth along z for a packing."""
    sys.path.insert(0, APP)
    import report_plots
    load = {"data": np.array([0.0, 15.24e3, 9e3]), "unit": "N", "label": None}
    for scene, D, t in (('kind = "voronoi_cells"\nshape = "disc"\ncentre = ["35 mm", "35 mm"]\nradius = "35 mm"\n'
                         'thickness = "55 mm"', 0.07, 0.055),
                        ('kind = "packing"\nshape = "cylinder"\nlo = [0, 0, 0]\nhi = ["70 mm", "80 mm", "3 cm"]',
                         0.07, 0.03)):
        run = {"dimension": 3, "scene_text": "[specimen]\n" + scene, "xy_plots": [("d", "group.bottom.reaction_y")],
               "history": {"group.bottom.reaction_y": load}}
        s = report_plots.splitting_strength(run) or {}
        check(f"3D disc ({scene.split(chr(10))[0]}): f_st = 2P/(πDt) with D = {D} m, t = {t} m",
              np.isclose(s.get("f_st", 0), 2 * 15.24e3 / (np.pi * D * t)), str(s))
    run["scene_text"] = "[specimen]\nkind = \"packing\"\nshape = \"box\"\nlo = [0, 0, 0]\nhi = [1, 1, 1]"
    check("a box is no Brazilian disc", report_plots.splitting_strength(run) is None)


def check_shear_lag_curve_is_the_summary_solution():
    """An elastic pull's strain panel draws ε₀ sinh(λ(L − x))/sinh(λL) of the summary's shear_lag block, its legend
    giving λL and the gauges' deviation; without the block, no such curve."""
    sys.path.insert(0, APP)
    import matplotlib.pyplot as plt
    import report_pullout
    fig, ax = plt.subplots()
    lam, eps0, length = 75.0, 2e-4, 0.04
    report_pullout.draw_shear_lag(ax, {"shear_lag": {"lambda": lam, "epsilon_0": eps0,
                                                     "max_deviation_over_epsilon_0": 0.012}}, length)
    lines = [ln for ln in ax.lines if ln.get_label().startswith("shear lag")]
    ok = len(lines) == 1
    if ok:
        x, y = lines[0].get_xdata() * 1e-3, lines[0].get_ydata() * 1e-6
        ok = np.allclose(y, eps0 * np.sinh(lam * (length - x)) / np.sinh(lam * length), rtol=1e-12, atol=1e-15)
        ok = ok and "λL = 3," in lines[0].get_label() and "within 1.2 % of ε₀" in lines[0].get_label()
    check("elastic pull: the shear-lag curve of the summary's λ and ε₀, labelled with λL and the deviation", ok,
          str([ln.get_label() for ln in ax.lines]))
    fig2, ax2 = plt.subplots()
    report_pullout.draw_shear_lag(ax2, {}, length)
    check("a pull without interface_stiffness: no shear-lag curve", not ax2.lines)
    plt.close(fig)
    plt.close(fig2)
    names = [report_pullout.capacity_name({"summary": {"pullout": {"peak_passed": p}}}) for p in (True, False)]
    check("a pull that never peaked marks its largest load so far, not a capacity",
          names == ["capacity", "largest load so far (no peak)"], str(names))


def main():
    keep = os.environ.get("REPORT_PLOTS_KEEP")
    with tempfile.TemporaryDirectory() as tmp:
        d = keep or tmp
        os.makedirs(d, exist_ok=True)

        f2 = os.path.join(d, "disc2d.h5")
        make_run(f2, 2, 3000, xy="axial_strain:axial_stress;measure.box.strain_yy:measure.box.stress_yy", cracks=400)
        before = (digest(f2), os.stat(f2).st_mtime_ns)
        check_pngs("2D with frames and cracks", run_report(f2),
                   ["disc2d_history.png", "disc2d_xy.png", "disc2d_energy.png", "disc2d_specimen.png",
                    "disc2d_cracks.png"])
        check("2D: HDF5 file unchanged", (digest(f2), os.stat(f2).st_mtime_ns) == before)
        for kind in ("history", "xy", "energy"):
            note = png_description(os.path.join(d, f"disc2d_{kind}.png")) or ""
            check(f"2D {kind} plot says its forces are per metre of thickness", "per metre of thickness" in note, note)

        f2n = os.path.join(d, "disc2d_noframes.h5")
        make_run(f2n, 2, 500, frames=0)
        out = os.path.join(d, "plots")
        p = run_report(f2n, "--out-dir", out)
        check_pngs("2D no frames, --out-dir", p,
                   ["disc2d_noframes_history.png", "disc2d_noframes_energy.png", "disc2d_noframes_specimen.png"])
        check("2D no frames: PNGs in --out-dir", all(os.path.dirname(q) == out for q in p.stdout.split()))

        f3 = os.path.join(d, "sphere3d.h5")
        make_run(f3, 3, 4000, xy="axial_strain:axial_stress", cracks=300)
        check_pngs("3D with frames and cracks", run_report(f3),
                   ["sphere3d_history.png", "sphere3d_xy.png", "sphere3d_energy.png", "sphere3d_slice.png",
                    "sphere3d_cracks.png"])
        check("3D history plot has no thickness note", png_description(os.path.join(d, "sphere3d_history.png")) is None)

        f3n = os.path.join(d, "sphere3d_bare.h5")
        make_run(f3n, 3, 1000, frames=0, history=False)
        check_pngs("3D no frames, no history", run_report(f3n), ["sphere3d_bare_slice.png"])

        # A run still writing holds the file open (and locked) for writing: report must still read it.
        fw = os.path.join(d, "writing.h5")
        make_run(fw, 2, 300)
        with h5py.File(fw, "r+") as w:
            w["history/time"].attrs.create("unit", fixed("s"))
            w.flush()
            check_pngs("2D file open for writing", run_report(fw),
                       ["writing_history.png", "writing_energy.png", "writing_specimen.png"])

        # A pull test ([pullout] in the stored scene): load-slip, strain profiles and the staged crack pictures.
        fp = os.path.join(d, "pull.h5")
        make_run(fp, 2, 2000, frames=0, cracks=300)
        with h5py.File(fp, "r+") as w:
            del w["scene"]
            w.create_dataset("scene", data=fixed(PULL_SCENE))
            h = w["history"]
            s = np.linspace(0, 1, h["time"].shape[0])
            load = 3e5 * np.sin(np.pi * s)  # N/m: up to 15 kN for b_f = 50 mm, and down again
            series(h, "pullout.load", load, "N")
            series(h, "pullout.slip", 1e-4 * s, "m")
            for k in range(5):
                series(h, f"pullout.strain_{k}", load / 2.34e8 * np.exp(-0.5 * k), "-")
        check_pngs("pull test", run_report(fp),
                   ["pull_history.png", "pull_energy.png", "pull_specimen.png", "pull_cracks.png", "pull_pullout.png",
                    "pull_pullout_cracks.png"])
        status, figures = report_figures(fp, os.path.join(d, "figures"))
        check_legends_inside("pull test", figures, at_least=("pullout_cracks",))
        with h5py.File(fp, "r") as w:
            yields = int((w["cracks/kind"][()] == 1).sum())
        stages = figures["pullout_cracks"].axes
        dots = [sum(len(c.get_offsets()) for c in ax.collections if type(c).__name__ == "PathCollection")
                for ax in stages]
        check("pull test: the crack stages draw the first yields as dots, all of them at the end",
              dots[-1] == yields > 0 and dots == sorted(dots), f"{dots}, {yields} first yields logged")
        colours = {tuple(np.round(c.get_facecolor()[0], 3)) for ax in stages for c in ax.collections
                   if type(c).__name__ == "PathCollection"}
        check("pull test: first yields in a colour of their own",
              colours == {tuple(np.round(to_rgba("tab:orange"), 3))}, str(colours))
        labels = [x.get_text() for x in stages[0].get_legend().get_texts()]
        check("pull test: the legend names the first yields", "first yield (softening)" in labels, str(labels))
        title = stages[-1].get_title(loc="left")
        check("pull test: each stage counts its first yields", title.endswith(f"{yields} first yields"), title)
        # Without load levels (scenes/pull_elastic_2d.toml), the strain profile at the end of the run.
        fpn = os.path.join(d, "pull_no_levels.h5")
        with open(fp, "rb") as a, open(fpn, "wb") as b:
            b.write(a.read())
        set_scene(fpn, PULL_SCENE.replace('load_levels = ["4 kN", "8 kN", "12 kN", "14 kN"]\n', ""))
        status, figures = report_figures(fpn, os.path.join(d, "figures"))
        with h5py.File(fpn, "r") as w:
            last = [w[f"history/pullout.strain_{k}"][-1] * 1e6 for k in range(5)]
        drawn = figures["pullout"].axes[1].lines
        profiles = [ln for ln in drawn if "end of the run" in ln.get_label()]
        check("pull test without load levels: the strain profile at the end of the run",
              len(profiles) == 1 and np.allclose(profiles[0].get_ydata(), last), str([ln.get_label() for ln in drawn]))

        # Rigid cells: the crack pattern of their facets, by the load's peak and at the end (2D), or at the end in
        # the section at mid-thickness (3D: the scene plots no load).
        fc2 = os.path.join(d, "cells2d.h5")
        make_run(fc2, 2, 48, frames=5, xy="axial_strain:axial_stress")
        add_cells(fc2, 2, (6, 8))
        check_pngs("2D rigid cells", run_report(fc2),
                   ["cells2d_history.png", "cells2d_xy.png", "cells2d_energy.png", "cells2d_specimen.png",
                    "cells2d_cells.png"])
        fc3 = os.path.join(d, "cells3d.h5")
        make_run(fc3, 3, 96, frames=3, history=False)
        add_cells(fc3, 3, (4, 6, 4))
        check_pngs("3D rigid cells", run_report(fc3), ["cells3d_slice.png", "cells3d_cells.png"])
        status, figures = report_figures(fc3, os.path.join(d, "figures"))
        # The section at z = 10 mm, the top of the second layer of cells: its 4 x 6 cells are cut.
        check_cells_drawn_as_polygons("3D rigid cells", figures, 24)

        # Their crack logs: the facets the log names drawn as lines, over the cells as polygons.
        with h5py.File(fc2, "r") as w:
            faces = w["specimen/cells/face_start"].shape[0] - 1
        cracked = add_cell_cracks(fc2, kind=0)
        check_pngs("2D rigid cells with a crack log", run_report(fc2),
                   ["cells2d_history.png", "cells2d_xy.png", "cells2d_energy.png", "cells2d_specimen.png",
                    "cells2d_cracks.png", "cells2d_cells.png"])
        status, figures = report_figures(fc2, os.path.join(d, "figures"))
        with h5py.File(fc2, "r") as w:
            g = w["specimen/cells"]
            corner, start, ends = g["corner"][()], g["facet_start"][()], g["facet_corner"][()]
        check_cells_drawn_as_polygons("2D rigid cells", figures, faces,
                                      [corner[ends[start[k]:start[k + 1]]] * 1e3 for k in cracked])
        check_legends_inside("2D rigid cells", figures, at_least=("cracks", "specimen"))
        cracked = add_cell_cracks(fc3, kind=1)
        status, figures = report_figures(fc3, os.path.join(d, "figures"))
        with h5py.File(fc3, "r") as w:
            g = w["specimen/cells"]
            corner, start, ends = g["corner"][()], g["facet_start"][()], g["facet_corner"][()]
        cut = []
        for k in cracked:  # the cracked facets the section crosses: their corners on the plane, in x-y
            q = corner[ends[start[k]:start[k + 1]]]
            if q[:, 2].min() < 10e-3 <= q[:, 2].max() + 1e-12:
                cut.append(np.unique(q[np.isclose(q[:, 2], 10e-3)][:, :2], axis=0) * 1e3)
        check_cells_drawn_as_polygons("3D rigid cells with a crack log", figures, 24, cut)
        check("3D rigid cells: 6 cracked facets cut by the section", len(cut) == 6, str(len(cut)))

        # Brazilian discs: the legends inside the figures, the peak load and the splitting strength marked.
        fb = os.path.join(d, "brazilian_cells.h5")
        make_run(fb, 2, 196, frames=5)
        add_cells(fb, 2, (14, 14))
        set_scene(fb, BRAZILIAN_CELLS)
        P = add_disc_load(fb, 3.6e5)
        add_cell_cracks(fb, kind=1)
        status, figures = report_figures(fb, os.path.join(d, "figures"))
        check("Brazilian disc of cells: report exit 0", status == 0)
        check_legends_inside("Brazilian disc of cells", figures, at_least=("cracks", "specimen", "xy"))
        check_splitting_strength("Brazilian disc of cells", figures,
                                 os.path.join(d, "figures", "brazilian_cells_xy.png"), P, 0.07)
        with h5py.File(fb, "r") as w:
            faces = w["specimen/cells/face_start"].shape[0] - 1
        check_cells_drawn_as_polygons("Brazilian disc of cells", figures, faces)

        fe = os.path.join(d, "brazilian_particles.h5")
        make_run(fe, 2, 3000, frames=3, cracks=400)
        set_scene(fe, BRAZILIAN_PACKING)
        P = add_disc_load(fe, 2.8e5)
        add_contacts(fe, frame_count=False)
        status, figures = report_figures(fe, os.path.join(d, "figures"))
        check("Brazilian disc of particles: report exit 0", status == 0)
        check_legends_inside("Brazilian disc of particles", figures, at_least=("cracks", "specimen", "xy"))
        check_splitting_strength("Brazilian disc of particles", figures,
                                 os.path.join(d, "figures", "brazilian_particles_xy.png"), P, 0.02)
        check_force_chains("2D contacts (no frame_count)", figures, fe)

        # Force chains in 3D: the contacts whose two spheres the slice cuts. Without /contacts, no chain panel.
        f3c = os.path.join(d, "sphere3d_contacts.h5")
        make_run(f3c, 3, 4000, frames=3)
        add_contacts(f3c)
        status, figures = report_figures(f3c, os.path.join(d, "figures"))
        with h5py.File(f3c, "r") as w:
            x, r = w["frames/x"][-1].reshape(-1, 3), w["specimen/radius"][()]
        yc = 0.5 * ((x[:, 1] - r).min() + (x[:, 1] + r).max())
        check_force_chains("3D contacts", figures, f3c, in_slice=np.abs(x[:, 1] - yc) < r)
        check_legends_inside("3D contacts", figures, at_least=("slice",))
        status, figures = report_figures(f2, os.path.join(d, "figures"))
        check("2D without /contacts: no force-chain panel", not axes_titled(figures["specimen"], "force chains"),
              str([a.get_title() for a in figures["specimen"].axes]))
        check("2D without /contacts: the force panel is the out-of-balance force",
              len(axes_titled(figures["specimen"], "out-of-balance force")) == 1)
        check("not a Brazilian disc: no splitting strength", "f_st" not in (png_description(
            os.path.join(d, "figures", "disc2d_xy.png")) or "x"))
        check_legends_inside("2D with frames and cracks", figures, at_least=("cracks", "specimen"))

        missing = os.path.join(d, "no_such_run.h5")
        check_error("missing file", run_report(missing), missing, ["no such file"])

        other = os.path.join(d, "other.h5")
        with h5py.File(other, "w") as f:
            f["data"] = np.arange(10.0)
        check_error("HDF5 file not from mesocrack", run_report(other), other, ["not a mesocrack file"])

        text = os.path.join(d, "text.h5")
        with open(text, "w") as f:
            f.write("not hdf5\n")
        check_error("not an HDF5 file", run_report(text), text, ["HDF5"])

    check_compression_curve_reads_left_to_right_with_its_strength_and_modulus_marked()
    check_splitting_strength_of_3d_discs()
    check_shear_lag_curve_is_the_summary_solution()

    failed = [r for r in results if not r[1]]
    for name, _, detail in failed:
        print(f"FAIL {name}: {detail}")
    print(f"report_plots: {len(results) - len(failed)} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
