#!/usr/bin/python3
"""The peers and mesocrack on the shared bonded specimen (benchmarks/specimens/README.md), timed in one session on
this machine, interleaved and repeated, with the ratios and their spread (`make peers-bench`).

Each round runs, for each specimen, every pairing one after the other: the peer, then mesocrack on the same
specimen and model, so that a slower stretch of the machine falls on both. A ratio is taken within a round; the
table gives its mean and its range over the rounds, and is written to a new file in benchmarks/results/peers/
(`--out`), named by the thread count and the date, headed by the processor and the commit. A peer that is not
installed is skipped with a line saying so (`--install` installs the Debian packages first: never a project
dependency, never needed by `make test`).

Pairings (like with like):
  - parallel bonds against ESyS-Particle's RotBond (bonds with bending and twisting moments; a worker process per
    thread, beside its master);
  - parallel bonds against Yade's CohFrict (cohesive bonds with bending and twisting moments);
  - CPM against Yade's CPM;
  - unbonded linear contacts against LIGGGHTS's Hertz contacts with tangential history (it has no bonds).
Each engine runs the stepping loop alone, 2 000 steps after 10 of warm-up, on `--threads` threads.

  benchmarks/peers/peers_bench.py [--install] [--specimens n10k,n50k] [--rounds 2] [--threads 1] [--build build]
                                  [--pairings parallel_vs_esys_rotbond,...]
"""
import argparse
import datetime
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
sys.path.insert(0, str(HERE))
from peer_inputs import write_geo, write_liggghts_data  # noqa: E402

PACKAGES = {"yade": "yade", "esysparticle": "esys-particle", "liggghts": "liggghts"}
# pairing: (peer label, the peer's executable, its model, mesocrack's model)
PAIRINGS = {
    "parallel_vs_esys_rotbond": ("ESyS-Particle RotBond", "esysparticle", "rotbond", "parallel"),
    "parallel_vs_yade_cohfrict": ("Yade CohFrict", "yade", "cohfrict", "parallel"),
    "cpm_vs_yade_cpm": ("Yade CPM", "yade", "cpm", "cpm"),
    "unbonded_vs_liggghts_hertz": ("LIGGGHTS Hertz/history (no bonds)", "liggghts", "hertz", "unbonded"),
}


def result_line(text):
    """The particle-steps per second of a run's RESULT line, or of LIGGGHTS's last "Loop time" line."""
    for line in text.splitlines():
        if line.startswith("RESULT"):
            return float(re.search(r"particle_steps_per_s=([0-9.eE+-]+)", line).group(1))
    loops = re.findall(r"Loop time of ([0-9.eE+-]+) on \d+ procs for (\d+) steps with (\d+) atoms", text)
    if loops:
        seconds, steps, atoms = loops[-1]
        return int(atoms) * int(steps) / float(seconds)
    raise RuntimeError("no RESULT line in:\n" + text[-2000:])


def run(cmd, threads):
    # Every engine under its OpenMP runtime's own wait policy, as its users run it (the machine is quiet).
    env = {k: v for k, v in os.environ.items() if k != "OMP_WAIT_POLICY"}
    env.update({"OMP_NUM_THREADS": str(threads), "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"})
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))}: exit {p.returncode}\n{p.stdout[-1500:]}\n{p.stderr[-1500:]}")
    return result_line(p.stdout)


def peer_command(engine, model, spheres, threads, work):
    if engine == "yade":
        return ["yade", "-n", f"-j{threads}", "-x", str(HERE / "yade_bonded.py"), str(spheres), model, "2000"]
    if engine == "esysparticle":
        geo = work / f"{spheres.stem}.geo"
        if not geo.exists():
            write_geo(spheres, geo)
        return ["mpirun", "--oversubscribe", "--mca", "mpi_yield_when_idle", "1", "-np", str(threads + 1),
                "esysparticle", str(HERE / "esys_rotbond.py"), str(geo), "2000", str(threads)]
    if engine == "liggghts":
        data = work / f"{spheres.stem}.liggghts"
        r_min = write_liggghts_data(spheres, data)
        return ["mpirun", "--oversubscribe", "-np", str(threads), "liggghts", "-in", str(HERE / "liggghts_hertz.in"),
                "-var", "data", str(data), "-var", "steps", "2000", "-var", "rmin", repr(r_min), "-log", "none"]
    raise ValueError(engine)


def install(engines):
    missing = [PACKAGES[e] for e in engines if not shutil.which(e)]
    if not missing:
        return
    cmd = ["apt-get", "install", "-y", "--no-install-recommends"] + missing
    if os.geteuid() != 0:
        cmd = ["sudo"] + cmd
    print("installing the peers:", " ".join(cmd), flush=True)
    subprocess.run(cmd, check=True, env={**os.environ, "DEBIAN_FRONTEND": "noninteractive"})


def machine():
    """The processor's model name as the kernel reports it, and the core count."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return f"{line.split(':', 1)[1].strip()}, {os.cpu_count()} cores"
    except OSError:
        pass
    return f"{platform.machine()}, {os.cpu_count()} cores"


def commit():
    """This tree's checked-out commit, marked when tracked files have uncommitted changes. The build named by
    --build is taken to be of this tree: a build folder made from another checkout is not detected."""
    def git(*args):
        return subprocess.run(["git", "-C", str(ROOT), *args], capture_output=True, text=True).stdout.strip()
    head = git("rev-parse", "--short", "HEAD") or "unknown"
    return head + (" with uncommitted changes" if git("status", "--porcelain", "--untracked-files=no") else "")


def results_file(out, threads, suffix):
    """A new file for each run (date, then a count): a run never overwrites the figures of one kept before."""
    stem = f"peers_{threads}thread{suffix}_{datetime.date.today()}"
    path, k = out / f"{stem}.md", 2
    while path.exists():
        path, k = out / f"{stem}_{k}.md", k + 1
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--install", action="store_true", help="apt-get install the peers that are missing")
    ap.add_argument("--specimens", default="n10k")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--pairings", default=",".join(PAIRINGS), help="which pairings, by key")
    ap.add_argument("--build", default=str(ROOT / "build"), help="the build folder (its benchmarks/throughput)")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "results" / "peers"))
    a = ap.parse_args()
    throughput = Path(a.build) / "benchmarks" / "throughput"
    specimens = Path(a.build) / "specimens"
    if not throughput.exists():
        sys.exit(f"{throughput}: not found (build first: make demo)")
    engines = sorted({PAIRINGS[k][1] for k in a.pairings.split(",") if k in PAIRINGS})
    if a.install:
        install(engines)
    pairings = {}
    for key in a.pairings.split(","):
        if key not in PAIRINGS:
            sys.exit(f"--pairings: '{key}' is not one of {', '.join(PAIRINGS)}")
        p = PAIRINGS[key]
        if shutil.which(p[1]):
            pairings[key] = p
        else:
            print(f"{p[0]}: skipped ({p[1]} is not installed; --install, or apt-get install {PACKAGES[p[1]]})")
    work = Path(tempfile.mkdtemp(prefix="peers_bench."))
    figures = {}  # (specimen, pairing) -> [(peer, ours), ...]
    for rnd in range(a.rounds):
        for name in a.specimens.split(","):
            spheres = specimens / f"{name}.spheres"
            if not spheres.exists():
                sys.exit(f"{spheres}: not found (the build unpacks the shared specimens there)")
            for key, (label, engine, model, ours_model) in pairings.items():
                peer = run(peer_command(engine, model, spheres, a.threads, work), a.threads)
                ours = run([str(throughput), "--one", f"{name}:{ours_model}:{a.threads}", "--specimen-dir",
                            str(specimens)], a.threads)
                figures.setdefault((name, key), []).append((peer, ours))
                print(f"round {rnd + 1}, {name}, {label}: {peer:.3g} particle-steps/s; mesocrack {ours_model}: "
                      f"{ours:.3g}; ratio {ours / peer:.2f}", flush=True)
    lines = [f"`benchmarks/peers/peers_bench.py --specimens {a.specimens} --rounds {a.rounds} --threads {a.threads}`, "
             f"{datetime.date.today()}, {machine()}, commit {commit()}; particle-steps per second of "
             "the stepping loop, each pairing run peer then mesocrack, the rounds one after another.", "",
             "| specimen | mesocrack against | peer (rounds) | mesocrack (rounds) | ratio: mean (range) |",
             "|---|---|---|---|---|"]
    for (name, key), runs in figures.items():
        ratios = [o / p for p, o in runs]
        lines.append(f"| {name} | {PAIRINGS[key][0]} | {', '.join(f'{p:.3g}' for p, _ in runs)} | "
                     f"{', '.join(f'{o:.3g}' for _, o in runs)} | {statistics.mean(ratios):.2f} "
                     f"({min(ratios):.2f}–{max(ratios):.2f}) |")
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    suffix = "" if a.pairings == ",".join(PAIRINGS) else "_" + a.pairings.replace(",", "_")
    path = results_file(out, a.threads, suffix)
    path.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"written to {path}")


if __name__ == "__main__":
    main()
