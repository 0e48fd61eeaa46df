#!/usr/bin/python3
"""Every XDMF reader of ParaView (Debian's 5.11: Xdmf3ReaderS and Xdmf3ReaderT, what its "Open" picks, and the legacy
XDMFReader) opens the sidecar of each kind of output (2D and 3D particles, 2D rigid cells with their facets, 3D cells
with fibres), steps through every frame, and reads the values the HDF5 file holds: the positions and velocities of
the last frame, its contacts' forces, the facets' damage, the fibres' state.
Run: tests/paraview_opens_outputs.py MESOCRACK SOURCE_DIR.
Skipped (exit 77) where ParaView's Python (python3-paraview) is not installed."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

SKIP = 77
# Run inside pvpython: the data each reader gives at every frame, as JSON on a line of its own.
READ = r"""
import json, sys
from paraview import servermanager
from paraview.simple import Xdmf3ReaderS, Xdmf3ReaderT, XDMFReader
path, kind = sys.argv[1], sys.argv[2]
r = {"S": lambda: Xdmf3ReaderS(FileName=[path]), "T": lambda: Xdmf3ReaderT(FileName=[path]),
     "legacy": lambda: XDMFReader(FileNames=[path])}[kind]()
times = list(r.TimestepValues) if hasattr(r.TimestepValues, "__len__") else [r.TimestepValues]
def leaves(d, name=""):
    if d is None:  # a collection without a grid at this time (the contacts of a frame that has none)
        return
    if d.IsA("vtkMultiBlockDataSet"):
        for k in range(d.GetNumberOfBlocks()):
            meta = d.GetMetaData(k)
            yield from leaves(d.GetBlock(k), meta.Get(d.NAME()) if meta and meta.Has(d.NAME()) else str(k))
    elif d is not None and d.IsA("vtkMultiPieceDataSet"):
        for k in range(d.GetNumberOfPieces()):
            yield from leaves(d.GetPiece(k), f"{name}.{k}")
    elif d is not None:
        yield name, d
out = {"times": times, "frames": []}
for t in times:
    r.UpdatePipeline(t)
    frame = {}
    for name, leaf in leaves(servermanager.Fetch(r)):
        block = {"points": leaf.GetNumberOfPoints(), "cells": leaf.GetNumberOfCells(),
                 "point0": list(leaf.GetPoint(0)) if leaf.GetNumberOfPoints() else None, "arrays": {}}
        for data, centre in ((leaf.GetPointData(), "node"), (leaf.GetCellData(), "cell")):
            for k in range(data.GetNumberOfArrays()):
                a = data.GetArray(k)
                block["arrays"][a.GetName()] = [a.GetTuple(i) for i in range(min(a.GetNumberOfTuples(), 50))]
        frame[name] = block
    out["frames"].append(frame)
print("RESULT " + json.dumps(out))
"""

results = []


def check(name, ok, detail=""):
    results.append((name, bool(ok), detail))


def read_with(pvpython, script, xdmf, kind):
    p = subprocess.run([pvpython, script, xdmf, kind], capture_output=True, text=True, timeout=300)
    lines = [l for l in p.stdout.splitlines() if l.startswith("RESULT ")]
    if p.returncode != 0 or not lines:
        return None, f"exit {p.returncode}: {p.stderr.strip()[-400:]}"
    return json.loads(lines[-1][len("RESULT "):]), ""


def by_points(frame, n):
    """The block of a frame with n points (the particles, or the cells' nodes)."""
    return next((b for b in frame.values() if b["points"] == n and "radius" in b["arrays"]), None)


def check_output(pvpython, script, h5, kinds):
    with h5py.File(h5, "r") as f:
        d = int(f.attrs["dimension"])
        n = f["specimen/radius"].shape[0]
        frames = f["frames/time"].shape[0]
        x_last = f["frames/x"][-1].reshape(n, d)
        v_last = f["frames/v"][-1].reshape(n, d)
        damage = f["frames/damage"][-1] if "frames/damage" in f else None
        fibre_state = f["frames/fibre_state"][-1] if "frames/fibre_state" in f else None
        contacts = None  # the last frame's normal forces, when the frames record contacts
        if "contacts" in f and f["contacts/frame_count"][-1] > 0:
            first, count = f["contacts/frame_first"][-1], f["contacts/frame_count"][-1]
            contacts = f["contacts/normal_force"][first:first + count]
    stem = os.path.basename(h5)
    xdmf = os.path.splitext(h5)[0] + ".xdmf"
    for kind in kinds:
        case = f"{stem} with {kind}"
        got, why = read_with(pvpython, script, xdmf, kind)
        check(f"{case}: opens and steps through its frames", got is not None, why)
        if got is None:
            continue
        check(f"{case}: one time step per frame", len(got["times"]) == frames, f"{len(got['times'])} vs {frames}")
        last = got["frames"][-1]
        bodies = by_points(last, n)
        check(f"{case}: the bodies as {n} points with a vertex each", bodies is not None and bodies["cells"] == n,
              json.dumps({k: (b["points"], b["cells"]) for k, b in last.items()}))
        if bodies is None:
            continue
        # Float 8 in the XDMF: ParaView reads the file's doubles, so they compare exactly.
        check(f"{case}: body 0 where the last frame has it", bodies["point0"][:d] == list(x_last[0]),
              f"{bodies['point0']} vs {x_last[0]}")
        v = bodies["arrays"].get("velocity")
        check(f"{case}: body 0's velocity of the last frame", v is not None and v[0][0] == v_last[0][0],
              f"{v[0] if v else None} vs {v_last[0]}")
        for name in ("id", "phase", "radius"):
            check(f"{case}: names {name}", name in bodies["arrays"])
        if damage is not None:
            facets = next((b for b in last.values() if "damage" in b["arrays"]), None)
            check(f"{case}: the facets' damage of the last frame",
                  facets is not None and [t[0] for t in facets["arrays"]["damage"]] == list(damage[:50]))
        if contacts is not None:
            lines = next((b for b in last.values() if "normal_force" in b["arrays"]), None)
            check(f"{case}: the last frame's {len(contacts)} contacts as lines",
                  lines is not None and lines["cells"] == len(contacts),
                  json.dumps({k: (b["points"], b["cells"]) for k, b in last.items()}))
            check(f"{case}: the contacts' normal forces of the last frame",
                  lines is not None and [t[0] for t in lines["arrays"]["normal_force"]] == list(contacts[:50]))
            check(f"{case}: names the contacts' shear force, bond and branch vector",
                  lines is not None and all(a in lines["arrays"] for a in ("shear_force", "bonded", "branch")))
        if fibre_state is not None:
            fibres = next((b for b in last.values() if "state" in b["arrays"]), None)
            check(f"{case}: the fibres' state of the last frame",
                  fibres is not None and [t[0] for t in fibres["arrays"]["state"]] == list(fibre_state[:50]))


def main():
    pvpython = shutil.which("pvpython")
    if not pvpython:
        print("paraview_opens_outputs: skipped, ParaView's Python is not installed (apt install python3-paraview)")
        return SKIP
    cli, source = sys.argv[1], sys.argv[2]
    scenes = os.path.join(source, "scenes")
    with tempfile.TemporaryDirectory() as d:
        script = os.path.join(d, "read.py")
        with open(script, "w") as f:
            f.write(READ)
        runs = [("bar2d.h5", "lattice_tension_2d.toml", ["run.duration=0.05 ms"]),
                ("impact3d.h5", "collision_3d.toml", []),
                ("disc2d.h5", "brazilian_2d.toml", ["run.steps=3"]),
                ("fibre3d.h5", "fibre_pullout_two_sided_3d.toml", ["run.steps=3"])]
        for out, scene, sets in runs:
            args = [cli, "run", os.path.join(scenes, scene), "-o", os.path.join(d, out), "--threads", "1"]
            for s in sets:
                args += ["--set", s]
            p = subprocess.run(args, capture_output=True, text=True)
            if p.returncode != 0 and "built without the rigid-cell family" in p.stderr:
                continue  # a build without the rigid-cell family
            check(f"{scene} runs", p.returncode == 0, p.stderr.strip())
            if p.returncode == 0:
                check_output(pvpython, script, os.path.join(d, out), ["S", "T", "legacy"])
    failed = [r for r in results if not r[1]]
    for name, ok, detail in results:
        print(("ok   " if ok else "FAIL ") + name + ("" if ok or not detail else f": {detail}"))
    print(f"paraview_opens_outputs: {len(results) - len(failed)} passed, {len(failed)} failed")
    return 1 if failed or not results else 0


if __name__ == "__main__":
    sys.exit(main())
