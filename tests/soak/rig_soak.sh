#!/usr/bin/env bash
# rig_soak.sh: `vkfuse run` on a simulated DIGIT with a virtual clock for many
# cycles - the rig's capture threads, LED switching, background model and
# per-cycle fusion, as a robot would run them for days - watching the
# process's resident memory from outside (/proc/PID/status, every second).
#
#   rig_soak.sh VKFUSE CYCLES [vkfuse run options...]
#
# Passes when vkfuse exits 0 having fused every cycle with no error, printed
# no Vulkan validation message (VKFUSE_VALIDATION=1: the layer's object
# tracker reports any object left at teardown), and its resident memory
# stopped growing: a leak grows with every cycle, a driver's pools fill to a
# steady size and stop (lavapipe, Mesa 25: 3-7 MiB in 1 MiB steps over the
# first 3,000-5,400 wavelet cycles, depending on the host, then flat). So over
# the last 40 % of the samples memory may grow by less than 1 MiB, and from
# the end of warm-up (the first tenth of the samples, at least 5 s) by less
# than 16 MiB. Prints the memory curve (start,
# after warm-up, ten points to the end) and one JSON line.
set -euo pipefail

if [ $# -lt 2 ]; then
    echo "usage: rig_soak.sh VKFUSE CYCLES [vkfuse run options...]" >&2
    exit 2
fi
vkfuse=$1
cycles=$2
shift 2

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

start=$SECONDS
VKFUSE_VALIDATION=1 "$vkfuse" run --virtual-clock --cycles "$cycles" "$@" >"$work/summary.json" 2>"$work/stderr" &
pid=$!
samples=()  # resident kB, one per second
while kill -0 "$pid" 2>/dev/null; do
    rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
    [ -n "$rss" ] && samples+=("$rss")
    sleep 1
done
status=0
wait "$pid" || status=$?
seconds=$((SECONDS - start))

problems=()
[ "$status" -eq 0 ] || problems+=("vkfuse exited with status $status")
fused=$(grep -o '"fused": [0-9]*' "$work/summary.json" | grep -o '[0-9]*$' || echo 0)
[ "$fused" = "$cycles" ] || problems+=("fused $fused of $cycles cycles")
grep -q '"errors": \[\]' "$work/summary.json" || problems+=("the summary lists errors")
validation=$(grep -c 'Vulkan validation' "$work/stderr" || true)
[ "$validation" -eq 0 ] || problems+=("$validation validation messages")

n=${#samples[@]}
if [ "$n" -lt 10 ]; then
    problems+=("only $n memory samples: the run was too short to judge")
    warm=0 growth=0 curve=""
else
    warm=$((n / 10 > 5 ? n / 10 : 5))
    peak=0
    for ((i = warm; i < n; ++i)); do [ "${samples[$i]}" -gt "$peak" ] && peak=${samples[$i]}; done
    growth=$((peak - samples[warm]))
    late=$((n * 6 / 10))
    late_peak=0
    for ((i = late; i < n; ++i)); do [ "${samples[$i]}" -gt "$late_peak" ] && late_peak=${samples[$i]}; done
    late_growth=$((late_peak - samples[late]))
    [ "$late_growth" -lt 1024 ] || problems+=("resident memory grew by $late_growth kB over the last 40 % of the run")
    [ "$growth" -lt 16384 ] || problems+=("resident memory grew by $growth kB after warm-up")
    curve="start ${samples[0]} kB, after warm-up (${warm} s) ${samples[$warm]} kB"
    for ((k = 1; k <= 10; ++k)); do
        i=$((warm + (n - 1 - warm) * k / 10))
        curve+=", ${i} s ${samples[$i]}"
    done
fi

echo "rig soak: $cycles cycles of vkfuse run $* in ${seconds} s"
echo "resident memory: $curve; peak growth after warm-up ${growth} kB, over the last 40 % ${late_growth:-0} kB"
tail -3 "$work/stderr" | sed 's/^/  stderr: /' >&2
ok=true
[ ${#problems[@]} -eq 0 ] || ok=false
printf '{"cycles": %s, "seconds": %s, "samples": %s, "rss_start_kb": %s, "rss_after_warmup_kb": %s, "rss_end_kb": %s, "growth_kb": %s, "validation_messages": %s, "ok": %s}\n' \
    "$cycles" "$seconds" "$n" "${samples[0]:-0}" "${samples[$warm]:-0}" "${samples[$((n > 0 ? n - 1 : 0))]:-0}" \
    "$growth" "$validation" "$ok"
if [ "$ok" = false ]; then
    printf 'rig soak failed: %s\n' "${problems[@]}" >&2
    exit 1
fi
