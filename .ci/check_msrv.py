"""The dependency half of the rust-version check: every package a user's build of `diffraction`
compiles (the library's normal and build dependencies, with every feature on, at the versions of
Cargo.lock) declares a `rust-version` no newer than the crate's own.

What it catches: a dependency (or a lockfile update) that requires a newer Rust than the
crate's `rust-version`. What it does not: a dependency that declares no `rust-version` (listed,
not failed: nothing to compare), a declared value that is wrong, versions a user's own lockfile
resolves differently (Cargo's MSRV-aware resolver picks older ones for an older toolchain), and
anything about the crate's own code (clippy's `incompatible_msrv` covers std APIs; language
features and syntax need a build with the old toolchain).

Usage: python3 .ci/check_msrv.py [ROOT]   (exit 1 and the offenders on failure)
"""
import json
import os
import subprocess
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")


def version(v):
    """"1.82" or "1.82.0" -> (1, 82, 0)."""
    parts = [int(p) for p in v.split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


meta = json.loads(
    subprocess.run(
        ["cargo", "metadata", "--format-version", "1", "--all-features", "--locked"],
        cwd=root,
        check=True,
        capture_output=True,
        text=True,
    ).stdout
)
packages = {p["id"]: p for p in meta["packages"]}
nodes = {n["id"]: n for n in meta["resolve"]["nodes"]}
crate_id = meta["resolve"]["root"]
ours = packages[crate_id]["rust_version"]
if not ours:
    sys.exit("Cargo.toml declares no rust-version")

# Walk the dependency graph through normal and build edges only (dev-dependencies are not part
# of a user's build).
seen, todo = set(), [crate_id]
while todo:
    node = nodes[todo.pop()]
    for dep in node["deps"]:
        kinds = {k["kind"] for k in dep["dep_kinds"]}
        if kinds & {None, "build"} and dep["pkg"] not in seen:
            seen.add(dep["pkg"])
            todo.append(dep["pkg"])

newer, unknown = [], []
for pid in sorted(seen, key=lambda i: packages[i]["name"]):
    p = packages[pid]
    rv = p.get("rust_version")
    label = f'{p["name"]} {p["version"]}'
    if rv is None:
        unknown.append(label)
    elif version(rv) > version(ours):
        newer.append(f"{label} needs Rust {rv}")
    else:
        print(f"  {label}: rust-version {rv}")
for u in unknown:
    print(f"  {u}: declares no rust-version (not checked)")
if newer:
    print(f"dependencies newer than the crate's rust-version {ours}:")
    for n in newer:
        print("  " + n)
    sys.exit(1)
print(f"rust-version {ours}: {len(seen)} dependencies, none declares a newer Rust")
