#!/usr/bin/env bash
# The check to run on a machine with a real GPU, on a tree built by the quick
# start (bash tools/quickstart.sh test, or its build step): `vkfuse info`, the
# `vulkan` label, and the default bench plus the Vulkan cells at --sensors 1,64, all into one JSON
# (README, "On a real GPU"). Under 8 minutes on a discrete GPU; each step has
# its own time limit, and a step that fails or runs out is recorded as such.
#   bash tools/gpu_check.sh [OUT.json] [BUILD_DIR]   (defaults: gpu_check.json, build)
set -uo pipefail
cd "$(dirname "$0")/.."
out=${1:-gpu_check.json}
build=${2:-build}
for program in "$build/vkfuse" "$build/bench/vkfuse-bench"; do
    [ -x "$program" ] || { echo "gpu_check: $program is missing (build with bash tools/quickstart.sh test)" >&2; exit 2; }
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
start=$SECONDS

# A JSON string of a file's text.
json_text() { sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/\t/\\t/g' "$1" | awk 'BEGIN{printf "\""} {printf "%s\\n", $0} END{printf "\""}'; }

# step NAME LIMIT_S COMMAND...: runs it, output into $work/NAME.log; sets step_rc and step_s.
step() {
    local name=$1 limit=$2
    shift 2
    echo "gpu_check: $name" >&2
    local t=$SECONDS
    timeout "$limit" "$@" >"$work/$name.log" 2>&1
    step_rc=$?
    step_s=$((SECONDS - t))
}

step info 60 "$build/vkfuse" info
info_rc=$step_rc
info_json=$(json_text "$work/info.log")

step vulkan_label 240 bash -c "cd '$build' && ctest -L vulkan -j\"\$(nproc)\" --timeout 120 --output-on-failure"
label_rc=$step_rc
label_s=$step_s
summary=$(grep -E 'tests passed, [0-9]+ tests? failed out of [0-9]+' "$work/vulkan_label.log" | tail -1)
[ -n "$summary" ] || { label_rc=${label_rc/#0/1}; summary="no tests ran"; }  # a tree without the tests is no pass
# ctest's list of failures: "<tab> 12 - Suite.Name (Failed)" with the test's labels after it.
failed_tests=$(sed -n 's/^[[:space:]]*[0-9]* - \([^ ]*\) (.*$/\1/p' "$work/vulkan_label.log" | sed 's/.*/"&"/' | paste -sd, -)
# A failing label keeps its whole log beside the JSON, with each failure's output.
[ "$label_rc" -eq 0 ] || cp "$work/vulkan_label.log" "${out%.json}.vulkan_label.log"

step bench_default 240 "$build/bench/vkfuse-bench" --json "$work/bench_default.json"
default_rc=$step_rc
default_s=$step_s
step bench_sensors 120 "$build/bench/vkfuse-bench" --backend vulkan --sensors 1,64 --json "$work/bench_sensors.json"
sensors_rc=$step_rc
sensors_s=$step_s

array_or_null() { if [ -s "$1" ]; then cat "$1"; else printf 'null'; fi; }
{
    printf '{\n  "seconds": %d,\n' $((SECONDS - start))
    printf '  "info": {"rc": %d, "text": %s},\n' "$info_rc" "$info_json"
    printf '  "vulkan_label": {"rc": %d, "seconds": %d, "summary": "%s", "failed": [%s]},\n' \
        "$label_rc" "$label_s" "$summary" "$failed_tests"
    printf '  "bench_default": {"rc": %d, "seconds": %d, "cells": ' "$default_rc" "$default_s"
    array_or_null "$work/bench_default.json"
    printf '},\n  "bench_sensors": {"rc": %d, "seconds": %d, "cells": ' "$sensors_rc" "$sensors_s"
    array_or_null "$work/bench_sensors.json"
    printf '}\n}\n'
} >"$out.tmp" && mv "$out.tmp" "$out"
echo "gpu_check: wrote $out in $((SECONDS - start)) s (info rc $info_rc, vulkan label rc $label_rc: $summary," \
     "bench rc $default_rc and $sensors_rc)"
[ "$info_rc" -eq 0 ] && [ "$label_rc" -eq 0 ] && [ "$default_rc" -eq 0 ] && [ "$sensors_rc" -eq 0 ]
