#!/usr/bin/env bash
# The long checks, run before a release (not in CI: about 35 minutes on 2
# cores on top of a build): libFuzzer on every input parser, the soaks at full
# length, and the vulkan label under every simulated GPU variant. Needs the quick start's build (bash tools/quickstart.sh test).
#
#   bash tools/long_checks.sh            fuzz 60 s per target, full soaks
#   FUZZ_SECONDS=600 bash tools/long_checks.sh
set -euo pipefail
cd "$(dirname "$0")/.."
FUZZ_SECONDS=${FUZZ_SECONDS:-60}

declare -a STAGES=()
stage_start=$SECONDS
stage_done() {
    STAGES+=("$(printf '%-32s %5d s' "$1" $((SECONDS - stage_start)))")
    stage_start=$SECONDS
}
trap 'printf "long_checks: %s\n" "${STAGES[@]}"' EXIT
[ -x build/vkfuse ] || bash tools/quickstart.sh test

# 1. libFuzzer, FUZZ_SECONDS per target, from the committed seeds and regressions;
#    what the run discovers stays in build-fuzz/ (a crash fails CI and leaves
#    build-fuzz/crash-<target>-*: add it to fuzz/regressions/<target>/).
FUZZ_PACKAGES=(clang-14 libclang-rt-14-dev)
missing=()
for p in "${FUZZ_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVKFUSE_FUZZ=ON \
    -DVKFUSE_BUILD_TESTS=OFF -DVKFUSE_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_png fuzz_npy fuzz_args fuzz_mcap fuzz_ws
for target in png npy args mcap ws; do
    mkdir -p "build-fuzz/found-$target"
    extra=()
    [ -f "fuzz/$target.dict" ] && extra+=("-dict=fuzz/$target.dict")
    inputs=("fuzz/corpus/$target")
    [ -d "fuzz/regressions/$target" ] && inputs+=("fuzz/regressions/$target")
    status=0
    max_len=4096
    [ "$target" = mcap ] && max_len=65536  # a recording of two small sensors
    "build-fuzz/fuzz/fuzz_$target" -max_total_time="$FUZZ_SECONDS" -max_len="$max_len" -print_final_stats=1 "${extra[@]}" \
        -artifact_prefix="build-fuzz/crash-$target-" "build-fuzz/found-$target" "${inputs[@]}" \
        >"build-fuzz/fuzz-$target.log" 2>&1 || status=$?
    echo "fuzz_$target: $(grep -E '^Done [0-9]+ runs' "build-fuzz/fuzz-$target.log" || echo 'no summary')"
    if [ "$status" -ne 0 ]; then
        tail -40 "build-fuzz/fuzz-$target.log" >&2
        echo "long_checks: fuzz_$target failed (status $status); the input is build-fuzz/crash-$target-*" >&2
        exit 1
    fi
done
# The Python module's entry points, random calls for as long (CI's python.fuzz: 20 s).
if [ -d build/python/vkfuse ]; then
    PYTHONPATH=build/python python3 tests/python/fuzz_entry_points.py "$FUZZ_SECONDS"
fi
stage_done "fuzzing (6 x $FUZZ_SECONDS s)"

# 2. Soaks. (a) Plan::run 100,000 times: memory flat, output bit-identical for
#    identical input, no Vulkan object leaked (64x48 frames: ~2 ms a cycle on
#    lavapipe). (b) `vkfuse run` on a simulated DIGIT with a virtual clock -
#    capture threads, LED switching, background model - 100,000 cycles on the
#    CPU path (~8 ms a cycle) with memory watched from outside, then 10,000 on
#    the Vulkan path with the validation layer's object tracking (~25 ms a
#    QVGA cycle on lavapipe: 100,000 would take 45 minutes).
./build/tests/vkfuse_soak --cycles 100000 --width 64 --height 48
stage_done "soak: Plan::run (100k cycles)"
bash tests/soak/rig_soak.sh build/vkfuse 100000 --method brovey --backend cpu --motion tap --motion-period 0.4
stage_done "soak: vkfuse run cpu (100k)"
bash tests/soak/rig_soak.sh build/vkfuse 10000 --method wavelet --backend vulkan --skip off
stage_done "soak: vkfuse run vulkan (10k)"
# (c) Tile-sparse fusion (--skip tiles, the default) on a ball sliding across
#     the gel: every cycle fuses part of the frame, from records rewritten
#     each run.
bash tests/soak/rig_soak.sh build/vkfuse 10000 --backend vulkan --object ball --motion slide --motion-period 1
stage_done "soak: vkfuse run vulkan tiles (10k)"

# 3. The whole vulkan label under each way a GPU differs from lavapipe:
#    compensated float32 filters and every simulated device profile (CI runs
#    the first; the label's VulkanDeviceProfiles runs every method under each
#    profile).
bash tools/vulkan_variants.sh build
stage_done "vulkan label: GPU variants"
