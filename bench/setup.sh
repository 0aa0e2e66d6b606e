#!/usr/bin/env bash
# Installs what rt-bench's peers need beyond the Rust build: Embree 3
# (Debian's libembree-dev; the bench loads libembree3.so.3 at run time) and
# the Vulkan driver the wgpu backend and the hand-written kernel run on when
# there is no GPU (Mesa's lavapipe). Run as root; without Embree the bench
# still runs and reports "embree": null with the reason on stderr.
set -euo pipefail
if [ "$(id -u)" != 0 ]; then
    echo "bench/setup.sh: run as root (apt-get install libembree-dev mesa-vulkan-drivers)" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
if apt-cache show libembree-dev > /dev/null 2>&1; then
    apt-get install -y -qq libembree-dev
else
    apt-get install -y -qq libembree3-3
fi
apt-get install -y -qq mesa-vulkan-drivers
ls /usr/lib/*/libembree3.so.3 > /dev/null && echo "bench/setup.sh: Embree 3 installed"
