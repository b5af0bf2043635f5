#!/usr/bin/env bash
# Builds cnets in the browser (docs/web.md) into OUT_DIR (default target/web): the editor compiled
# to wasm32 (crates/web, profile `web`), its JavaScript glue by wasm-bindgen, shrunk by wasm-opt
# when it is installed (Debian's `binaryen`), next to index.html and worker.js, with a gzip (.gz)
# and a brotli (.br) copy of each file beside it for servers that send them. Serve the folder
# statically, e.g.
#   python3 -m http.server -d target/web 8000   → http://localhost:8000/?example=torus-monge
# Needs: rustup target add wasm32-unknown-unknown; installs wasm-bindgen-cli at the version of the
# wasm-bindgen crate in Cargo.lock when missing (cargo install, without --locked: its own lock file
# pins a webpki-roots the registry does not serve). Brotli: the `brotli` command, else Node's zlib.
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
bytes() { stat -c %s "$1"; }
# wasm-opt runs on rustc's output, before wasm-bindgen: binaryen 108 (Debian 12) rewrites the
# externref table wasm-bindgen adds into one the browser refuses at start-up ("function-typed
# object must be null"), even with no passes; before wasm-bindgen there is no such table.
# CNETS_WASM_OPT=0 skips it (a quicker build while working on the page).
if [ "${CNETS_WASM_OPT:-1}" != 0 ] && command -v wasm-opt >/dev/null 2>&1; then
  # The features rustc's wasm32 target turns on (binaryen 108 needs them named).
  echo "== wasm-opt -Os ($(wasm-opt --version))"
  started=$(date +%s)
  optimized="$(dirname "$wasm")/opt"
  mkdir -p "$optimized"
  wasm-opt -Os --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
    --enable-mutable-globals --enable-reference-types --enable-multivalue \
    "$wasm" -o "$optimized/cnets_web.wasm"
  echo "wasm-opt: $(bytes "$wasm") → $(bytes "$optimized/cnets_web.wasm") bytes in $(( $(date +%s) - started )) s"
  wasm="$optimized/cnets_web.wasm"
else
  echo "web.sh: wasm-opt not installed (Debian: apt-get install binaryen): the wasm is not shrunk"
fi
echo "== wasm-bindgen → $OUT"
wasm-bindgen "$wasm" --out-dir "$OUT" --target web --no-typescript
cp crates/web/static/index.html crates/web/static/worker.js "$OUT/"

# Compressed copies beside each file (docs/web.md: how to serve them).
echo "== gzip and brotli copies"
files=("$OUT/index.html" "$OUT/worker.js" "$OUT/cnets_web.js" "$OUT/cnets_web_bg.wasm")
for f in "${files[@]}"; do
  gzip -9 -n -k -f "$f"
  rm -f "$f.br"
  if command -v brotli >/dev/null 2>&1; then
    brotli -q 11 -f -o "$f.br" "$f"
  elif command -v node >/dev/null 2>&1; then
    node -e '
      const fs = require("fs"), zlib = require("zlib");
      const [src, dst] = process.argv.slice(1);
      const q = zlib.constants.BROTLI_PARAM_QUALITY, size = zlib.constants.BROTLI_PARAM_SIZE_HINT;
      fs.writeFileSync(dst, zlib.brotliCompressSync(fs.readFileSync(src),
        { params: { [q]: 11, [size]: fs.statSync(src).size } }));' "$f" "$f.br"
  fi
done
wasm_file="$OUT/cnets_web_bg.wasm"
br="no brotli copy"
[ -f "$wasm_file.br" ] && br="$(bytes "$wasm_file.br") brotli"
echo "web.sh: $OUT ready: cnets_web_bg.wasm $(bytes "$wasm_file") bytes," \
  "$(bytes "$wasm_file.gz") gzipped, $br"
