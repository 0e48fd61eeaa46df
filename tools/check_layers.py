#!/usr/bin/env python3
"""The include rule of the floors (docs/ARCHITECTURE.md): a file includes only from its own floor or the floors
below it, and the engine and the contact models include no TOML or HDF5. Prints every include that breaks the
rule as FILE:LINE: what, and exits 1 if there is any. Usage: check_layers.py [SOURCE_DIR]."""
import pathlib
import re
import sys

# Each folder and the folders it may include from (its own floor first). Tests and benchmarks stand on top.
BELOW = {
    "engine": ["engine"],
    "contact_models": ["contact_models", "engine"],
    "preprocess": ["preprocess", "contact_models", "engine"],
    "io": ["io", "engine"],
    "rigid_cell": ["rigid_cell", "engine"],
    "scene": ["scene", "preprocess", "io", "rigid_cell", "contact_models", "engine"],
    "studies": ["studies", "scene", "preprocess", "io", "rigid_cell", "contact_models", "engine"],
    "app": ["app", "studies", "scene", "preprocess", "io", "rigid_cell", "contact_models", "engine"],
}
# Library headers a floor must not see: the force laws, the kernel, the preprocessor and the rigid cells know
# nothing of scene files, HDF5 or the command line.
NO_FILES_OR_KEYS = [r"toml", r"hdf5\.h", r"H5\w*\.h", r"CLI/"]
FORBIDDEN = {floor: NO_FILES_OR_KEYS for floor in ("engine", "contact_models", "preprocess", "rigid_cell")}
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def check(root: pathlib.Path):
    problems = []
    for folder, allowed in BELOW.items():
        base = root / folder
        if not base.is_dir():
            continue
        for path in sorted(base.rglob("*")):
            if path.suffix not in (".hpp", ".cpp", ".h"):
                continue
            rel = path.relative_to(root)
            for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                kind, target = m.groups()
                top = target.split("/")[0]
                if kind == '"' and top in BELOW and top not in allowed:
                    problems.append(f"{rel}:{n}: includes {target}, from the floor '{top}' above '{folder}' "
                                    f"(allowed: {', '.join(allowed)})")
                for pattern in FORBIDDEN.get(folder, []):
                    if re.match(pattern, target):
                        problems.append(f"{rel}:{n}: includes <{target}>: '{folder}' must not depend on it")
    return problems


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    problems = check(root)
    for p in problems:
        print(p, file=sys.stderr)
    if problems:
        print(f"check_layers: {len(problems)} include(s) break the rule of the floors (docs/ARCHITECTURE.md)",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
