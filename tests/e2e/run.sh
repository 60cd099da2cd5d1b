#!/usr/bin/env bash
# bvh-lab's browser end-to-end test, from scratch on a fresh machine: installs what it needs
# (Node.js and Debian's Chromium with software Vulkan/GL when missing and we are root, then the
# pinned playwright-core, pngjs, axe-core and scorm-again with npm ci; zip and unzip), builds
# the page (web/build.sh, unless tests/check.sh has just built it), serves it on a free local port (web/server.mjs), runs the tests of
# tests/e2e/ against it (lab, view3d, embed, lesson, teacher, hosting, a11y; then scorm, which packages
# the lab and serves the packages itself), and stops the server.
# The exit code is the test's. Screenshots and the server's log go to target/e2e/.
set -euo pipefail
cd "$(dirname "$0")/../.."

apt_install() {
  if [ "$(id -u)" != 0 ]; then
    echo "tests/e2e/run.sh: missing $*; install it (apt-get install $*) or run as root" >&2
    exit 1
  fi
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "$@"
}

# Node.js: only when missing. A machine whose Node.js comes from elsewhere (with its own npm)
# refuses Debian's npm package ("nodejs : Conflicts: npm"), so never ask apt for it then.
if ! command -v node >/dev/null; then
  apt_install nodejs npm
elif ! command -v npm >/dev/null; then
  apt_install npm
fi
# zip and unzip: web/package.sh makes the SCORM packages with zip; the test unpacks them.
if ! command -v zip >/dev/null || ! command -v unzip >/dev/null; then
  apt_install zip unzip
fi
if [ ! -x "${CHROMIUM:-/usr/bin/chromium}" ]; then
  apt_install chromium libegl1 libgl1-mesa-dri libegl-mesa0 mesa-vulkan-drivers libvulkan1
fi

(cd tests/e2e && npm ci --no-audit --no-fund --loglevel=error)

# tests/check.sh has just built the page and says so; run alone, this builds it.
if [ "${BVHLAB_E2E_PAGE_BUILT:-}" = 1 ] && [ -f dist/index.html ] && [ -f dist/bvh-lab-offline.html ]; then
  echo "tests/e2e/run.sh: testing the page tests/check.sh built (dist/)"
else
  bash web/build.sh
fi

mkdir -p target/e2e
log=target/e2e/server.log
: >"$log"
node web/server.mjs 0 >"$log" 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null || true; wait "$server" 2>/dev/null || true' EXIT

url=
for _ in $(seq 100); do
  url=$(grep -o 'http://127\.0\.0\.1:[0-9]*/' "$log" || true)
  [ -n "$url" ] && break
  if ! kill -0 "$server" 2>/dev/null; then
    echo "tests/e2e/run.sh: the server stopped:" >&2
    cat "$log" >&2
    exit 1
  fi
  sleep 0.1
done
if [ -z "$url" ]; then
  echo "tests/e2e/run.sh: the server printed no address within 10 s" >&2
  exit 1
fi
echo "Testing $url in headless Chromium ($("${CHROMIUM:-/usr/bin/chromium}" --version 2>/dev/null || echo '?'))"

node tests/e2e/lab.test.mjs "$url"
node tests/e2e/view3d.test.mjs "$url"
node tests/e2e/embed.test.mjs "$url"
node tests/e2e/lesson.test.mjs "$url"
node tests/e2e/teacher.test.mjs "$url"
node tests/e2e/hosting.test.mjs "$url"
node tests/e2e/a11y.test.mjs "$url"
# The SCORM packages (web/package.sh) in an LMS page with scorm-again; it serves them itself.
node tests/e2e/scorm.test.mjs
