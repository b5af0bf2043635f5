#!/usr/bin/env bash
# Runs the real cnets-editor window under Xvfb on the default graph, takes an in-app screenshot
# (egui ViewportCommand::Screenshot) and checks that it is not blank (the editor exits non-zero
# when the picture has too few colours or an empty 3D view).
#
#   scripts/editor-screenshot.sh [OUT.png] [GRAPH.ron]
#
# Needs xvfb-run (apt: xvfb) and a Vulkan driver (apt: mesa-vulkan-drivers for the software
# rasterizer); scripts/install-test-deps.sh installs both.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/editor-screenshot.png}"
graph="${2:-}"
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  export XDG_RUNTIME_DIR="$(mktemp -d)"
  chmod 700 "$XDG_RUNTIME_DIR"
fi
export WGPU_BACKEND="${WGPU_BACKEND:-vulkan}"
# Keep the designer's own recent files and recovery file out of it.
export CNETS_EDITOR_HOME="${CNETS_EDITOR_HOME:-$(mktemp -d)}"
cargo build -q -p cnets-editor
mkdir -p "$(dirname "$out")"
xvfb-run -a -s "-screen 0 1600x1000x24" target/debug/cnets-editor ${graph:+"$graph"} \
  --screenshot "$out" --quit-after-frames 10 --size 1400x860
echo "screenshot: $out"
