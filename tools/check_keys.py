#!/usr/bin/env python3
"""Only scene/ and the models' own key tables know the models' keys.

A model's keys are declared once, in its key table beside its Params (contact_models/<model>.cpp, the facet law's in
rigid_cell/facet_law.hpp). Anywhere else in the floors below and above scene/ (engine, contact_models' headers,
preprocess, io, rigid_cell, studies, app) a string literal that is a model key ("bond_modulus", "friction_angle",
"contacts[0].modulus=...") reads or writes keys behind the tables' back (a message may name a key for the user): studies set a model's parameters through its
Params and the scene's --set lines from the table (scene/model_registry.hpp). Tests, benchmarks and scenes write
scene files and may name keys.

Usage: check_keys.py SOURCE_DIR. Prints each offending literal as file:line and exits 1 if there is any.
"""
import pathlib
import re
import sys

TABLES = ["contact_models/*.cpp", "rigid_cell/facet_law.hpp"]  # the models' key tables: their keys are read here
CHECKED = ["engine", "contact_models", "preprocess", "io", "rigid_cell", "studies", "app"]

KEY = re.compile(r'\{\s*\.name\s*=\s*"(\w+)"|\{\.name = "(\w+)"')
STRING = re.compile(r'"((?:[^"\\\n]|\\.)*)"')


def code_only(text):
    """The text with // and /* */ comments blanked out (string literals kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            i = n if j < 0 else j + 2
        elif text[i] == '"':
            m = STRING.match(text, i)
            if not m:
                out.append(text[i])
                i += 1
                continue
            out.append(m.group(0))
            i = m.end()
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def model_keys(root):
    keys, files = set(), set()
    for pattern in TABLES:
        for f in root.glob(pattern):
            files.add(f)
            for m in KEY.finditer(f.read_text()):
                keys.add(m.group(1) or m.group(2))
    scattered = {k + suffix for k in keys for suffix in ("_std", "_weibull_shape")}
    return keys | scattered, files


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    keys, tables = model_keys(root)
    if not keys:
        print("check_keys: found no model keys in " + ", ".join(TABLES), file=sys.stderr)
        return 1
    bad = []
    for folder in CHECKED:
        for f in sorted((root / folder).rglob("*.[ch]pp")):
            if f in tables:
                continue
            text = code_only(f.read_text())
            for m in STRING.finditer(text):
                literal = m.group(1)
                # A key itself, a key path or a --set line; a message that names a key for the user is none.
                path = re.match(r"^[\w.\[\]]*?(\w+)(=|$)", literal)
                if literal in keys or "contacts[" in literal or (path and "." in literal and path.group(1) in keys):
                    line = text.count("\n", 0, m.start()) + 1
                    bad.append(f"{f.relative_to(root)}:{line}: \"{literal}\"")
    for b in bad:
        print(b)
    if bad:
        print(f"check_keys: {len(bad)} string(s) above name a model's key outside scene/ and the models' key tables",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
