#!/usr/bin/env bash
# The browser test of cnets in the browser (docs/web.md): installs Debian's Chromium and the npm
# test tools when missing, builds the site with scripts/web.sh, serves it with scripts/serve.py
# (the compressed copies, as a user serves it) on a free loopback port and runs
# tests/web/browser.test.mjs (playwright-core driving
# headless Chromium on software WebGL2). Screenshots and figures go to target/web-test/.
set -euo pipefail
cd "$(dirname "$0")/.."

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@"; else
    echo "test-web: need root to run: $*" >&2; return 1; fi
}
if [ ! -x /usr/bin/chromium ]; then
  echo "== installing Chromium (apt)"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq chromium >/dev/null
fi
if [ ! -d node_modules/playwright-core ]; then
  echo "== installing npm test tools (package.json)"
  npm ci --silent --no-audit --no-fund
fi

site="${CNETS_WEB_OUT:-target/web}"
# scripts/test.sh builds the site beside the Python tests and says so (CNETS_WEB_BUILT=1).
if [ -z "${CNETS_WEB_BUILT:-}" ]; then
  ./scripts/web.sh "$site"
fi

# Port 0: the server takes a free port and names it ("Serving HTTP on 127.0.0.1 port N"), so no
# other process (the Python step's servers run beside) can take a probed one before it binds.
mkdir -p target
python3 -u scripts/serve.py "$site" 0 >target/web-server.log 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true' EXIT
port=""
for _ in $(seq 600); do
  port=$(sed -n 's/^Serving HTTP on .* port \([0-9]*\) .*/\1/p' target/web-server.log | head -1)
  if [ -n "$port" ] &&
     python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/index.html')" 2>/dev/null; then
    break
  fi
  port=""
  kill -0 "$server" 2>/dev/null || break
  sleep 0.1
done
if [ -z "$port" ]; then
  cat target/web-server.log >&2
  echo "test-web.sh: the site's server did not start (above)" >&2
  exit 1
fi

echo "== browser test (headless Chromium, WebGL2 on SwiftShader)"
node tests/web/browser.test.mjs "http://127.0.0.1:$port" target/web-test
