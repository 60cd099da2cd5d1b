#!/usr/bin/env bash
# The README's first command: sets up a fresh machine as far as needed, builds the web page into
# dist/ and serves the lab on localhost.
#
#   bash web/serve.sh [PORT]      (or PORT=... in the environment; default 8080)
#
# web/build.sh installs the wasm32 target and wasm-bindgen-cli (the version in Cargo.lock) when
# they are missing: about 2 minutes once on 2 cores, then seconds. The first release build of
# the lab for wasm32 takes about 3½ minutes on 2 cores; after that a few seconds.
set -euo pipefail
cd "$(dirname "$0")/.."

port=${1:-${PORT:-8080}}

bash web/build.sh

echo
if command -v node >/dev/null; then
  # Prints "bvh-lab is served at http://127.0.0.1:PORT/" once it listens; Ctrl-C stops it.
  exec node web/server.mjs "$port"
else
  echo "node is not installed: serving dist/ with Python's http.server instead"
  echo "(no Content-Security-Policy header, and no Access-Control-Allow-Origin, so a frame"
  echo "sandboxed without allow-same-origin cannot load the lab; install Node.js for web/server.mjs)."
  [ "$port" != 0 ] && echo "bvh-lab is served at http://127.0.0.1:$port/"
  exec python3 -m http.server --bind 127.0.0.1 --directory dist "$port"
fi
