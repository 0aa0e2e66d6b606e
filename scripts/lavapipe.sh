# Mesa's lavapipe (the Vulkan adapter on machines without a GPU), sourced by
# scripts/test.sh and scripts/tour.sh. The ray-query traversal needs
# VK_KHR_ray_query and VK_KHR_acceleration_structure, which lavapipe has
# from Mesa 25 on: Debian bookworm's own mesa-vulkan-drivers is 22.3, so
# ensure_lavapipe adds the bookworm-backports suite (25.0.7) to apt's
# sources and installs from it, as root; elsewhere it says what to run.

mesa_version() {
    dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true
}

lavapipe_has_ray_queries() {
    local v
    v=$(mesa_version)
    [ -n "$v" ] && dpkg --compare-versions "$v" ge 25
}

ensure_lavapipe() {
    if lavapipe_has_ray_queries; then
        return 0
    fi
    if [ "$(id -u)" != 0 ] || ! command -v apt-get >/dev/null; then
        if [ -z "$(mesa_version)" ]; then
            echo "lavapipe.sh: no lavapipe found; wgpu tests need a Vulkan adapter (as root: scripts/test.sh installs Mesa 25's from bookworm-backports)" >&2
        else
            echo "lavapipe.sh: lavapipe $(mesa_version) has no ray queries; the ray-query tests will be skipped (as root: scripts/test.sh installs Mesa 25's from bookworm-backports)" >&2
        fi
        return 0
    fi
    local codename
    codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
    if [ "$codename" = bookworm ]; then
        echo "lavapipe.sh: installing mesa-vulkan-drivers from bookworm-backports (lavapipe with ray queries)"
        if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
            cat >/etc/apt/sources.list.d/bookworm-backports.sources <<'SOURCES'
Types: deb
URIs: http://deb.debian.org/debian
Suites: bookworm-backports
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SOURCES
        fi
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -t bookworm-backports mesa-vulkan-drivers libvulkan1 >/dev/null
    else
        echo "lavapipe.sh: installing mesa-vulkan-drivers (lavapipe)"
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq mesa-vulkan-drivers libvulkan1 >/dev/null
    fi
}
