#!/usr/bin/python3
"""Check of app/report.py on small synthetic mesocrack-1 files (2D/3D, with and without frames,
with an xy_plots attribute) plus the error cases. Run: /usr/bin/python3 tests/report_plots.py
Set REPORT_PLOTS_KEEP=DIR to keep the files and PNGs in DIR for a look."""
import hashlib
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

REPORT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "app", "report.py")
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
                series(h, f"wall.top.force_{c}", (2e4 if c == "y" else 50) * s * (1 + 0.01 * rng.standard_normal(S)), "N")
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
            fr["force"] = (rng.lognormal(2, 0.8, (frames, n, 1)) * rng.standard_normal((frames, n, dim))).reshape(frames, -1)
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
    """The PNG's Description text chunk (tEXt), or None."""
    data = open(path, "rb").read()
    at = 8
    while at + 8 <= len(data):
        size = int.from_bytes(data[at:at + 4], "big")
        kind = data[at + 4:at + 8]
        if kind == b"tEXt":
            key, _, value = data[at + 8:at + 8 + size].partition(b"\0")
            if key == b"Description":
                return value.decode("latin-1")
        at += 12 + size
    return None


def check_error(case, p, path, words):
    lines = p.stderr.strip().splitlines()
    check(f"{case}: exit 3 (a file error)", p.returncode == 3, f"exit {p.returncode}")
    check(f"{case}: one-line message naming the file",
          len(lines) == 1 and path in lines[0] and all(w in lines[0] for w in words) and "Traceback" not in p.stderr,
          repr(p.stderr))


def check_compression_curve_reads_left_to_right_with_its_strength_and_modulus_marked():
    """A uniaxial compression run's strain and stress are negative: the x-y plot draws their magnitudes (left to
    right, upwards), marks the strength at the curve's peak and E's secant as `summary` reads them."""
    sys.path.insert(0, os.path.join(os.path.dirname(REPORT)))
    import report_plots
    figures = []
    report_plots.save = lambda fig, out_dir, stem, kind, dpi=120: figures.append(fig) or kind
    strain = -np.linspace(0, 2e-3, 201)
    stress = np.where(-strain < 1e-3, 30e9 * strain, -30e6 - 10e9 * (strain + 1e-3))  # peak 30 MPa at 1e-3
    run = {"dimension": 3, "xy_plots": [("strain.axial", "wall.top.stress")],
           "history": {"strain.axial": {"data": strain, "unit": "-", "label": None},
                       "wall.top.stress": {"data": stress, "unit": "Pa", "label": None}},
           "summary": {"uniaxial": {"ucs": 30e6, "E_platens": 30e9, "E": 30e9, "peak_passed": True}},
           "uniaxial_pair": ("strain.axial", "wall.top.stress")}
    report_plots.plot_xy(run, "c", ".")
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

    failed = [r for r in results if not r[1]]
    for name, _, detail in failed:
        print(f"FAIL {name}: {detail}")
    print(f"report_plots: {len(results) - len(failed)} passed, {len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
