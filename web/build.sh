#!/usr/bin/env bash
# Builds the web page of the lab into dist/ at the repository root: the lab app
# (crates/bvhlab-app) for wasm32-unknown-unknown, its JavaScript bindings from wasm-bindgen, and
# index.html. Installs what it needs when it is missing (the wasm32 target, wasm-bindgen-cli of
# exactly the version in Cargo.lock); those checks take a second when already done.
#
# No wasm-opt: Debian's binaryen (108) breaks wasm-bindgen's output (the browser fails with
# "WebAssembly.Table.set(): Argument 1 is invalid for table") and npm's binaryen costs minutes
# per release build; the page works without it (about 8 MB of wasm, under 3 MB gzipped).
set -euo pipefail
cd "$(dirname "$0")/.."
# Where cargo install puts binaries, in case the shell's PATH lacks it (a fresh machine).
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"

# The wasm32 target and the wasm-bindgen CLI of the version in Cargo.lock.
source web/wasm-toolchain.sh
ensure_wasm_toolchain web/build.sh

# Without the symbol names (the wasm's "name" section, 1.4 MB of the 11.7 MB): a panic's
# message still names the file and line.
CARGO_PROFILE_RELEASE_STRIP=symbols cargo build -p bvhlab-app --release --target wasm32-unknown-unknown
wasm=${CARGO_TARGET_DIR:-target}/wasm32-unknown-unknown/release/bvhlab-app.wasm

rm -rf dist
mkdir -p dist
wasm-bindgen --target web --no-typescript --out-dir dist --out-name app "$wasm"
cp index.html web/loader.js web/main.js web/lab.css dist/
# The example course page that embeds two labs, and the script it uses to drive them.
cp web/embed.html web/embed.js web/embed.css web/bvhlab-embed.js web/course.html web/course.js dist/

if command -v node >/dev/null; then
  node web/size.mjs dist
  # The lab in one file, for classrooms without a server (opened from disk).
  node web/offline.mjs dist
fi
