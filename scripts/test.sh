#!/usr/bin/env bash
# Runs every check and test of cnets, installing what the tests need on a fresh machine while the
# first builds compile (scripts/install-test-deps.sh: lavapipe, xvfb, Chromium, the wasm32 target,
# the glTF validator, playwright-core, ezdxf, the Python test environment). Then fmt, clippy,
# cargo test, the Python package tests (scripts/test-python.sh) and the browser test
# (scripts/test-web.sh). CI runs exactly this script (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."

mkdir -p target
# The installs wait on the network, the first builds on the processors: they run side by side.
./scripts/install-test-deps.sh >target/install-test-deps.log 2>&1 &
installing=$!
wait_for_installs() {
  if ! wait "$installing"; then
    cat target/install-test-deps.log >&2
    echo "test.sh: installing the test tools failed (above)" >&2
    exit 1
  fi
  cat target/install-test-deps.log
}

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
# Clippy lints the workspace's crates while the test build compiles them: clippy-driver is cargo's
# workspace wrapper (what `cargo clippy` sets up, there in check mode), with the same lints and
# -D warnings as `cargo clippy --workspace --all-targets -- -D warnings`. The ~400 dependencies are
# then compiled once instead of once more in check mode (about 4 minutes on 2 cores). Every later
# cargo command of the Rust and Python steps keeps these variables, so nothing is rebuilt.
export RUSTC_WORKSPACE_WRAPPER="$(rustc --print sysroot)/bin/clippy-driver"
export CLIPPY_ARGS="-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__"
echo "== cargo clippy and the test build (clippy-driver as the workspace wrapper, -D warnings)"
cargo test --workspace --all-targets --no-run
wait_for_installs
echo "== cargo test"
cargo test --workspace
./scripts/test-limits.sh  # issue 27 §2: the memory cases under ulimit -v (target/debug/cnets)
# The test executables (~2.5 GB) are not used again: on a small disk the Python and wasm builds
# need the room (a CI run once stopped with "No space left on device" in the wasm build). The
# libraries stay, so the Python build reuses them. CNETS_KEEP_TESTS=1 keeps them.
if [ -z "${CNETS_KEEP_TESTS:-}" ]; then
  find target/debug/deps -maxdepth 1 -type f -perm -u+x ! -name '*.so' -delete
fi
# The site's wasm build (with wasm-bindgen-cli's install on a fresh machine) runs beside the Python
# step, at a lower priority, in its own target folder (the Python build holds target/'s lock).
# (Not linted: wasm-bindgen-cli's install would be linted as a workspace of its own.)
env -u RUSTC_WORKSPACE_WRAPPER -u CLIPPY_ARGS CARGO_TARGET_DIR="$PWD/target/web-build" \
  nice -n 10 ./scripts/web.sh target/web \
  >target/web-build.log 2>&1 &
building_site=$!
./scripts/test-python.sh
if ! wait "$building_site"; then
  cat target/web-build.log >&2
  echo "test.sh: the web build failed (above)" >&2
  exit 1
fi
cat target/web-build.log
CNETS_WEB_BUILT=1 ./scripts/test-web.sh
