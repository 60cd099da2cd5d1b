#!/usr/bin/env bash
# Fuzzes what the lab reads from outside (mesh files, scene files, share links, saved trees) with
# libFuzzer, on stable Rust: builds the targets of fuzz/ with the sanitizer-coverage instrumentation
# cargo-fuzz would add (but without AddressSanitizer, which needs nightly; the code is safe
# Rust, so a panic, a hang or an out-of-memory is what there is to find), then runs each target
# for the given seconds over its committed corpus. Any crash, hang (a case over 10 s) or
# allocation past 2 GiB fails the run, with the input's path printed.
#
#   bash tests/fuzz.sh [seconds-per-target] [target...]   # default: 20 s each, every target
#
# New inputs found go to a scratch corpus beside the build, never into fuzz/corpus; to keep
# them, merge them in (`-merge=1` keeps only inputs that add coverage):
#   target/fuzz/x86_64-unknown-linux-gnu/release/mesh_load -merge=1 fuzz/corpus/mesh_load target/fuzz/new/mesh_load
# Long runs: `bash tests/fuzz.sh 3600 mesh_load`, or with nightly and cargo-fuzz installed,
# `cargo +nightly fuzz run mesh_load` (adds AddressSanitizer).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-20}
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(mesh_load scene_file share_link saved_tree)
fi

host=$(rustc -vV | sed -n 's/^host: //p')
# Its own target directory: these flags differ from the main workspace's, and sharing one
# would rebuild everything each time either is built.
out=${CARGO_TARGET_DIR:-$PWD/target}/fuzz
# What cargo-fuzz passes (coverage counters, the pc table, comparison tracing for libFuzzer's
# value profile, `cfg(fuzzing)`), all stable. `--target` keeps them off build scripts and
# proc macros. Debug assertions and overflow checks are on through fuzz/Cargo.toml's release
# profile.
export RUSTFLAGS="--cfg fuzzing -Cpasses=sancov-module \
-Cllvm-args=-sanitizer-coverage-level=4 \
-Cllvm-args=-sanitizer-coverage-inline-8bit-counters \
-Cllvm-args=-sanitizer-coverage-pc-table \
-Cllvm-args=-sanitizer-coverage-trace-compares \
-Cllvm-args=-sanitizer-coverage-stack-depth \
-Cdebug-assertions -Coverflow-checks"

printf '==> fuzz: building %s (release, instrumented)\n' "${targets[*]}"
build_start=$SECONDS
bins=()
for target in "${targets[@]}"; do bins+=(--bin "$target"); done
CARGO_TARGET_DIR=$out cargo build --locked --release --manifest-path fuzz/Cargo.toml \
    --target "$host" "${bins[@]}"
printf '==> fuzz: built in %d s\n' $((SECONDS - build_start))

failed=()
for target in "${targets[@]}"; do
    corpus=fuzz/corpus/$target
    scratch=$out/new/$target
    artifacts=$out/artifacts/$target
    log=$out/logs/$target.log
    rm -rf "$artifacts"
    mkdir -p "$corpus" "$scratch" "$artifacts" "$(dirname "$log")"
    printf '==> fuzz: %s for %d s over %s (%d inputs)\n' \
        "$target" "$seconds" "$corpus" "$(find "$corpus" -type f | wc -l)"
    # The scratch directory comes first: libFuzzer writes what it finds into the first one.
    if "$out/$host/release/$target" "$scratch" "$corpus" \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 \
        -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/" >"$log" 2>&1; then
        runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
        rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
        printf '    ok: %s runs, %s per second\n' "${runs:-?}" "${rate:-?}"
    else
        tail -n 40 "$log"
        printf '    FAILED: %s; the input that did it:\n' "$target"
        find "$artifacts" -type f | sed 's/^/      /'
        printf '    replay: %s %s\n' "$out/$host/release/$target" '<that file>'
        failed+=("$target")
    fi
done

if [ ${#failed[@]} -ne 0 ]; then
    printf '==> fuzz: %s FAILED (logs in %s/logs)\n' "${failed[*]}" "$out"
    exit 1
fi
printf '==> fuzz: %s: no crash, hang or out-of-memory\n' "${targets[*]}"
