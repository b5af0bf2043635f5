#!/usr/bin/env bash
# Lists the dependencies the Python step's build (the cnets-python package alone, as maturin builds
# it) would compile with other features or settings than the test build
# (`cargo test --workspace --all-targets`), each such one compiled a second time by the test
# command. python/Cargo.toml turns the missing features on; run this after changing dependencies
# and add what it lists there. Uses cargo's unit graph (unstable, hence RUSTC_BOOTSTRAP); builds
# nothing. Exit 1 when something differs.
set -euo pipefail
cd "$(dirname "$0")/.."
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
RUSTC_BOOTSTRAP=1 cargo test -q --workspace --features cnets-editor/drivers --all-targets --no-run -Z unstable-options --unit-graph >"$tmp/workspace.json"
RUSTC_BOOTSTRAP=1 cargo build -q -p cnets-python --lib -Z unstable-options --unit-graph >"$tmp/python.json"
python3 - "$tmp/workspace.json" "$tmp/python.json" <<'PY'
import json, sys

def units(path):
    """Every dependency unit: (package, target, mode, host) -> the set of (features, profile)
    built. Host units (procedural macros, build scripts and what they use) are told apart from
    the target's: in a build for the machine itself both share target/debug, and a host unit
    with the same features as a target one does not make that one fresh."""
    graph = json.load(open(path))
    all_units = graph["units"]
    host = [False] * len(all_units)
    seen = set()
    stack = [(root, False) for root in graph["roots"]]
    while stack:
        index, is_host = stack.pop()
        unit = all_units[index]
        is_host = is_host or "proc-macro" in unit["target"]["kind"]
        if (index, is_host) in seen:
            continue
        seen.add((index, is_host))
        host[index] = host[index] or is_host
        builds = "custom-build" in unit["target"]["kind"]
        for dep in unit["dependencies"]:
            stack.append((dep["index"], is_host or builds))
    out = {}
    for index, is_host in seen:
        unit = all_units[index]
        package = unit["pkg_id"].split("#")[-1]
        if package.startswith("cnets-python"):
            continue
        key = (package, unit["target"]["name"], unit["mode"], is_host)
        # The profile's name is not part of an artifact's hash (dev and test share target/debug).
        settings = {k: v for k, v in unit["profile"].items() if k != "name"}
        profile = json.dumps(settings, sort_keys=True)
        out.setdefault(key, set()).add((tuple(unit["features"]), profile))
    return out

workspace, python = units(sys.argv[1]), units(sys.argv[2])
drift = 0
for key, built in sorted(python.items()):
    for features, profile in built:
        if (features, profile) not in workspace.get(key, set()):
            drift += 1
            host = ", host" if key[3] else ""
            seen = workspace.get(key, set())
            if any(f == features for f, _ in seen):
                print(f"{key[0]} ({key[1]}, {key[2]}{host}): other profile settings: {profile}")
                continue
            print(f"{key[0]} ({key[1]}, {key[2]}{host}): the Python build has features {list(features)}; "
                  f"the test build {sorted(set(f for f, _ in seen)) or 'does not build it'}")
if drift:
    print(f"feature-drift.sh: {drift} units differ: the Python step compiles them again")
    sys.exit(1)
print("feature-drift.sh: the Python step's build reuses every dependency of the test build")
PY
