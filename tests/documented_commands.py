#!/usr/bin/python3
"""Every command the README and the scenes' headers print is run, in a small version where the printed one takes
minutes or hours (a shorter run.duration, fewer realizations or ranks), or is named as run by another test, or
says why it cannot run here. The commands are found in the text (code blocks and inline code of README.md that
call mesocrack, make, mpirun or a study script; lines of a scene's header comment with `mesocrack` or `--set`): a
command printed that no entry below covers fails, and so does an entry that no longer matches a printed command.
Run: tests/documented_commands.py MESOCRACK SOURCE_DIR [mpi|no-mpi] (no-mpi: the mpirun commands are skipped, as
the rigid-cell ones are in a build without that family)."""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib

MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1", "OMP_NUM_THREADS": "1"}
# SCENE.toml of the templates, and the small version of scenes/uniaxial_2d.toml (its reduced copy): seconds to its
# peak, where the full scene's genesis alone takes half a minute (every_scene_in_scenes_folder_runs runs that one).
SMALL = "tests/scenes/uniaxial_2d_small.toml"
SHORT = ["--set", "run.duration=0.3 ms"]


def run(*argv, env=None, after=None):
    """The command run in a scratch folder holding out/ (as `mkdir -p out` makes it); {cli} and {src} are the
    binary and the source tree."""
    return {"argv": list(argv), "env": env or {}, "after": after}


def covered(test, why):
    """Run by the named test (its name must be in the tree's tests)."""
    return {"test": test, "why": why}


def not_here(why):
    return {"skip": why}


# (what identifies the printed command, how it is run). Placeholders of the templates (SCENE.toml, OUT.h5, N) are
# filled with the small scene.
ENTRIES = [
    ("make demo", not_here("builds the tree: `make demo` is CI's first command after a clean clone")),
    ("make test-minimal", not_here("a second build without the optional families; CI (.ci/run) runs it")),
    ("make test", not_here("the command that runs this test")),
    ("make bench", not_here("the benchmarks, hours")),
    ("make peers-bench", not_here("needs the peers (Yade, ESyS-Particle) installed: benchmarks/peers/")),
    ("mesocrack run SCENE.toml -o OUT.h5 [--threads N]",
     run("{cli}", "run", "{src}/" + SMALL, "-o", "out/o.h5", "--threads", "2", *SHORT)),
    ("mesocrack run --resume OUT.h5", run("{cli}", "run", "--resume", "out/o.h5", "--set", "run.duration=0.4 ms")),
    ("mesocrack generate SCENE.toml -o SPECIMEN.h5", run("{cli}", "generate", "{src}/" + SMALL, "-o", "out/s.h5")),
    ("mesocrack run SCENE.toml -o OUT.h5 --realizations N",
     run("{cli}", "run", "{src}/" + SMALL, "-o", "out/r.h5", "--realizations", "2", *SHORT)),
    ("calibrate SCENE.toml --target E=30GPa,nu=0.2,ucs=40MPa",
     covered("calibration_converges_on_a_small_2d_specimen", "E, ν and UCS on a small 2D packing")),
    ("calibrate scenes/rigid_cell_calibration_tension_2d.toml",
     covered("rigid_cell_calibration_to_a_model_code_class_gives_its_e_nu_ft_and_gf_in_the_calibrated_scene",
             "the class's calibration, and the calibrated scene run again")),
    ("--target class=C30/37 -o CALIBRATED.toml",
     covered("concrete_command_prints_a_classs_values_with_units_and_calibrate_takes_those_its_model_fits",
             "one run of the class's calibration on that scene")),
    ("calibrate scenes/tension_mortar_softening_2d.toml",
     covered("calibrate_on_the_phase_scenes_own_values_converges_in_the_runs_their_headers_say",
             "the header's targets on the scene itself")),
    ("mpirun -np 2 build/mesocrack calibrate scenes/cpm_uniax_tension.toml",
     covered("calibration_over_two_ranks_equals_the_serial_calibration_bit_for_bit",
             "a CPM calibration with f_c on two ranks")),
    ("mesocrack calibrate scenes/cpm_uniax_tension.toml",
     covered("CPM calibration reaches E, nu and f_t targets on a small specimen", "CPM's tension targets")),
    ("mesocrack concrete C", run("{cli}", "concrete", "C30/37")),
    ("mesocrack summary OUT.h5", run("{cli}", "summary", "out/o.h5")),
    ("mesocrack report OUT.h5", run("{cli}", "report", "out/o.h5")),
    ("mpirun -np 8 build/mesocrack run scenes/uniaxial_2d.toml -o out/u.h5 --realizations 32",
     run("mpirun", "-np", "2", "--oversubscribe", "{cli}", "run", "{src}/" + SMALL, "-o", "out/u.h5",
         "--realizations", "2", "--threads", "1", *SHORT, env=MPI_ENV)),
    ("mpirun -np 4 build/mesocrack run scenes/cpm_uniax_tension.toml -o out/cpm.h5",
     run("mpirun", "-np", "4", "--oversubscribe", "{cli}", "run", "{src}/scenes/cpm_uniax_tension.toml", "-o",
         "out/cpm.h5", "--threads", "1", "--set", "run.duration=0.2 ms", env=MPI_ENV)),
    ("mpirun -np 2 build/mesocrack run scenes/cpm_uniax_tension.toml --resume out/cpm.h5",
     run("mpirun", "-np", "2", "--oversubscribe", "{cli}", "run", "{src}/scenes/cpm_uniax_tension.toml",
         "--resume", "out/cpm.h5", "--threads", "1", "--set", "run.duration=0.3 ms", env=MPI_ENV)),
    ("split_scaling --particles 1000000",
     run("mpirun", "-np", "2", "--oversubscribe", "{build}/benchmarks/split_scaling", "--particles", "20000",
         "--threads", "1", env=MPI_ENV)),
    ("mpirun -np N python3 benchmarks/STUDY.py", not_here("a template: its studies are the entries below")),
    ("#SBATCH", not_here("a cluster's batch script (SLURM)")),
    ("build/mesocrack run beam_3d.toml", not_here("a cluster example on the user's own scene")),
    ("mesocrack keys --markdown",
     covered("key_reference_page_is_what_the_key_tables_declare", "docs/keys.md against it")),
    ("build/mesocrack keys rigid_cell.fibres", run("{cli}", "keys", "rigid_cell.fibres")),
    ("build/mesocrack keys rigid_cell", run("{cli}", "keys", "rigid_cell")),
    ("build/mesocrack keys walls", run("{cli}", "keys", "walls")),
    ("build/mesocrack keys", run("{cli}", "keys")),
    ("mesocrack run scenes/uniaxial_2d.toml -o out/u.h5 --realizations 5",
     run("{cli}", "run", "{src}/" + SMALL, "-o", "out/u5.h5", "--realizations", "2", *SHORT)),
    ("mesocrack run scenes/pull_tang_2d.toml -o pull.h5 --threads 2",
     run("{cli}", "run", "{src}/scenes/pull_tang_2d.toml", "-o", "pull.h5", "--threads", "2", "--set",
         "run.steps=50")),
    ("mesocrack run scenes/pull_tang_softening_2d.toml -o pull_soft.h5 --threads 2",
     run("{cli}", "run", "{src}/scenes/pull_tang_softening_2d.toml", "-o", "pull_soft.h5", "--threads", "2",
         "--set", "run.steps=50")),
    ("mesocrack run --threads 1", not_here("prose: how the accuracy studies call the command")),
    ("mesocrack run", not_here("the command named in prose")),
    ("mesocrack report", not_here("the command named in prose")),
    ("mpirun", not_here("the word in prose")),
]
# The studies: each parses its options and says what it does (their runs are the benchmarks', hours).
for study in ("brazilian_kveton", "kveton_l_shape_cts", "brazilian_two_families", "kveton_dynamic_rates",
              "spalling_kveton", "rigid_cell_direct_tension_hordijk", "bending_gregoire_size_effect",
              "bending_petersson", "bending_garcia_alvarez"):
    ENTRIES.append((f"python3 benchmarks/{study}.py", run("/usr/bin/python3", f"{{src}}/benchmarks/{study}.py",
                                                           "--help")))

# A scene header's `--set KEY=VALUE` hint: the scene with it, a few steps.
HINT_STEPS = ["--set", "run.steps=3"]
# Scenes whose hint is another's on the same [mesostructure] (placing 60 % of aggregates takes a minute): the hint
# runs on the first, and the test checks that the tables are the same.
SAME_MESOSTRUCTURE = {"bending_tang_softening_2d.toml": "bending_tang_brittle_2d.toml"}
HINTS = {
    "bending_tang_brittle_2d.toml": ["mesostructure.fraction=0.6"],
    "bending_tang_softening_2d.toml": ["mesostructure.fraction=0.6"],  # SAME_MESOSTRUCTURE: run once
    "fibre_contact_volume_fraction_3d.toml": ["rigid_cell.fibres[0].count=40"],
    "fibre_prism_random_field_3d.toml": ["rigid_cell.random_field.seed_offset=1"],
    "fibre_prism_tension_3d.toml": ["rigid_cell.fibres[0].debonding_energy=0",
                                    "contacts[0].fracture_energy=20 N/m"],
    "fibre_prism_wall_effect_3d.toml": ["rigid_cell.fibres[0].boundary=redraw"],
    "fibre_pullout_two_sided_3d.toml": ["rigid_cell.fibres[0].slip_hardening=0.01",
                                        "rigid_cell.fibres[0].debonding_energy=0",
                                        "rigid_cell.fibres[0].ends=[0.002,0.001,0.001,0.022,0.001,0.001]"],
    "rolling_slope_3d.toml": ["contacts[0].rolling_friction=0.4"],
}
# A header's calibrate command (from the scene's own values: it converges at once) is run by this test of
# tests/calibration_tension.cpp, whose list must name the scene; or not, and why.
HEADER_CALIBRATIONS = "calibrate_on_the_phase_scenes_own_values_converges_in_the_runs_their_headers_say"
CALIBRATIONS_NOT_RUN = {
    "rigid_cell_calibration_tension_2d.toml":
        "run, and its result checked, by rigid_cell_calibration_to_a_model_code_class_gives_its_e_nu_ft_and_gf_in_"
        "the_calibrated_scene (tests/rigid_cell/rigid_cell_calibration.cpp)",
    "pull_concrete_tension_2d.toml": "15 s a run on one core, 8 iterations: the phase scenes check the same path",
    "pull_concrete_softening_tension_2d.toml": "8 minutes a run (its header): the phase scenes check the same path",
    "bending_gregoire_explicit_2d.toml":
        "calibrates another scene (tension_mortar_softening_2d) to other targets, 54 s: the phase scenes check the "
        "same path",
}

results = []


def check(name, ok, detail=""):
    results.append((name, bool(ok), detail))


def readme_commands(text):
    """Commands in README.md's code blocks (a line continued by a backslash joined) and inline code."""
    pattern = re.compile(r"mesocrack (run|generate|calibrate|summary|report|keys|concrete)|^make |make [a-z-]+$|"
                         r"python3 benchmarks/|^mpirun|#SBATCH")
    found = []
    for block in re.findall(r"```[a-z]*\n(.*?)```", text, re.S):
        for line in block.replace("\\\n", " ").splitlines():
            line = " ".join(line.split())
            if pattern.search(line) and not line.startswith("#!"):
                found.append(line)
    prose = re.sub(r"```.*?```", "", text, flags=re.S)
    for code in re.findall(r"`([^`\n]+)`", prose):
        code = " ".join(code.split())
        if pattern.search(code):
            found.append(code)
    return found


def header_lines(path):
    head = []
    with open(path) as f:
        for line in f:
            if not line.startswith("#"):
                break
            head.append(line[1:].rstrip())
    return " ".join(head).replace("\\", " ")


def entry_for(command):
    """The first entry whose text the command holds (entries are listed most specific first where they overlap)."""
    return next((e for e in ENTRIES if e[0] in command), None)


def tests_named(source):
    names = set()
    for root, _, files in os.walk(os.path.join(source, "tests")):
        for f in files:
            if f.endswith(".cpp"):
                with open(os.path.join(root, f)) as s:
                    names.update(re.findall(r'TEST_CASE\("([^"]+)"', s.read()))
    return names


def execute(label, how, cli, source, build, scratch, mpi=True):
    argv = [a.format(cli=cli, src=source, build=build) for a in how["argv"]]
    if argv[0] == "mpirun" and not mpi:
        check(f"skipped: {label} (a build without MPI)", True)
        return None
    env = dict(os.environ, **how["env"])
    start = time.monotonic()
    p = subprocess.run(argv, cwd=scratch, env=env, capture_output=True, text=True, timeout=600)
    label += f", {time.monotonic() - start:.1f} s"
    if p.returncode != 0 and "built without the rigid-cell family" in p.stderr:
        check(f"skipped: {label} (a build without the rigid-cell family)", True)
        return p
    check(f"runs: {label} (as {' '.join(a.replace(source + '/', '').replace(build + '/', 'build/') for a in argv)})",
          p.returncode == 0, f"exit {p.returncode}: {p.stderr.strip()[-600:]}")
    return p


def main():
    cli, source = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    mpi = len(sys.argv) < 4 or sys.argv[3] == "mpi"
    build = os.path.dirname(cli)
    with open(os.path.join(source, "README.md")) as f:
        printed = readme_commands(f.read())
    known = tests_named(source)
    with open(os.path.join(source, "tests", "calibration_tension.cpp")) as f:
        calibration_list = f.read()
    used = set()
    with tempfile.TemporaryDirectory() as scratch:
        os.makedirs(os.path.join(scratch, "out"))
        for command in printed:
            e = entry_for(command)
            check(f"README's `{command[:90]}` is covered", e is not None, "add it to ENTRIES")
            if e is None or e[0] in used:
                continue
            used.add(e[0])
            how = e[1]
            if "argv" in how:
                execute(e[0], how, cli, source, build, scratch, mpi)
            elif "test" in how:
                check(f"`{e[0]}` is run by the test {how['test']} ({how['why']})", how["test"] in known)
        for pattern, _ in ENTRIES:
            check(f"entry `{pattern}` matches a command the README prints", pattern in used)

        scenes = os.path.join(source, "scenes")
        for name in sorted(os.listdir(scenes)):
            if not name.endswith(".toml"):
                continue
            head = header_lines(os.path.join(scenes, name))
            if re.search(r"mesocrack calibrate", head):
                if name in CALIBRATIONS_NOT_RUN:
                    check(f"{name}: its header's calibrate command is not run ({CALIBRATIONS_NOT_RUN[name]})", True)
                else:
                    check(f"{name}: its header's calibrate command is run by {HEADER_CALIBRATIONS}",
                          HEADER_CALIBRATIONS in known and f'"{name}"' in calibration_list)
            # The --set lines of a calibrate command are its own (run with it); the others are hints.
            hinted = "--set" in re.sub(r"mesocrack calibrate.*", "", head)
            check(f"{name}: every --set its header suggests is run", hinted == (name in HINTS),
                  "add its hints to HINTS" if hinted else "HINTS names a scene whose header suggests none")
            if name in SAME_MESOSTRUCTURE:
                other = SAME_MESOSTRUCTURE[name]
                with open(os.path.join(scenes, name), "rb") as a, open(os.path.join(scenes, other), "rb") as b:
                    same = tomllib.load(a).get("mesostructure") == tomllib.load(b).get("mesostructure")
                check(f"{name}: its [mesostructure] is {other}'s, where its hint runs", same)
                continue
            for value in HINTS.get(name, []):
                key = value.split("=")[0].split("[0].")[-1]
                check(f"{name}: the header names `{key}`", key in head)
                execute(f"{name} --set {value}", run(cli, "run", os.path.join(scenes, name), "-o",
                                                    f"out/hint_{name}.h5", "--set", value, *HINT_STEPS),
                        cli, source, build, scratch)
    failed = [r for r in results if not r[1]]
    for name, ok, detail in results:
        print(("ok   " if ok else "FAIL ") + name + ("" if ok or not detail else f": {detail}"))
    print(f"documented_commands: {len(results) - len(failed)} passed, {len(failed)} failed")
    return 1 if failed or not results else 0


if __name__ == "__main__":
    sys.exit(main())
