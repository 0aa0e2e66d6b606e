#!/usr/bin/env bash
# The library crates as crates.io would get them, and a user's crate built
# on them. `cargo package` packs each publishable crate (sources, README,
# licence files; no tests, scenes or goldens) into target/package and
# verifies it: builds it from the packed files alone, against the other
# packs. Then scripts/consumer (README's first program in a crate outside
# the workspace) is copied to target/consumer, pointed at those packs
# through [patch.crates-io] as `cargo add rt-std rt-runtime` would get
# them, built, and run: it renders one image on the CPU backend and
# checks its pixels.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${CARGO_BUILD_JOBS:-2}"
crates="rt-abi rt-compiler rt-macros rt-std rt-runtime rt-scene"
# The members with `publish = false` (examples, bench, tests, the page):
# cargo 1.95's `cargo package --workspace` packs them too (only `cargo
# publish --workspace` skips them), and then fails on rt-bench's path
# dependency on `examples`, which has no version. So they are excluded,
# by the names their manifests give.
unpublished=$(grep -l '^publish = false' ./*/Cargo.toml ./*/*/Cargo.toml 2>/dev/null |
    xargs -r awk '/^\[/ { in_package = ($0 == "[package]") } in_package && $1 == "name" { gsub(/"/, "", $3); print $3 }')
target=$(cargo metadata --format-version 1 --no-deps | sed -n 's/.*"target_directory":"\([^"]*\)".*/\1/p')
version=$(sed -n 's/^version = "\(.*\)"$/\1/p' Cargo.toml | head -1)
# A pack verified against the others is built from them as from a
# registry, and cargo takes a registry crate of one version as unchanged:
# it neither unpacks it again into its registry's sources (one folder per
# local registry path) nor rebuilds what an earlier run built of it. So
# the packs of an earlier run, unpacked and built, go first.
cargo_home="${CARGO_HOME:-$HOME/.cargo}"
for c in $crates; do
    rm -rf "$cargo_home"/registry/src/-*/"$c-$version"
    lib=${c//-/_}
    for d in "$target"/debug/deps/"$lib"-*.d; do
        [ -e "$d" ] && grep -q 'registry/src/-' "$d" || continue
        hash=${d##*-}
        hash=${hash%.d}
        rm -rf "$target/debug/.fingerprint/$c-$hash" "$target"/debug/deps/*"$lib-$hash".*
    done
done
# (--allow-dirty: what is checked is the packing, not git's state.)
# shellcheck disable=SC2046
cargo package --workspace $(printf -- '--exclude %s ' $unpublished) --allow-dirty -j"$jobs"
echo "scripts/package.sh: the packages"
for c in $crates; do
    echo "  $c-$version.crate $(stat -c %s "$target/package/$c-$version.crate") bytes"
done
consumer="$target/consumer"
rm -rf "$consumer"
mkdir -p "$consumer"
cp -r scripts/consumer/src "$consumer/"
# (rt-scene is verified above; the consumer needs only these.)
patches=$(for c in rt-abi rt-compiler rt-macros rt-std rt-runtime; do echo "$c = { path = \"$target/package/$c-$version\" }"; done)
awk -v p="$patches" '$0 == "@PATCHES@" { print p; next } { print }' scripts/consumer/Cargo.toml.in > "$consumer/Cargo.toml"
# The workspace's versions of everything else, as a user's lock would
# hold after `cargo add`.
cp Cargo.lock "$consumer/"
echo "scripts/package.sh: building and running the consumer (target/consumer)"
# (In the workspace's target folder, sharing its compiled dependencies.)
(cd "$consumer" && CARGO_TARGET_DIR="$target" cargo run -j"$jobs" -- "$consumer/consumer.png")
