# Sourced by web/build.sh and crates/bvhlab-bench/compare.sh, from the repository root.
#
# ensure_wasm_toolchain NAME: installs what building for the web needs when it is missing,
# the wasm32-unknown-unknown target and the wasm-bindgen CLI of exactly the version of the
# wasm-bindgen crate in Cargo.lock (the CLI refuses modules from another version). The
# checks take a second when both are there; the CLI takes about 2 minutes to install on 2
# cores. NAME
# (the calling script) prefixes the error message.
ensure_wasm_toolchain() {
  local name=$1 version
  if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    rustup target add wasm32-unknown-unknown
  fi
  version=$(awk '
    /^\[\[package\]\]/ { in_wb = 0 }
    /^name = "wasm-bindgen"$/ { in_wb = 1 }
    in_wb && /^version = / { gsub(/"/, "", $3); print $3; exit }
  ' Cargo.lock)
  if [ -z "$version" ]; then
    echo "$name: no wasm-bindgen package in Cargo.lock" >&2
    return 1
  fi
  if [ "$(wasm-bindgen --version 2>/dev/null || true)" != "wasm-bindgen $version" ]; then
    echo "Installing wasm-bindgen-cli $version (about 2 minutes)..."
    # No --locked: the CLI's own lock file pins a crate version some registries lack.
    cargo install wasm-bindgen-cli --version "$version"
  fi
}
