#!/usr/bin/env bash
# The project's test command (README.md; .ci/run calls it). Builds with two
# jobs, as on the CI machine, checks formatting and clippy's lints, and runs
# every test in the workspace (all targets, then doc tests). Tests of the
# wgpu backend need an adapter: on a machine without a GPU that is Mesa's
# lavapipe, installed here when missing or too old for ray queries (as
# root: Mesa 25 from bookworm-backports). A missing adapter fails those
# tests; it is never skipped. The viewer's tests need Xvfb, installed
# here too. Node and Dawn's npm package run the Tint check (tint.rs);
# Chromium and the page scripts/web.sh builds, the browser test.
set -euo pipefail
cd "$(dirname "$0")/.."
# The ray-query traversal's tests need lavapipe with VK_KHR_ray_query:
# Mesa 25 from bookworm-backports (bookworm's own 22.3 has none).
. "$(dirname "$0")/lavapipe.sh"
ensure_lavapipe
if lavapipe_has_ray_queries; then
    # Its tests then fail rather than skip.
    export RT_REQUIRE_RAY_QUERY="${RT_REQUIRE_RAY_QUERY:-1}"
fi
# The viewer's tests open its window on a virtual X display; the viewer
# loads the X11 libraries it needs at run time.
x11_packages="xvfb libx11-6 libx11-xcb1 libxcursor1 libxi6 libxkbcommon0 libxkbcommon-x11-0"
# shellcheck disable=SC2086
if ! command -v Xvfb >/dev/null || ! dpkg -s $x11_packages >/dev/null 2>&1; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        echo "scripts/test.sh: installing xvfb and the X11 libraries for the viewer's tests"
        # shellcheck disable=SC2086
        apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $x11_packages >/dev/null
    else
        echo "scripts/test.sh: no Xvfb (or X11 libraries) found; the viewer's window tests may be skipped or fail (apt-get install $x11_packages)" >&2
    fi
fi
# Tint, Dawn's WGSL compiler (Chrome's), through Node and the npm package
# `webgpu` (scripts/tint): tests/tests/tint.rs gives it every kernel the
# suite links and every snapshot. Required here: without Node it fails.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        echo "scripts/test.sh: installing nodejs and npm for the Tint check"
        apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq nodejs npm >/dev/null
    else
        echo "scripts/test.sh: no node/npm found; the Tint check (tests/tests/tint.rs) will fail (apt-get install nodejs npm)" >&2
    fi
fi
if command -v npm >/dev/null && [ ! -e scripts/tint/node_modules/webgpu/package.json ]; then
    echo "scripts/test.sh: npm ci in scripts/tint (Dawn for Node, the package \`webgpu\`)"
    npm ci --prefix scripts/tint --no-audit --no-fund --loglevel=error
fi
# The megakernel in a browser (web/, examples/tests/browser.rs): headless
# Chromium, whose WebGPU adapter is SwiftShader's on a machine without a
# GPU.
if ! command -v chromium >/dev/null; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        echo "scripts/test.sh: installing chromium for the browser test"
        apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
    else
        echo "scripts/test.sh: no chromium found; the browser test (examples/tests/browser.rs) will fail (apt-get install chromium)" >&2
    fi
fi
# GNU parallel, for README's distributed render run as written
# (examples/tests/gnu_parallel.rs, with local workers).
if ! parallel --version 2>/dev/null | grep -q 'GNU parallel'; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        echo "scripts/test.sh: installing GNU parallel for the distributed render test"
        apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq parallel >/dev/null
    else
        echo "scripts/test.sh: no GNU parallel found; examples/tests/gnu_parallel.rs will fail (apt-get install parallel)" >&2
    fi
fi
export RT_REQUIRE_PARALLEL=1
export RT_TINT=require
# rt-runtime keeps every kernel the suite links here, for the Tint check.
export RT_WGSL_KERNEL_DIR="$PWD/target/rt-kernels"
rm -rf "$RT_WGSL_KERNEL_DIR"
export CARGO_BUILD_JOBS="${CARGO_BUILD_JOBS:-2}"
start=$(date +%s)
# Lint first: formatting and clippy's warnings fail the run as a test does.
echo "scripts/test.sh: cargo fmt --check and cargo clippy (-D warnings)"
cargo fmt --all --check
cargo clippy --workspace --all-targets -j"$CARGO_BUILD_JOBS" -- -D warnings
# The platforms this machine cannot run: macOS (wgpu's Metal backend) and
# Windows (DX12, GLES, Vulkan). clippy compiles the runtime, the loaders,
# the examples (the viewer's window and surface code included) and the
# bench for each, without linking.
for target in aarch64-apple-darwin x86_64-pc-windows-msvc; do
    if command -v rustup >/dev/null && ! rustup target list --installed | grep -qx "$target"; then
        echo "scripts/test.sh: rustup target add $target"
        rustup target add "$target"
    fi
    echo "scripts/test.sh: cargo clippy --target $target (-D warnings)"
    cargo clippy --target "$target" -p rt-runtime -p rt-scene -p examples -p rt-bench -j"$CARGO_BUILD_JOBS" -- -D warnings
done
# The API documentation, every warning an error (broken and private
# links included).
echo "scripts/test.sh: cargo doc --workspace --no-deps (RUSTDOCFLAGS=-D warnings)"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps -j"$CARGO_BUILD_JOBS"
# rt-runtime's wgpu backend builds for the browser (wasm32, WebGPU): the
# page of web/ (rt-web, over rt-runtime and the examples), which the
# browser test serves to Chromium.
echo "scripts/test.sh: scripts/web.sh (rt-web and rt-runtime for wasm32-unknown-unknown, the page)"
bash scripts/web.sh
export RT_REQUIRE_BROWSER=1
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# The Tint check reads the kernels the rest of the suite linked: it runs
# after it.
tint_test=tint_accepts_every_kernel_and_snapshot
cargo test --workspace --all-targets -j"$CARGO_BUILD_JOBS" -- --skip "$tint_test" 2>&1 | tee "$log"
cargo test -p rt-tests --test tint -j"$CARGO_BUILD_JOBS" -- --exact "$tint_test" --nocapture 2>&1 | tee -a "$log"
cargo test --workspace --doc -j"$CARGO_BUILD_JOBS" 2>&1 | tee -a "$log"
# The CPU backend's traversal on each instruction set it is built for (the
# runs above took the best this CPU has): the runtime suite's CPU tests,
# the bunny and the example goldens on the CPU backend. (Its own tests,
# rt-runtime's accel::wide and rt-tests' cpu_simd, walk every path in
# one run.)
for simd in sse4.1 scalar; do
    echo "scripts/test.sh: the CPU backend's traversal tests with RT_CPU_SIMD=$simd"
    RT_CPU_SIMD=$simd cargo test -p rt-tests --test runtime -j"$CARGO_BUILD_JOBS" -- cpu:: 2>&1 | tee -a "$log"
    RT_CPU_SIMD=$simd cargo test -p examples --test golden -j"$CARGO_BUILD_JOBS" -- cpu_renders_match_the_goldens 2>&1 | tee -a "$log"
done
# Ray generation programs ran one launch index at a time above (the CPU
# backend's default); their lane-wise form, what RT_CPU_EXEC=lanes runs,
# against the runtime suite's CPU tests, wgpu (the differential tests) and
# the goldens.
echo "scripts/test.sh: the CPU backend's tests with RT_CPU_EXEC=lanes"
RT_CPU_EXEC=lanes cargo test -p rt-tests --test runtime -j"$CARGO_BUILD_JOBS" -- cpu:: 2>&1 | tee -a "$log"
RT_CPU_EXEC=lanes cargo test -p rt-tests --test differential -j"$CARGO_BUILD_JOBS" 2>&1 | tee -a "$log"
RT_CPU_EXEC=lanes cargo test -p examples --test golden -j"$CARGO_BUILD_JOBS" -- cpu_renders_match_the_goldens 2>&1 | tee -a "$log"
# The library crates packed as crates.io would get them (each verified
# against the others' packs), and a user's crate outside the workspace
# built on the packs: README's first program, one image on the CPU
# backend, its pixels checked.
echo "scripts/test.sh: scripts/package.sh (cargo package, then a consumer outside the workspace)"
bash scripts/package.sh
passed=$(grep -Eo '^test result: [a-zA-Z]+\. [0-9]+ passed' "$log" | awk '{s += $4} END {print s + 0}')
failed=$(grep -Eo '[0-9]+ failed;' "$log" | awk '{s += $1} END {print s + 0}')
echo "scripts/test.sh: tests took $(( $(date +%s) - start )) s"
echo "tests: $passed passed, $failed failed"
