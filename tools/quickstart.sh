#!/usr/bin/env bash
# vkfuse quick start: installs what is missing (Debian 12, as root), builds, then
#   run   the main job: `vkfuse run` on the simulated DIGIT (or a real sensor when supported), best Vulkan device else CPU
#   test  the whole test suite, Vulkan tests included (on lavapipe when no GPU)
#   bench the default vkfuse-bench run with its peers (PyWavelets, OpenCV + numpy, OpenCV C++),
#         writing bench.json
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(cmake make g++ pkg-config libpng-dev libjpeg62-turbo-dev libzstd-dev liblz4-dev libgtest-dev libvulkan-dev libvulkan1
          mesa-vulkan-drivers vulkan-validationlayers glslang-tools pybind11-dev python3-dev
          cyclonedds-dev cyclonedds-tools  # Cyclone DDS: `vkfuse run --publish ros2`
          libboost1.81-dev)  # Boost.Beast: `vkfuse run --serve`

# What the ros2 tests read vkfuse's topics with (Fast DDS, the other DDS ROS 2
# ships), and make two hosts of one machine with (network namespaces, nftables).
ROS2_TEST_PACKAGES=(libfastrtps-dev libfastcdr-dev nftables iproute2)

# What the Python module's tests need: pytest, the peers it is checked against,
# PyTorch (tensors in and out), mypy (the type stubs) and pip in a venv (`pip install .`).
PYTHON_TEST_PACKAGES=(python3-pytest python3-numpy python3-pywt python3-opencv python3-torch python3-mypy
                      python3-venv python3-pip python3-setuptools python3-wheel libdlpack-dev)

# What reads vkfuse's MCAP files back in the tests (tests/mcap: @mcap/core from
# npm), and the real browser and protocol client the live page is checked with
# (tests/serve: Debian's chromium driven by puppeteer-core from npm, Python's
# websockets). Node's npm comes with it from NodeSource, from Debian as its own package.
NODE_TEST_PACKAGES=(nodejs chromium python3-websockets)

# What the hardware-in-the-loop test needs (ctest -L hil, tests/hil): QEMU to
# boot Debian's kernel with emulated DIGITs, busybox for its initramfs,
# v4l2-compliance. VKFUSE_HIL=0 leaves the test (and these) out.
HIL_PACKAGES=(qemu-system-x86 busybox-static v4l-utils xz-utils)
HIL_CMAKE=ON
if [ "${VKFUSE_HIL:-1}" = 0 ]; then
    HIL_PACKAGES=()
    HIL_CMAKE=OFF
fi

# What the bench's peers need: the Python pipelines and the OpenCV C++ one.
PEER_PACKAGES=(python3-numpy python3-pywt python3-opencv libopencv-dev)

install_missing() {
    local missing=()
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    [ ${#missing[@]} -eq 0 ] && return
    if [ "$(id -u)" -ne 0 ]; then
        echo "quickstart: missing packages ${missing[*]}; run as root (or sudo) to install them" >&2
        exit 2
    fi
    echo "quickstart: installing ${missing[*]}"
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# Debian 12's lavapipe (Mesa 22.3) runs our kernels about 1.7x slower than bookworm-backports
# (Mesa 25). On bookworm the driver comes from there, pinned so that only it and the Mesa/libdrm
# libraries it needs do; everything else stays the release's. VKFUSE_LAVAPIPE=debian keeps the
# release's own driver (and leaves apt's sources alone).
BACKPORTS_LIST=/etc/apt/sources.list.d/vkfuse-bookworm-backports.sources
BACKPORTS_PIN=/etc/apt/preferences.d/vkfuse-lavapipe
lavapipe_from_backports() {
    [ "${VKFUSE_LAVAPIPE:-backports}" = debian ] && return
    grep -qs '^VERSION_CODENAME=bookworm$' /etc/os-release || return 0
    dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null | grep -q '~bpo12' && return
    if [ "$(id -u)" -ne 0 ]; then
        echo "quickstart: lavapipe from bookworm-backports needs root (VKFUSE_LAVAPIPE=debian keeps Debian's own)" >&2
        exit 2
    fi
    echo "quickstart: installing lavapipe from bookworm-backports (Mesa 25, faster; VKFUSE_LAVAPIPE=debian keeps Debian 12's)"
    grep -rqs 'bookworm-backports' /etc/apt/sources.list /etc/apt/sources.list.d/ ||
        printf '%s\n' 'Types: deb' 'URIs: http://deb.debian.org/debian' 'Suites: bookworm-backports' \
            'Components: main' 'Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg' >"$BACKPORTS_LIST"
    printf '%s\n' '# vkfuse quick start: lavapipe and the Mesa/libdrm libraries it needs from backports' \
        'Package: mesa-vulkan-drivers mesa-libgallium libegl-mesa0 libgbm1 libgl1-mesa-dri libglx-mesa0 libglapi-mesa libdrm* libllvm*' \
        'Pin: release n=bookworm-backports' 'Pin-Priority: 990' >"$BACKPORTS_PIN"
    if ! apt-get update -qq || ! DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
            mesa-vulkan-drivers >/dev/null; then
        rm -f "$BACKPORTS_LIST" "$BACKPORTS_PIN"
        echo "quickstart: bookworm-backports unreachable; keeping Debian 12's lavapipe" >&2
    fi
}

# build [TARGET...]: everything, or only the targets named (and what they need).
build() {
    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DVKFUSE_HIL=$HIL_CMAKE >/dev/null
    cmake --build build -j"$(nproc)" ${1:+--target "$@"}
}

run_main_job() {
    ./build/vkfuse info
    # The DIGITs plugged in (else one simulated DIGIT pressing a coin, said in one line), cycling
    # the paper's best pair (15,15,15) + (0,15,0) and fusing every cycle with its best method
    # (wavelet, bior4.4), in real time.
    ./build/vkfuse run --cycles 120 --out out --replace  # out/ from an earlier quick start is replaced
    echo "quickstart: wrote out/metrics.jsonl, out/fused/<serial>/*.png, out/side_by_side/"
}

run_tests() {
    cd build
    ctest --output-on-failure -j"$(nproc)"
}

case "${1:-}" in
    run) install_missing "${PACKAGES[@]}"; lavapipe_from_backports; build vkfuse_cli; run_main_job ;;
    test) install_missing "${PACKAGES[@]}" "${PYTHON_TEST_PACKAGES[@]}" "${ROS2_TEST_PACKAGES[@]}" "${HIL_PACKAGES[@]}" \
              "${NODE_TEST_PACKAGES[@]}"
          command -v npm >/dev/null || install_missing npm
          lavapipe_from_backports
          build; run_tests ;;
    bench) install_missing "${PACKAGES[@]}" "${PEER_PACKAGES[@]}"; lavapipe_from_backports; build vkfuse-bench
           ./build/bench/vkfuse-bench --json bench.json ;;
    *) echo "usage: bash tools/quickstart.sh run|test|bench" >&2; exit 2 ;;
esac
