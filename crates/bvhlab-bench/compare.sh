#!/usr/bin/env bash
# The side-by-side comparison of issue 7, in one command (from anywhere in the repository):
#
#   bash crates/bvhlab-bench/compare.sh            # everything: about 50 minutes built
#   bash crates/bvhlab-bench/compare.sh --quick    # a smoke run: the bunny, small workload
#   bash crates/bvhlab-bench/compare.sh --no-native  # without the native run below
#
# Everything is: the WebAssembly comparison; the native one (default flags, five scenes); the
# same built with -C target-cpu=native (adds tinybvh's BVH8_CPU) on the three real meshes, into
# bench/native/ (BVHLAB_BENCH_SCENES overrides the scenes of both native runs); and bvhlab's
# batch queries on both cores (`--parallel`, unpinned), added to bench/RESULTS.md.
#
# 1. builds bvhlab for wasm32-unknown-unknown with +simd128 (crates/bvhlab-bench-wasm) and its
#    bindings (wasm-bindgen --target nodejs), installs three, three-mesh-bvh and @dimforge/rapier3d-compat (pinned in
#    crates/bvhlab-bench-wasm/js/package-lock.json), and times both in one node process
#    (bench/wasm.json);
# 2. runs the native comparison (cargo bench --bench peers), which writes bench/results.json
#    and bench/RESULTS.md with the WebAssembly results merged in.
# Every timed run is pinned to one core (taskset) and single-threaded: tinybvh's C++ is
# compiled with NO_THREADED_BUILDS, the Rust peers without their parallel features, Embree's
# device with threads=1.
set -euo pipefail
cd "$(dirname "$0")/../.."
export PATH="${CARGO_HOME:-$HOME/.cargo}/bin:$PATH"

quick=""
native=1
for arg in "$@"; do
  case "$arg" in
    --quick) quick="--quick" ;;
    --native) native=1 ;;  # the default now; kept so that older command lines still work
    --no-native) native="" ;;
    *) echo "compare.sh: unknown argument $arg (use --quick, --no-native)" >&2; exit 2 ;;
  esac
done

target="${CARGO_TARGET_DIR:-target}"
# The last CPU: on a 2-core machine, the one the shell is less likely to be using.
cpu=$(( $(nproc) - 1 ))
pin=()
if command -v taskset >/dev/null; then pin=(taskset -c "$cpu"); fi
# tinybvh builds big meshes on a thread pool unless told not to (cc passes CXXFLAGS on).
export CXXFLAGS="${CXXFLAGS:-} -DNO_THREADED_BUILDS"
mkdir -p bench
rm -f bench/wasm.json bench/parallel.json

# Intel Embree 3 is a peer behind the bench crate's `embree` feature, which links the system's
# libembree3 (Debian's libembree-dev): installed here when we are root, else left out.
# (grep reads all of ldconfig's list: `grep -q` would stop early, and under pipefail the
# broken pipe of ldconfig would count as "missing".)
have_embree() { { ldconfig -p || /sbin/ldconfig -p; } 2>/dev/null | grep 'libembree3\.so ' >/dev/null; }
if ! have_embree && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
  echo "compare.sh: installing libembree-dev (Intel Embree 3) for the Embree row"
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libembree-dev || true
fi
features=()
if have_embree; then
  features=(--features embree)
else
  echo "compare.sh: libembree3 is missing and could not be installed (needs root and apt-get):"
  echo "compare.sh: running without the Embree row; install libembree-dev to add it"
fi

# --- 1. WebAssembly ----------------------------------------------------------------------
# The wasm32 target and the wasm-bindgen CLI of the version in Cargo.lock (shared with the
# web build).
source web/wasm-toolchain.sh
ensure_wasm_toolchain compare.sh
RUSTFLAGS="-C target-feature=+simd128" \
  cargo build -p bvhlab-bench-wasm --release --target wasm32-unknown-unknown
pkg="$target/bench-wasm"
rm -rf "$pkg"
wasm-bindgen --target nodejs --no-typescript --out-dir "$pkg" \
  "$target/wasm32-unknown-unknown/release/bvhlab_bench_wasm.wasm"
(cd crates/bvhlab-bench-wasm/js && npm ci --no-audit --no-fund --loglevel=error)
meshes=../shared/data/meshes
if [ -d "$meshes" ]; then
  "${pin[@]}" node crates/bvhlab-bench-wasm/js/run.mjs --pkg "$(realpath "$pkg")" \
    --meshes "$meshes" --out bench/wasm.json $quick
else
  echo "compare.sh: $meshes is missing: no WebAssembly comparison (it runs on the real meshes)"
fi

# --- 2. Native ---------------------------------------------------------------------------
cargo bench -p bvhlab-bench --bench peers "${features[@]}" --no-run
"${pin[@]}" cargo bench -p bvhlab-bench --bench peers "${features[@]}" -- $quick
# Both cores: not pinned.
cargo bench -p bvhlab-bench --bench peers "${features[@]}" -- $quick --parallel

if [ -n "$native" ]; then
  native_scenes="${BVHLAB_BENCH_SCENES:-bunny,dragon,ogre}"
  if [ -n "$quick" ]; then native_scenes="${BVHLAB_BENCH_SCENES:-bunny}"; fi
  # A second build of everything with the host's instruction set, in its own target folder,
  # on the real meshes.
  RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$target/native" \
    cargo bench -p bvhlab-bench --bench peers "${features[@]}" --no-run
  RUSTFLAGS="-C target-cpu=native" CARGO_TARGET_DIR="$target/native" \
    BVHLAB_BENCH_SCENES="$native_scenes" BVHLAB_BENCH_OUT="$PWD/bench/native" "${pin[@]}" \
    cargo bench -p bvhlab-bench --bench peers "${features[@]}" -- $quick
fi
