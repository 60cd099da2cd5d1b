#!/usr/bin/env bash
# Runs every check of bvh-lab, exactly as CI does: it is the README's test command.
# On a fresh machine it first installs what it needs: the wasm target, rustfmt and clippy here;
# wasm-bindgen-cli for the web page (in the background, see below); the browser test
# (tests/e2e/run.sh) installs npm packages and, as root, Chromium. Those steps take seconds
# when already done.
#
# Each step's time is printed when it ends, and all of them again at the end (also when a step
# fails), so that every log shows where the minutes go.
set -euo pipefail
cd "$(dirname "$0")/.."

step_name=
step_start=$SECONDS
times=()
background=
end_step() {
    if [ -n "$step_name" ]; then
        local took=$((SECONDS - step_start))
        printf '==> %s: %d s\n' "$step_name" "$took"
        times+=("$(printf '%6d s  %s' "$took" "$step_name")")
    fi
    step_name=
}
step() {
    end_step
    step_name=$*
    step_start=$SECONDS
    printf '\n==> %s\n' "$*"
}
summary() {
    local status=$?
    end_step
    if [ -n "$background" ]; then
        kill -- "-$background" 2>/dev/null || true
    fi
    printf '\n==> time per step\n'
    printf '%s\n' "${times[@]}"
    printf '%6d s  in all%s\n' "$SECONDS" "$([ "$status" = 0 ] || echo ", FAILED")"
}
trap summary EXIT

# The core's optional features, on in every build of the workspace below: the core is then
# compiled once for the tests, once for the lints and the docs, and the tests of saved
# trees (`serde`) and of batch queries and parallel builds (`parallel`) run with the rest. The
# core without them is documented on its own and built for wasm32 (inside the web page).
features=(--features bvhlab/serde,bvhlab/parallel)

# Property tests draw their cases from this seed rather than a new one each run (proptest's
# default), so that a commit's result is the same every time; `cargo test` alone still
# explores with fresh seeds.
export PROPTEST_RNG_SEED=28

step "toolchain: wasm32 target, rustfmt, clippy"
rustup target add wasm32-unknown-unknown
rustup component add rustfmt clippy
# The web page needs wasm-bindgen-cli (about 2 minutes of compiling on 2 cores, once). It
# compiles in the background at the lowest priority, on the cycles the steps before the web
# page leave idle (links, test runs, fuzzing); that step waits for it.
mkdir -p target/check
bindgen_log=target/check/wasm-bindgen-cli.log
# (In a process group of its own, so that a failing check stops all of it.)
setsid nice -n 19 bash -c 'source web/wasm-toolchain.sh && ensure_wasm_toolchain tests/check.sh' \
    >"$bindgen_log" 2>&1 &
background=$!

step "format"
cargo fmt --all -- --check

step "tests (native): build and run the tests"
# The benchmarks are not built here: the lints step type-checks every one of them (clippy's
# --all-targets), and building and linking the eleven of them in the test profile cost a clean
# run about half a minute for no test. Run them with `cargo bench`; timings are not tests.
# The 3D renderer and heat-map tests render on the GPU (Mesa lavapipe on CI): here they must
# find an adapter, not skip.
BVHLAB_REQUIRE_GPU=1 cargo test --workspace "${features[@]}" --lib --bins --tests
cargo test --workspace "${features[@]}" --doc

step "fuzzing (libFuzzer on stable Rust: mesh files, scene files, share links, saved trees)"
# Builds fuzz/ instrumented, replays every committed input, then fuzzes each target from a
# fixed seed for a fixed number of runs: the same result on every run of the same commit.
bash tests/fuzz.sh check

step "lints (native, then the core and the lab for wasm32)"
# With the comparison's Embree peer (the bench crate's `embree` feature), in the same pass (a
# second pass for it alone took half a minute on a clean machine). Linting does not link, so
# this needs no libembree3; running it does (crates/bvhlab-bench/compare.sh installs it).
cargo clippy --workspace --all-targets --features bvhlab/serde,bvhlab/parallel,bvhlab-bench/embree -- -D warnings
cargo clippy -p bvhlab -p bvhlab-meshio -p bvhlab-app --target wasm32-unknown-unknown -- -D warnings
# The lab's model alone (what fuzz/ builds): no egui may creep into it.
cargo clippy -p bvhlab-app --no-default-features -- -D warnings

step "docs"
# The core as most users build it, without its optional features: no link may lead to them.
RUSTDOCFLAGS="-D warnings" cargo doc -p bvhlab --no-deps
# Then everything, the core with its features.
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps "${features[@]}"
# Last, the core as docs.rs builds it (what target/doc keeps): every feature, each item marked
# with the feature it needs (rustdoc's doc_cfg, behind the `docsrs` cfg; RUSTC_BOOTSTRAP lets
# stable rustdoc use it, as docs.rs's nightly does). A newcomer once missed `saved` and
# `build_parallel` in the default docs (issue 33): they must be there, and marked.
RUSTC_BOOTSTRAP=1 RUSTDOCFLAGS="--cfg docsrs -D warnings" cargo doc -p bvhlab --no-deps --all-features
bash tests/docs_features.sh target/doc/bvhlab

step "the web page (the lab and the core for wasm32)"
if ! wait "$background"; then
    echo "the background install of wasm-bindgen-cli failed; web/build.sh tries again:"
fi
background=
cat "$bindgen_log"
bash web/build.sh
# The core alone, without features, as a WebAssembly user builds it (with web/build.sh's
# release settings, so it is the build the page already made of it: a second or two).
CARGO_PROFILE_RELEASE_STRIP=symbols cargo build -p bvhlab --release --target wasm32-unknown-unknown

step "browser end-to-end (headless Chromium, WebGPU and WebGL2)"
# Installs what it lacks itself (Chromium as root, npm packages), serves dist/ and drives the
# page; screenshots in target/e2e/.
# The page built in the step before is the one to test: run.sh need not build it again (a
# build with nothing to compile still takes about 25 s: wasm-bindgen and the one-file page).
BVHLAB_E2E_PAGE_BUILT=1 bash tests/e2e/run.sh

end_step
printf '\n==> all checks passed\n'
