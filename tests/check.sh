#!/usr/bin/env bash
# Runs every check of bvh-lab, exactly as CI does: it is the README's test command.
# On a fresh machine it first installs what it needs: the wasm target, rustfmt and clippy here;
# the browser test (tests/e2e/run.sh) installs npm packages, wasm-bindgen-cli and, as root,
# Chromium. Those steps take seconds when already done.
set -euo pipefail
cd "$(dirname "$0")/.."

step() { printf '\n==> %s\n' "$*"; }

step "toolchain: wasm32 target, rustfmt, clippy"
rustup target add wasm32-unknown-unknown
rustup component add rustfmt clippy

step "format"
cargo fmt --all -- --check

step "tests (native)"
# The 3D renderer and heat-map tests render on the GPU (Mesa lavapipe on CI): here they must
# find an adapter, not skip.
BVHLAB_REQUIRE_GPU=1 cargo test --workspace --lib --bins --tests
cargo test --workspace --doc
# The core's optional features, which no other crate turns on, in one extra build of the
# core: saved trees (`serde`), and batch queries and builds on every core (`parallel`).
cargo test -p bvhlab --features serde,parallel --test saved_trees --test example_save_load --test batch_queries --test bvh_parallel_build
cargo test -p bvhlab --features serde,parallel --doc

step "fuzzing (libFuzzer on stable Rust: mesh files, scene files, share links, saved trees; 20 s each)"
# Builds fuzz/ instrumented (cargo and the C++ compiler only; about 10 minutes cold on 2
# cores, seconds after), runs each target over its committed corpus; a crash fails.
bash tests/fuzz.sh 20

step "benchmarks compile (run them with cargo bench; timings are not tests)"
# The lab's frame bench is left out: building it means a release build of eframe and wgpu
# (about 6 minutes on 2 cores); clippy --all-targets below still type-checks it.
cargo bench --workspace --exclude bvhlab-app --no-run

step "lints (native, then the core and the lab for wasm32)"
cargo clippy --workspace --all-targets -- -D warnings
cargo clippy -p bvhlab --all-features --all-targets -- -D warnings
# The comparison's Embree peer (the bench crate's `embree` feature). Linting does not link, so
# this needs no libembree3; running it does (crates/bvhlab-bench/compare.sh installs it).
cargo clippy -p bvhlab-bench --all-targets --features embree -- -D warnings
cargo clippy -p bvhlab -p bvhlab-meshio -p bvhlab-app --target wasm32-unknown-unknown -- -D warnings

step "docs"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps
RUSTDOCFLAGS="-D warnings" cargo doc -p bvhlab --features serde --no-deps

step "core builds for wasm32-unknown-unknown"
cargo build -p bvhlab --release --target wasm32-unknown-unknown

step "browser end-to-end (headless Chromium, WebGPU and WebGL2)"
# Installs what it lacks itself (Chromium as root, npm packages, wasm-bindgen-cli), builds dist/
# with web/build.sh and drives the page; screenshots in target/e2e/.
bash tests/e2e/run.sh

step "all checks passed"
