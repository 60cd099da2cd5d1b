#!/usr/bin/env bash
# Fuzzes what the lab reads from outside (mesh files, scene files, share links, saved trees) with
# libFuzzer, on stable Rust: builds the targets of fuzz/ with the sanitizer-coverage instrumentation
# cargo-fuzz would add (but without AddressSanitizer, which needs nightly; the code is safe
# Rust, so a panic, a hang or an out-of-memory is what there is to find). Any crash, hang (a case
# over 10 s) or allocation past 2 GiB fails, with the input's path printed.
#
#   bash tests/fuzz.sh check [target...]              # the gate (tests/check.sh runs this)
#   bash tests/fuzz.sh explore [seconds] [target...]  # new inputs, with a new seed each run
#   bash tests/fuzz.sh merge [target...]              # keep what exploring found
#
# `check` gives the same result every time on the same commit: it replays every committed input
# of fuzz/corpus/<target> once, then fuzzes from them with a fixed seed for a fixed number of
# runs (RUNS below), starting each time from the committed corpus alone. What else made two
# such runs differ is turned off: libFuzzer re-reading its output folder every second
# (`-reload=0`); the addresses it records from comparisons, which move with address-space
# randomisation (`setarch -R`) and with the environment and arguments above the stack (the
# fuzzer runs with an empty environment and relative paths); hash maps' random keys (the
# targets fix them: `same_hash_keys_every_run!` in fuzz/src/lib.rs); and the lab's clock
# (`cfg(fuzzing)` in crates/bvhlab-app/src/model/clock.rs). Two runs of the same build give the same coverage, the same
# new inputs and the same verdict, and so do two builds of one commit in the same folder (as
# CI checks it out); a crash it reports is reproduced by running the same command again. A
# clone in another folder builds a program that embeds other source paths (panic messages
# name their files), so its fixed-seed runs may take other inputs; the replay is the same
# everywhere.
#
# `explore` (default 600 s per target) is for finding new inputs: libFuzzer picks a new seed each
# run and keeps what adds coverage in target/fuzz/new/<target>, never in fuzz/corpus. A crash
# stops it with the input's path: fix the bug, then copy that input into fuzz/corpus/<target>
# (named `regression-<what>`), so that `check` replays it from then on. `merge` adds to
# fuzz/corpus/<target> the fewest explored inputs that keep all they add to its coverage
# (libFuzzer's -set_cover_merge=1); commit them. With nightly and cargo-fuzz,
# `cargo +nightly fuzz run <target>` works too (adds AddressSanitizer).
set -euo pipefail
cd "$(dirname "$0")/.."

mode=check
case "${1:-}" in
    check | explore | merge) mode=$1; shift ;;
    # The old form, `bash tests/fuzz.sh SECONDS [target...]`, explores.
    [0-9]*) mode=explore ;;
esac
seconds=600
if [ "$mode" = explore ] && [[ "${1:-}" =~ ^[0-9]+$ ]]; then
    seconds=$1
    shift
fi
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
    targets=(mesh_load scene_file share_link saved_tree)
fi

# The gate's fuzzing: one seed for every target, and runs per target sized so that each takes
# five to ten seconds on a 2-core CI machine (measured in the note of issue 28).
SEED=28
declare -A RUNS=([mesh_load]=400000 [scene_file]=150000 [share_link]=60000 [saved_tree]=600000)

host=$(rustc -vV | sed -n 's/^host: //p')
# Its own target directory: these flags differ from the main workspace's, and sharing one
# would rebuild everything each time either is built.
out_abs=$(realpath -m "${CARGO_TARGET_DIR:-$PWD/target}/fuzz")
# Relative to the checkout where it lies inside it (as it does by default): the fuzzer is then
# started with the same arguments in every clone (see run_fuzzer).
out=$(realpath -m --relative-base=. "$out_abs")
# What cargo-fuzz passes (coverage counters, the pc table, comparison tracing for libFuzzer's
# value profile, `cfg(fuzzing)`), all stable. `--target` keeps them off build scripts and
# proc macros. Debug assertions and overflow checks are on through fuzz/Cargo.toml's release
# profile. (No --remap-path-prefix: cargo hashes these flags into every crate's symbols, so a
# path in them changes the program's layout from clone to clone more than the paths do.)
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

limits=(-timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=65536)
# The same addresses every run (see the header); without setarch, or where the kernel refuses
# it, the gate still runs, and says that its fuzzing may vary.
fixed_addresses=(setarch "$(uname -m)" -R)
if ! "${fixed_addresses[@]}" true 2>/dev/null; then
    echo "tests/fuzz.sh: setarch -R is not available here: the fixed-seed runs may vary" >&2
    fixed_addresses=()
fi

# Runs libFuzzer on `$target` with the given arguments, its output in `$log`; on failure prints
# the end of the log and the input that did it, and returns 1. The fuzzer gets an empty
# environment but for PATH, and paths relative to the checkout: the program's stack then
# starts at the same address in every clone and on every machine (its arguments and
# environment lie above it), and the addresses libFuzzer sees compared stay the same.
run_fuzzer() {
    local artifacts=$out/artifacts/$target
    rm -rf "$artifacts"
    mkdir -p "$artifacts" "$(dirname "$log")"
    if env -i PATH="$PATH" "${fixed_addresses[@]}" "$out/$host/release/$target" "${limits[@]}" \
        -print_final_stats=1 -artifact_prefix="$artifacts/" "$@" >"$log" 2>&1; then
        return 0
    fi
    tail -n 40 "$log"
    printf '    FAILED: %s; the input that did it:\n' "$target"
    find "$artifacts" -type f | sed 's/^/      /'
    printf '    replay: %s %s\n' "$out/$host/release/$target" '<that file>'
    return 1
}

# The number after `name:` on libFuzzer's last status line (`cov`, `ft`, `corp`), or `?`.
final_stat() {
    grep -E '^#[0-9]+' "$log" | tail -n 1 | grep -oE "$1: [0-9]+" | grep -oE '[0-9]+' || echo '?'
}

failed=()
for target in "${targets[@]}"; do
    corpus=fuzz/corpus/$target
    mkdir -p "$corpus"
    case $mode in
    check)
        start=$SECONDS
        log=$out/logs/$target.replay.log
        # -runs=0: read and run every input of the corpus once, then stop.
        if ! run_fuzzer -runs=0 "$corpus"; then
            failed+=("$target")
            continue
        fi
        printf '==> fuzz: %s: replayed %d committed inputs in %d s\n' \
            "$target" "$(find "$corpus" -type f | wc -l)" $((SECONDS - start))
        start=$SECONDS
        # New inputs go to a scratch folder emptied first (libFuzzer writes into the first
        # folder it is given), so that every run starts from the committed corpus alone.
        scratch=$out/check/$target
        rm -rf "$scratch"
        mkdir -p "$scratch"
        log=$out/logs/$target.log
        if ! run_fuzzer -seed="$SEED" -runs="${RUNS[$target]}" -reload=0 "$scratch" "$corpus"; then
            failed+=("$target")
            continue
        fi
        printf '==> fuzz: %s: %d runs from seed %d in %d s: coverage %s, features %s, %s new inputs\n' \
            "$target" "${RUNS[$target]}" "$SEED" $((SECONDS - start)) \
            "$(final_stat cov)" "$(final_stat ft)" "$(find "$scratch" -type f | wc -l)"
        ;;
    explore)
        scratch=$out/new/$target
        mkdir -p "$scratch"
        log=$out/logs/$target.explore.log
        printf '==> fuzz: exploring %s for %d s from %s and %s\n' "$target" "$seconds" "$corpus" "$scratch"
        if ! run_fuzzer -max_total_time="$seconds" "$scratch" "$corpus"; then
            failed+=("$target")
            continue
        fi
        printf '    %s runs; %d inputs kept in %s (bash tests/fuzz.sh merge %s adds the useful ones to %s)\n' \
            "$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")" \
            "$(find "$scratch" -type f | wc -l)" "$scratch" "$target" "$corpus"
        ;;
    merge)
        scratch=$out/new/$target
        log=$out/logs/$target.merge.log
        before=$(find "$corpus" -type f | wc -l)
        if [ -d "$scratch" ] && ! run_fuzzer -set_cover_merge=1 "$corpus" "$scratch"; then
            failed+=("$target")
            continue
        fi
        printf '==> fuzz: %s: %d inputs added to %s\n' \
            "$target" $(($(find "$corpus" -type f | wc -l) - before)) "$corpus"
        ;;
    esac
done

if [ ${#failed[@]} -ne 0 ]; then
    printf '==> fuzz: %s FAILED (logs in %s/logs)\n' "${failed[*]}" "$out"
    exit 1
fi
if [ "$mode" != merge ]; then
    printf '==> fuzz: %s: no crash, hang or out-of-memory\n' "${targets[*]}"
fi
