#!/usr/bin/env bash
# vkfuse quick start: installs what is missing (Debian 12, as root), builds, then
#   run   the main job: `vkfuse run` on the simulated DIGIT (or a real sensor when supported), best Vulkan device else CPU
#   test  the whole test suite, Vulkan tests included (on lavapipe when no GPU)
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(cmake make g++ pkg-config libpng-dev libgtest-dev libvulkan-dev libvulkan1
          mesa-vulkan-drivers vulkan-validationlayers glslang-tools)

install_missing() {
    local missing=()
    for p in "${PACKAGES[@]}"; do
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

build() {
    cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build build -j"$(nproc)"
}

run_main_job() {
    ./build/vkfuse info
    # One simulated DIGIT pressing a coin, cycling the paper's best pair (15,15,15) + (0,15,0) and
    # fusing every cycle with its best method (wavelet, bior4.4), in real time.
    ./build/vkfuse run --cycles 120 --out out --replace  # out/ from an earlier quick start is replaced
    echo "quickstart: wrote out/metrics.jsonl, out/fused/SIM-0001/*.png, out/side_by_side/coin_SIM-0001.png"
}

run_tests() {
    cd build
    ctest --output-on-failure -j"$(nproc)"
}

case "${1:-}" in
    run) install_missing; build; run_main_job ;;
    test) install_missing; build; run_tests ;;
    *) echo "usage: bash tools/quickstart.sh run|test" >&2; exit 2 ;;
esac
