#!/usr/bin/env bash
# Installs what the tests need, when it is missing: lavapipe, xvfb, Chromium and wasm-opt (apt), the wasm32
# target (rustup), gltf-validator and playwright-core (npm, into ./node_modules), ezdxf (pip, user
# site) and the Python package tests' virtual environment (target/pyenv, its requirements from
# scripts/requirements-python.txt). Uses sudo when not root; says what to install otherwise.
# scripts/test.sh runs it in the background while the first builds compile: it waits on the
# network, they on the processors.
set -euo pipefail
cd "$(dirname "$0")/.."

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@"; else
    echo "install-test-deps: need root to run: $*" >&2; return 1; fi
}

if ! ls /usr/share/vulkan/icd.d/lvp_icd*.json >/dev/null 2>&1; then
  echo "== installing the software Vulkan driver (mesa-vulkan-drivers, libvulkan1)"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq mesa-vulkan-drivers libvulkan1 >/dev/null
fi

if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "== installing a virtual X server for the editor's window test (xvfb, xauth)"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq xvfb xauth >/dev/null
fi

if [ ! -x /usr/bin/chromium ]; then
  echo "== installing Chromium for the browser test (apt)"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq chromium >/dev/null
fi

if ! command -v wasm-opt >/dev/null 2>&1; then
  # The site is tested as it ships: shrunk by wasm-opt (docs/web.md).
  echo "== installing wasm-opt for the web build (apt: binaryen)"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq binaryen >/dev/null
fi

if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
  echo "== adding the wasm32-unknown-unknown target (the web build)"
  rustup target add wasm32-unknown-unknown
fi

if [ -f package.json ] && [ ! -d node_modules/playwright-core ]; then
  echo "== installing npm test tools (package.json)"
  npm ci --silent --no-audit --no-fund
fi

if [ -f scripts/requirements-test.txt ]; then
  if ! python3 -c "import sys; import importlib; [importlib.import_module(l.split('=')[0].strip()) for l in open('scripts/requirements-test.txt') if l.strip() and not l.startswith('#')]" 2>/dev/null; then
    echo "== installing Python test tools (scripts/requirements-test.txt)"
    python3 -m pip install --quiet --user -r scripts/requirements-test.txt || python3 -m pip install --quiet -r scripts/requirements-test.txt
  fi
fi

# The Python package tests' environment (scripts/test-python.sh builds the package into it).
venv="${CARGO_TARGET_DIR:-$PWD/target}/pyenv"
if [ ! -x "$venv/bin/python" ]; then
  echo "== creating the Python test environment ($venv)"
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip --disable-pip-version-check -q install -r scripts/requirements-python.txt
