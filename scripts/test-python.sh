#!/usr/bin/env bash
# Builds the cnets Python package (python/: maturin + PyO3) into a virtual environment and runs its
# pytest suite (python/tests: the API, Rhino files, the Hops server, Dask sweeps). Called at the end
# of scripts/test.sh; runs on its own too. The venv lives in target/pyenv; the Rust build goes to
# the workspace's target/ (CARGO_TARGET_DIR), so a second run reuses it.
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
# The tests build with the `pytest` profile (release with thin local optimisation, see
# Cargo.toml); a user's plain `pip install ./python` builds with maturin's default (release).
"${pip[@]}" install --force-reinstall --no-deps \
  --config-settings=build-args="--profile pytest" "./python[rhino]"
cd python
"$venv/bin/python" -m pytest -q tests
