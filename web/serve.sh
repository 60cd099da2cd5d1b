#!/usr/bin/env bash
# The README's first command: set up a fresh machine, build the web page into dist/, and serve
# the lab on localhost.
#
# The browser lab (crates/bvhlab-app) is not written yet: until it is, this sets up the
# toolchain and builds the query core for WebAssembly, which is what the lab will run on.
set -euo pipefail
cd "$(dirname "$0")/.."

rustup target add wasm32-unknown-unknown
cargo build -p bvhlab --release --target wasm32-unknown-unknown
wasm=target/wasm32-unknown-unknown/release/libbvhlab.rlib
echo
echo "Built the bvhlab core for wasm32-unknown-unknown ($wasm)."
echo "The browser lab itself is not built yet, so there is no page to serve."
