#!/usr/bin/env bash
# Runs every check and test of cnets, installing first what the tests need on a fresh machine:
# the software Vulkan driver (lavapipe) for GPU tests, the Khronos glTF validator (npm) and the
# ezdxf DXF reader (pip) for file-format tests. CI runs exactly this script (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/install-test-deps.sh

# The software Vulkan driver prints a harmless warning without a private runtime directory.
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  export XDG_RUNTIME_DIR="$(mktemp -d)"
  chmod 700 "$XDG_RUNTIME_DIR"
fi
export WGPU_BACKEND="${WGPU_BACKEND:-vulkan}"
# A one-off build gains nothing from incremental caches; they would cost ~2 GB of disk.
export CARGO_INCREMENTAL="${CARGO_INCREMENTAL:-0}"
export PATH="$PWD/node_modules/.bin:$PATH"

echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy"
cargo clippy --workspace --all-targets -- -D warnings
echo "== cargo test"
cargo test --workspace
./scripts/test-python.sh
./scripts/test-web.sh
