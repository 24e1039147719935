#!/usr/bin/env bash
# The whole `vulkan` label again under each way a real GPU differs from
# lavapipe (docs/architecture.md, "Simulated devices"): compensated float32
# filters (the arithmetic `auto` picks on every GPU; lavapipe's default is
# float64), kernels reaching their buffers through bindings (as on every GPU;
# lavapipe's default is device addresses), then each simulated device profile. About 4 minutes a variant on an
# idle 2-core host. CI runs a representative subset (.ci/run); this is all of it.
#   bash tools/vulkan_variants.sh [BUILD_DIR]   (default: build, from the quick start)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
[ -x "$build/vkfuse" ] || { echo "vulkan_variants: no build in $build (bash tools/quickstart.sh test builds one)" >&2; exit 2; }
variants=("VKFUSE_FILTER_ARITHMETIC=compensated-float32" "VKFUSE_KERNEL_BUFFERS=bound")
for profile in $("$build/vkfuse" info | sed -n 's/^device profiles: //p' | tr -d ','); do
    variants+=("VKFUSE_DEVICE_PROFILE=$profile")
done
[ ${#variants[@]} -gt 1 ] || { echo "vulkan_variants: vkfuse info lists no device profiles" >&2; exit 2; }
failed=()
for variant in "${variants[@]}"; do
    echo "== ctest -L vulkan with $variant"
    start=$SECONDS
    if (cd "$build" && env "$variant" ctest --output-on-failure -j"$(nproc)" -L vulkan); then
        echo "== $variant: passed in $((SECONDS - start)) s"
    else
        echo "== $variant: FAILED after $((SECONDS - start)) s"
        failed+=("$variant")
    fi
done
[ ${#failed[@]} -eq 0 ] || { echo "vulkan_variants: failed under ${failed[*]}" >&2; exit 1; }
echo "vulkan_variants: the vulkan label passed under all ${#variants[@]} variants"
