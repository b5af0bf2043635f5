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
# target/install-test-deps.status holds its exit status once it is done (the site's build waits
# for it).
rm -f target/install-test-deps.status
(
  status=0
  ./scripts/install-test-deps.sh >target/install-test-deps.log 2>&1 || status=$?
  echo "$status" >target/install-test-deps.status
  exit "$status"
) &
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
# The property tests draw their random inputs from one fixed seed here, so the test command gives
# the same answer on every run: a new seed on every CI run once turned a rare input into a red CI
# that had nothing to do with the change. New inputs are explored by scripts/test-explore.sh
# (fresh seeds, more cases), run before every stop; what it finds is kept in the tests.
export PROPTEST_RNG_SEED="${PROPTEST_RNG_SEED:-20261205}"

echo "== cargo fmt --check"
cargo fmt --all -- --check
rustfmt --check --edition 2024 crates/web/bindgen/src/main.rs  # a workspace of its own

# The site's wasm build (and its glue writer, crates/web/bindgen) starts as soon as the installs
# are done (it needs the wasm32 target and wasm-opt), in its own target folder, at the lowest
# priority: it takes the processor time the test build, the tests and the Python step leave (a
# test binary's link holds one core, a window test waits on the software GPU), which cut about 10
# minutes of waiting for it at the end. The tests' timed assertions keep their margins beside it
# (issue 30: the suite passes beside another build). It skips wasm-opt -Os (CNETS_WASM_OPT=0:
# 190 s of processor time, which kept the test command over 30 minutes on 2 cores); the site as it
# ships, shrunk, is tested by `./scripts/test-web.sh` run on its own, before every stop.
# It runs in a process group of its own (setsid), stopped with the script if a step fails first.
CARGO_TARGET_DIR="$PWD/target/web-build" setsid bash -c '
  while [ ! -e target/install-test-deps.status ]; do sleep 2; done
  if [ "$(cat target/install-test-deps.status)" != 0 ]; then
    echo "test.sh: the installs failed; no web build"
    exit 1
  fi
  CNETS_WASM_OPT=0 exec nice -n 19 ./scripts/web.sh target/web
' >target/web-build.log 2>&1 &
building_site=$!
trap 'kill -- -"$building_site" 2>/dev/null || true' EXIT
# Clippy lints the workspace's crates while the test build compiles them: clippy-driver is cargo's
# workspace wrapper (what `cargo clippy` sets up, there in check mode), with the same lints and
# -D warnings as `cargo clippy --workspace --all-targets -- -D warnings`. The ~400 dependencies are
# then compiled once instead of once more in check mode (about 4 minutes on 2 cores). Every later
# cargo command of the Rust and Python steps keeps these variables, so nothing is rebuilt.
export RUSTC_WORKSPACE_WRAPPER="$(rustc --print sysroot)/bin/clippy-driver"
export CLIPPY_ARGS="-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__"
# The editor's test kit (feature `drivers`: the benchmarks and scripted sessions its window tests
# play) is built for the tests only; the release editor leaves it out.
tests=(--workspace --features cnets-editor/drivers)
echo "== cargo clippy and the test build (clippy-driver as the workspace wrapper, -D warnings)"
cargo test "${tests[@]}" --all-targets --no-run
wait_for_installs
echo "== cargo test"
rm -f target/tmp/skipped-tests.txt
cargo test "${tests[@]}"
# A window test that could not be played says why here (its own output is hidden when it passes).
cat target/tmp/skipped-tests.txt 2>/dev/null || true
./scripts/test-limits.sh  # issue 27 §2: the memory cases under ulimit -v (target/debug/cnets)
# The test executables (1.2 GB: one integration-test binary a crate) are not used again: on a small disk the Python and wasm builds
# need the room (a CI run once stopped with "No space left on device" in the wasm build). The
# libraries stay, so the Python build reuses them. CNETS_KEEP_TESTS=1 keeps them.
if [ -z "${CNETS_KEEP_TESTS:-}" ]; then
  find target/debug/deps -maxdepth 1 -type f -perm -u+x ! -name '*.so' -delete
fi
if ! wait "$building_site"; then
  cat target/web-build.log >&2
  echo "test.sh: the web build failed (above)" >&2
  exit 1
fi
cat target/web-build.log
# The Python step (its build of the package is mostly compiling) and the browser test (Chromium
# waits on its software GPU) run side by side: about a minute less than one after the other. The
# Python step's output follows the browser test's.
./scripts/test-python.sh >target/test-python.log 2>&1 &
python_step=$!
trap 'kill -- -"$building_site" 2>/dev/null || true; kill "$python_step" 2>/dev/null || true' EXIT
web_status=0
CNETS_WEB_BUILT=1 ./scripts/test-web.sh || web_status=$?
python_status=0
wait "$python_step" || python_status=$?
echo "== Python package tests (scripts/test-python.sh, beside the browser test)"
cat target/test-python.log
if [ "$python_status" != 0 ] || [ "$web_status" != 0 ]; then
  echo "test.sh: failed: the Python step (exit $python_status), the browser test (exit $web_status)" >&2
  exit 1
fi
