"""The layer check of ARCHITECTURE.md: every top-level module of src/ sits in exactly one row of
its layer table, and no module imports one from a higher row.

The table is the one whose header starts with `| layer |`; its rows run from the top layer down,
and its second column names the layer's modules as `name.rs` or `name/` in backticks (anything
else in the cell, such as the files of a folder in parentheses, is ignored). A module's imports
are its `crate::x` paths, with names re-exported at the crate root (`crate::{Grating, Band}`)
resolved to the module that defines them through `src/lib.rs`'s `pub use` lines. Modules in one
layer may use each other (cycles are the business of `module_cycles.py`).

Usage: python3 .ci/check_layers.py [ROOT]   (exit 1 and a list of the violations on failure)
"""
import os
import re
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
src = os.path.join(root, "src")


def modules():
    """Top-level module name -> its source files."""
    out = {}
    for e in sorted(os.listdir(src)):
        p = os.path.join(src, e)
        if e == "lib.rs":
            continue
        if e.endswith(".rs"):
            out.setdefault(e[:-3], []).append(p)
        elif os.path.isdir(p):
            for r, _, fs in os.walk(p):
                out.setdefault(e, []).extend(os.path.join(r, f) for f in fs if f.endswith(".rs"))
    return out


def layers():
    """Module name -> (row index, layer name), from ARCHITECTURE.md's table."""
    text = open(os.path.join(root, "ARCHITECTURE.md"), encoding="utf-8").read().splitlines()
    start = next((i for i, l in enumerate(text) if l.startswith("| layer |")), None)
    if start is None:
        sys.exit("ARCHITECTURE.md has no table starting with `| layer |`")
    out, row = {}, 0
    for line in text[start + 2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        name, mods = cells[0], cells[1]
        # Top-level modules only: drop what is in parentheses (a folder's files).
        depth, kept = 0, []
        for ch in mods:
            depth += ch == "("
            if depth == 0:
                kept.append(ch)
            depth -= ch == ")"
        for tok in re.findall(r"`([a-z_0-9]+)(?:\.rs|/)`", "".join(kept)):
            if tok in out and out[tok][0] != row:
                sys.exit(f"ARCHITECTURE.md lists `{tok}` in two layers")
            out[tok] = (row, name)
        row += 1
    return out


def reexports():
    """Name re-exported at the crate root -> the top-level module that defines it."""
    text = open(os.path.join(src, "lib.rs"), encoding="utf-8").read()
    text = re.sub(r"//[^\n]*", "", text)
    out = {}
    for m in re.finditer(r"pub use (\w+)::(\{[^}]*\}|\w+)\s*;", text, re.S):
        module, names = m.group(1), m.group(2)
        for n in re.findall(r"\b(\w+)\b", names):
            out[n] = module
    return out


def imports(path, names, mods):
    """The top-level modules a file refers to through `crate::`."""
    code = "\n".join(
        l for l in open(path, encoding="utf-8").read().splitlines() if not l.lstrip().startswith("//")
    )
    found = set()

    def note(tok):
        if tok in mods:
            found.add(tok)
        elif tok in names:
            found.add(names[tok])

    # `crate::x::...` and `crate::Name`: the first segment.
    for m in re.finditer(r"crate::(\w+)", code):
        note(m.group(1))
    # `crate::{a::b, Name, ...}`: the first segment of every item.
    for m in re.finditer(r"crate::\{([^}]*)\}", code):
        for item in m.group(1).split(","):
            note(item.strip().split("::")[0].strip())
    return found


def main():
    mods, table, names = modules(), layers(), reexports()
    problems = []
    for m in mods:
        if m not in table:
            problems.append(f"src module `{m}` is missing from ARCHITECTURE.md's layer table")
    for m in table:
        if m not in mods:
            problems.append(f"ARCHITECTURE.md lists `{m}`, which is not a module of src/")
    for m, files in sorted(mods.items()):
        if m not in table:
            continue
        row, layer = table[m]
        for f in files:
            for t in sorted(imports(f, names, mods)):
                if t == m or t not in table:
                    continue
                trow, tlayer = table[t]
                if trow < row:
                    problems.append(
                        f"{os.path.relpath(f, root)}: `{m}` ({layer}) imports `{t}` ({tlayer}), a higher layer"
                    )
    if problems:
        print("\n".join(problems))
        sys.exit(1)
    print(f"layers: {len(mods)} modules in {len(set(r for r, _ in table.values()))} layers, no upward import")


main()
