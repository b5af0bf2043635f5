#!/usr/bin/env bash
# Builds cnets in the browser (docs/web.md) into OUT_DIR (default target/web): the editor compiled
# to wasm32 (crates/web, profile `web`), its JavaScript glue by wasm-bindgen, shrunk by wasm-opt
# when it is installed (Debian's `binaryen`), next to index.html and worker.js, with a gzip (.gz)
# and a brotli (.br) copy of each file beside it for servers that send them. Serve the folder
# statically, e.g.
#   python3 scripts/serve.py target/web 8000   → http://localhost:8000/?example=torus-monge
# (it sends the .br/.gz copies with Content-Encoding: about 4 MB instead of 17 MB).
# Needs: the wasm32-unknown-unknown target (added when missing). The glue is written by
# crates/web/bindgen, wasm-bindgen's library at the version Cargo.lock pins (no `cargo install
# wasm-bindgen-cli`). CNETS_WASM_OPT=0 skips wasm-opt (a quicker build while working on the page;
# the test command tests the site as it ships, shrunk). Brotli: the `brotli` command, else Node's zlib.
set -euo pipefail
cd "$(dirname "$0")/.."
OUT="${1:-target/web}"

if ! rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
  echo "== adding the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

# The glue writer (crates/web/bindgen, a workspace of its own) must run wasm-bindgen's library at
# the version of the wasm-bindgen crate the page is compiled with.
lock_version() {
  awk -v name="$1" '$0 == "name = \"" name "\"" { getline; gsub(/version = |"/, ""); print; exit }' "$2"
}
page_version=$(lock_version wasm-bindgen Cargo.lock)
glue_version=$(lock_version wasm-bindgen-cli-support crates/web/bindgen/Cargo.lock)
if [ -z "$page_version" ] || [ "$page_version" != "$glue_version" ]; then
  echo "web.sh: wasm-bindgen ${page_version:-missing} in Cargo.lock, but crates/web/bindgen" \
    "locks wasm-bindgen-cli-support ${glue_version:-missing}: update its Cargo.toml and lock" >&2
  exit 1
fi
echo "== cargo build (the glue writer, crates/web/bindgen; linted by clippy as it compiles)"
RUSTC_WORKSPACE_WRAPPER="$(rustc --print sysroot)/bin/clippy-driver" \
  CLIPPY_ARGS="-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__" \
  cargo build -q --locked --manifest-path crates/web/bindgen/Cargo.toml
bindgen="${CARGO_TARGET_DIR:-crates/web/bindgen/target}/debug/cnets-web-bindgen"

echo "== cargo build (wasm32, profile web)"
cargo build -p cnets-web --target wasm32-unknown-unknown --profile web
wasm="${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/web/cnets_web.wasm"

mkdir -p "$OUT"
bytes() { stat -c %s "$1"; }
# wasm-opt runs on rustc's output, before wasm-bindgen: binaryen 108 (Debian 12) rewrites the
# externref table wasm-bindgen adds into one the browser refuses at start-up ("function-typed
# object must be null"), even with no passes; before wasm-bindgen there is no such table.
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
elif [ "${CNETS_WASM_OPT:-1}" = 0 ]; then
  echo "web.sh: CNETS_WASM_OPT=0: the wasm is not shrunk"
else
  echo "web.sh: wasm-opt not installed (Debian: apt-get install binaryen): the wasm is not shrunk"
fi
echo "== wasm-bindgen → $OUT"
"$bindgen" "$wasm" "$OUT"
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
