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
RUSTC_BOOTSTRAP=1 cargo test -q --workspace --all-targets --no-run -Z unstable-options --unit-graph >"$tmp/workspace.json"
RUSTC_BOOTSTRAP=1 cargo build -q -p cnets-python --lib -Z unstable-options --unit-graph >"$tmp/python.json"
python3 - "$tmp/workspace.json" "$tmp/python.json" <<'PY'
import json, sys

def units(path):
    """Every dependency unit: (package, target, mode) -> the set of (features, profile) built."""
    out = {}
    for unit in json.load(open(path))["units"]:
        package = unit["pkg_id"].split("#")[-1]
        if package.startswith("cnets-python"):
            continue
        key = (package, unit["target"]["name"], unit["mode"])
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
            seen = workspace.get(key, set())
            if any(f == features for f, _ in seen):
                print(f"{key[0]} ({key[1]}, {key[2]}): other profile settings: {profile}")
                continue
            print(f"{key[0]} ({key[1]}, {key[2]}): the Python build has features {list(features)}; "
                  f"the test build {sorted(set(f for f, _ in seen)) or 'does not build it'}")
if drift:
    print(f"feature-drift.sh: {drift} units differ: the Python step compiles them again")
    sys.exit(1)
print("feature-drift.sh: the Python step's build reuses every dependency of the test build")
PY
