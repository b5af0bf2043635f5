#!/usr/bin/env bash
# Builds the cnets Python package (python/: maturin + PyO3) into a virtual environment and runs its
# pytest suite (python/tests: the API, Rhino files, the Hops server, Dask sweeps, the shipped
# library, the docs' code blocks). Called at the end of scripts/test.sh; runs on its own too. The
# venv lives in target/pyenv; the Rust build goes to the workspace's target/ (CARGO_TARGET_DIR),
# so a second run reuses it. The Windows wheel has its own script: scripts/windows-wheel.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}"
venv="$CARGO_TARGET_DIR/pyenv"
python="${PYTHON:-python3}"
if [ ! -x "$venv/bin/python" ]; then
  "$python" -m venv "$venv"
fi
pip=("$venv/bin/python" -m pip --disable-pip-version-check -q)
"${pip[@]}" install -r scripts/requirements-python.txt
# The tests build with cargo's dev profile (CNETS_PYTHON_PROFILE=release for the release build):
# it reuses what `cargo test --workspace` compiled into target/debug, where a cold release build
# took 19 min on the shared 2-core machine (docs/python.md). A user's plain `pip install ./python`
# builds in release.
profile="${CNETS_PYTHON_PROFILE:-dev}"
started=$SECONDS
"${pip[@]}" install --force-reinstall --no-deps \
  --config-settings=build-args="--profile $profile" "./python[rhino]"
# After the test build, every dependency is reused (python/Cargo.toml turns on the features the
# workspace unifies; scripts/feature-drift.sh checks it): only the PyO3 crates and the package
# itself are compiled here.
echo "test-python.sh: the package built and installed in $((SECONDS - started)) s (profile $profile)"
# The library's command-line tests and the docs' `cnets` lines run the cnets binary: the one
# `cargo test --workspace` built (scripts/test.sh), else it is built here (CNETS_BIN names another).
if [ -z "${CNETS_BIN:-}" ]; then
  export CNETS_BIN="$CARGO_TARGET_DIR/debug/cnets"
  if [ ! -x "$CNETS_BIN" ]; then
    cargo build -q -p cnets
  fi
fi
# pytest (not `python -m pytest`): the source folder python/cnets must not shadow the installed
# package. The venv's bin first on PATH: the docs' `pip install` lines build metadata with its
# maturin.
export CNETS_PYTHON_PROFILE="$profile"
PATH="$venv/bin:$PATH" "$venv/bin/pytest" -q python/tests
