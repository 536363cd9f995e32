#!/usr/bin/env python3
"""The lock files of the separate workspaces agree with the root one.

Usage: .ci/lockfiles-agree.py

python/, ffi/, ffi/size-check/, nostd-check/, fuzz/ and firmware/ are workspaces of their own (their profiles must differ),
so each has its own Cargo.lock, and a `cargo update` in one does not move the others. A registry package that
the root Cargo.lock and a separate lock file both contain must be locked at the same version in both: what the
tests and the CLI exercise is what the wheel, the C library, the no_std proofs and the fuzzers link. A package
the root locks at several versions (two semver-incompatible majors) agrees when the other file's version is
one of them. To fix a failure, in the separate workspace:
    cargo update -p NAME@THEIR_VERSION --precise ROOT_VERSION
"""

import pathlib
import sys
import tomllib
from collections import defaultdict

ROOT = pathlib.Path(__file__).resolve().parent.parent
SEPARATE = ["python", "ffi", "ffi/size-check", "nostd-check", "fuzz", "firmware"]


def registry_versions(lock):
    """name -> set of locked versions, registry (and git) packages only: path packages are this repository's."""
    with open(lock, "rb") as f:
        data = tomllib.load(f)
    versions = defaultdict(set)
    for p in data.get("package", []):
        if "source" in p:
            versions[p["name"]].add(p["version"])
    return versions


def main():
    root = registry_versions(ROOT / "Cargo.lock")
    failures = 0
    for ws in SEPARATE:
        lock = ROOT / ws / "Cargo.lock"
        if not lock.exists():
            print(f"{ws}/Cargo.lock: none (nothing to compare)")
            continue
        other = registry_versions(lock)
        shared = sorted(n for n in other if n in root)
        bad = []
        for name in shared:
            for v in sorted(other[name] - root[name]):
                bad.append(f"  {name} {v} (root: {', '.join(sorted(root[name]))})")
        if bad:
            failures += len(bad)
            print(f"FAIL {ws}/Cargo.lock: {len(bad)} of {len(shared)} shared packages at other versions than the root:")
            print("\n".join(bad))
        else:
            print(f"ok   {ws}/Cargo.lock: {len(shared)} shared packages at the root's versions")
    if failures:
        sys.exit(1)


if __name__ == "__main__":
    main()
