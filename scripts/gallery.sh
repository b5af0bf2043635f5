#!/usr/bin/env bash
# Renders the gallery pictures (docs/gallery/*.png) from the graphs in graphs/ with `cnets render`,
# on whatever GPU adapter exists (the software Vulkan driver on machines without a GPU).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then
  export XDG_RUNTIME_DIR="$(mktemp -d)"
  chmod 700 "$XDG_RUNTIME_DIR"
fi
cargo build --release -q -p cnets
cnets=target/release/cnets
mkdir -p docs/gallery

# graph            view    colour      extra options
while read -r graph view color extra; do
  [ -z "$graph" ] && continue
  case "$graph" in \#*) continue ;; esac
  # shellcheck disable=SC2086
  "$cnets" render "graphs/$graph.ron" --png "docs/gallery/$graph.png" --size 960x540 \
    --view "$view" --color "$color" $extra
done <<'LIST'
torus-monge        iso     config      --hide apices
normalization      top     config      --hide apices
facade             iso     config      --hide apices
graph-to-apex      iso     config      --hide apices
support-layers     iso     config      --hide apices
parallel-transform iso     planarity   --hide apices
catamaran-hull     iso     plain       --hide apices
pedestrian-bridge  iso     config      --hide apices
tube-closure       iso     config      --hide apices
correction         top     config      --hide apices
corner-facade      iso     config      --hide apices
wall-canopy        iso     config      --hide apices
LIST
echo "gallery written to docs/gallery/"
