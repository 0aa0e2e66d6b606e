#!/usr/bin/env bash
# Builds the browser page (web/: the normal and cornell examples on the
# page's WebGPU) into target/web/: index.html and pkg/, the wasm module
# and its JavaScript glue made by wasm-bindgen. Serve target/web and open
# index.html in a browser with WebGPU (Chromium: --enable-unsafe-webgpu on
# Linux); examples/tests/browser.rs does that headless.
#
# Needs the wasm32 target (added here with rustup) and wasm-bindgen's
# command line at the version of the wasm-bindgen crate in Cargo.lock
# (installed here with cargo install when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${CARGO_BUILD_JOBS:-2}"
if command -v rustup >/dev/null && ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    echo "scripts/web.sh: rustup target add wasm32-unknown-unknown"
    rustup target add wasm32-unknown-unknown
fi
version=$(grep -A1 '^name = "wasm-bindgen"$' Cargo.lock | sed -n 's/^version = "\(.*\)"$/\1/p')
if ! command -v wasm-bindgen >/dev/null || [ "$(wasm-bindgen --version | awk '{print $2}')" != "$version" ]; then
    echo "scripts/web.sh: cargo install wasm-bindgen-cli $version (once; a few minutes)"
    cargo install wasm-bindgen-cli --version "$version" -j"$jobs"
fi
# No debug information: the page loads the module, nobody steps through it.
CARGO_PROFILE_DEV_DEBUG=false cargo build --target wasm32-unknown-unknown -p rt-web -j"$jobs"
# The module is where cargo put it (CARGO_TARGET_DIR may move it); the
# page goes to target/web, where the browser test serves it.
build=$(cargo metadata --format-version 1 --no-deps | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
rm -rf target/web
mkdir -p target/web
wasm-bindgen --target web --no-typescript --out-dir target/web/pkg "$build/wasm32-unknown-unknown/debug/rt_web.wasm"
cp web/index.html target/web/
echo "scripts/web.sh: the page is in target/web ($(du -sh target/web | cut -f1))"
