#!/usr/bin/env bash
# Builds cnets in the browser (docs/web.md) into OUT_DIR (default target/web): the editor compiled
# to wasm32 (crates/web, profile `web`), its JavaScript glue by wasm-bindgen, optionally shrunk by
# wasm-opt when it is installed, next to index.html. Serve the folder statically, e.g.
#   python3 -m http.server -d target/web 8000   → http://localhost:8000/?example=torus-monge
# Needs: rustup target add wasm32-unknown-unknown; installs wasm-bindgen-cli at the version of the
# wasm-bindgen crate in Cargo.lock when missing (cargo install, without --locked: its own lock file
# pins a webpki-roots the registry does not serve).
set -euo pipefail
cd "$(dirname "$0")/.."
OUT="${1:-target/web}"

if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
  echo "== adding the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/version = |"/, ""); print; exit }' Cargo.lock)
if [ -z "$version" ]; then
  echo "web.sh: no wasm-bindgen in Cargo.lock" >&2
  exit 1
fi
if [ "$(wasm-bindgen --version 2>/dev/null | awk '{print $2}')" != "$version" ]; then
  echo "== installing wasm-bindgen-cli $version"
  cargo install wasm-bindgen-cli --version "$version"
fi

echo "== cargo build (wasm32, profile web)"
cargo build -p cnets-web --target wasm32-unknown-unknown --profile web
wasm="${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/web/cnets_web.wasm"

mkdir -p "$OUT"
echo "== wasm-bindgen → $OUT"
wasm-bindgen "$wasm" --out-dir "$OUT" --target web --no-typescript
if command -v wasm-opt >/dev/null 2>&1; then
  echo "== wasm-opt -Os"
  wasm-opt -Os --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
    --enable-mutable-globals "$OUT/cnets_web_bg.wasm" -o "$OUT/cnets_web_bg.wasm.opt"
  mv "$OUT/cnets_web_bg.wasm.opt" "$OUT/cnets_web_bg.wasm"
fi
cp crates/web/static/index.html "$OUT/index.html"
raw=$(stat -c %s "$OUT/cnets_web_bg.wasm")
gz=$(gzip -9 -c "$OUT/cnets_web_bg.wasm" | wc -c)
echo "web.sh: $OUT ready: cnets_web_bg.wasm $raw bytes ($gz gzipped)"
