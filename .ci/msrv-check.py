#!/usr/bin/env python3
"""The declared `rust-version` is true: no workspace crate declares one below the highest `rust-version` of the
packages in its workspace's locked dependency tree.

Usage: .ci/msrv-check.py [WORKSPACE_DIR ...]   (default: the root workspace, python/, ffi/)

For each workspace it runs `cargo metadata --format-version 1 --locked --all-features` (so the lock file must be
up to date, and optional dependencies count), walks the resolve graph from the workspace members over every
dependency kind and platform, and takes the highest `rust_version` found. Each member that declares a
`rust-version` below it is a failure; one that declares none is listed.
"""

import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
DEFAULT = [".", "python", "ffi"]


def version_key(v):
    """'1.89' -> (1, 89, 0); '1.74.1' -> (1, 74, 1)."""
    parts = [int(p) for p in v.split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


def check(workspace):
    manifest = ROOT / workspace / "Cargo.toml"
    out = subprocess.run(
        ["cargo", "metadata", "--format-version", "1", "--locked", "--all-features", "--manifest-path",
         str(manifest)],
        check=True, stdout=subprocess.PIPE, text=True,
    ).stdout
    meta = json.loads(out)
    packages = {p["id"]: p for p in meta["packages"]}
    members = set(meta["workspace_members"])
    nodes = {n["id"]: n for n in meta["resolve"]["nodes"]}

    # Everything reachable from the members: the locked tree this workspace builds (all targets, all platforms).
    seen, stack = set(), list(members)
    while stack:
        pid = stack.pop()
        if pid in seen:
            continue
        seen.add(pid)
        stack.extend(d["pkg"] for d in nodes[pid]["deps"])

    deps = [packages[p] for p in seen - members if packages[p].get("rust_version")]
    if not deps:
        print(f"{workspace}: no dependency declares a rust-version")
        return True
    # On a tie, name a registry package (the cause) rather than one of this repository's path crates.
    top = max(deps, key=lambda p: (version_key(p["rust_version"]), p.get("source") is not None))
    floor = top["rust_version"]
    print(f"{workspace}: highest rust-version in the locked tree: {floor} ({top['name']} {top['version']})")

    ok = True
    for pid in sorted(members, key=lambda p: packages[p]["name"]):
        p = packages[pid]
        declared = p.get("rust_version")
        if declared is None:
            print(f"  {p['name']}: no rust-version declared")
        elif version_key(declared) < version_key(floor):
            print(f"  FAIL {p['name']}: declares rust-version {declared}, below {floor} "
                  f"({top['name']} {top['version']} needs it); raise it or pin the dependency")
            ok = False
        else:
            print(f"  ok   {p['name']}: rust-version {declared}")
    return ok


def main():
    workspaces = sys.argv[1:] or DEFAULT
    results = [check(w) for w in workspaces]
    if not all(results):
        sys.exit(1)


if __name__ == "__main__":
    main()
