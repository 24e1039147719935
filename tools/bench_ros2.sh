#!/usr/bin/env bash
# A rig across two hosts, measured (issue 35's benchmark): 16 QVGA sensors, 2
# settings, 4 pressing a sliding coin and 12 at rest, skipping on. Host A (a
# network namespace) plays them from a recording at the sensors' own pace as a
# capture host; host B (another, joined by a veth pair) fuses and publishes,
# and a ROS 2 subscriber on B measures each fused image's age on arrival.
# The same recording fused in one process (no DDS) is the baseline.
#
#   sudo tools/bench_ros2.sh [BUILD_DIR] [WORK_DIR]
#
# VETH_MTU sets the link's MTU (default 1500, Ethernet's); CYCLONEDDS_URI, if
# set, configures both hosts' DDS.
#
# Prints one line per measurement; the recording (about 450 MB, 5 minutes to
# make) is kept in WORK_DIR for the next run.
set -euo pipefail
BUILD=$(realpath "${1:-build}")
WORK=$(realpath -m "${2:-/tmp/vkfuse-bench-ros2}")
VKFUSE="$BUILD/vkfuse"
PROBE="$BUILD/bench/vkfuse-ros2-probe"
[ "$(id -u)" -eq 0 ] || { echo "bench_ros2: needs root (network namespaces)" >&2; exit 2; }
[ -x "$PROBE" ] || { echo "bench_ros2: $PROBE missing (a build with ROS 2)" >&2; exit 2; }
mkdir -p "$WORK"
DATA="$WORK/rig16"
CYCLES=150
DOMAIN=$((30 + $$ % 100))

if [ ! -f "$DATA/manifest.json" ]; then
    echo "bench_ros2: recording 16 simulated DIGITs, $CYCLES cycles, into $DATA" >&2
    "$VKFUSE" run --sensors 16 --pressing 4 --motion slide --virtual-clock --cycles $CYCLES --skip off \
        --record "$DATA" >/dev/null
fi

A=vkbench_a$$ B=vkbench_b$$
cleanup() { ip netns del $A 2>/dev/null || true; ip netns del $B 2>/dev/null || true; }
trap cleanup EXIT
ip netns add $A
ip netns add $B
ip link add vba$$ netns $A type veth peer name vbb$$ netns $B
for side in "$A vba$$ 10.77.0.1" "$B vbb$$ 10.77.0.2"; do
    set -- $side
    ip -n "$1" link set lo up
    ip -n "$1" addr add "$3/24" dev "$2"
    ip -n "$1" link set "$2" mtu "${VETH_MTU:-1500}" up multicast on
    ip -n "$1" route add 224.0.0.0/4 dev "$2"
done

# CPU seconds (user + sys) pid has used so far.
cpu_of() { awk -v t="$(getconf CLK_TCK)" '{ printf "%.2f", ($14 + $15) / t }' "/proc/$1/stat" 2>/dev/null || echo 0; }
# Waits until file $1 holds text $2 (at most $3 s).
await() { for _ in $(seq $(( $3 * 20 ))); do grep -q "$2" "$1" 2>/dev/null && return 0; sleep 0.05; done; return 1; }
fps() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print('%.2f' % d['fused_fps_per_sensor'])" "$1"; }

# Runs vkfuse (in namespace $2, or here when it is "-") with the rest of the
# arguments in the background, output to $WORK/$1.{json,err}; sets RUN_PID.
start_run() {
    local tag=$1 ns=$2; shift 2
    if [ "$ns" = - ]; then
        "$VKFUSE" "$@" >"$WORK/$tag.json" 2>"$WORK/$tag.err" &
    else
        ip netns exec "$ns" "$VKFUSE" "$@" >"$WORK/$tag.json" 2>"$WORK/$tag.err" &
    fi
    RUN_PID=$!
}
# The CPU a run spends from its first cycle to its end (a replay decodes the
# recording before it: not part of the rig's cost).
steady_cpu() {
    local pid=$1 tag=$2
    await "$WORK/$tag.err" "cycle 1/" 600 || true
    local before after
    before=$(cpu_of "$pid")
    after=$before
    while kill -0 "$pid" 2>/dev/null; do
        local now
        now=$(cpu_of "$pid")
        [ "$now" = 0 ] || after=$now
        sleep 0.1
    done
    wait "$pid" || true
    awk -v a="$after" -v b="$before" 'BEGIN { printf "%.2f", a - b }'
}

# The baseline: one process, no DDS.
start_run local - run --replay "$DATA" --realtime
local_cpu=$(steady_cpu $RUN_PID local)
echo "local (one process): $(fps "$WORK/local.json") fused fps per sensor; CPU from the first cycle $local_cpu s"

# The last "cycle N/" a run's progress line showed.
cycles_of() { tr '\r' '\n' <"$1" | sed -n 's/^vkfuse run: cycle \([0-9][0-9]*\).*/\1/p' | tail -1; }

# B fuses (publishing or not) what A plays. A plays the recording twice: the
# first time B starts (takes the background, builds its plans) and falls
# behind; the second, B is a fusion host already running when its capture
# host starts, and that is what is measured, from A's first cycle to its last.
distributed() {
    local tag=$1; shift
    start_run "$tag-b" $B run --source ros2 --ros-domain $DOMAIN --timeout 2 --startup-timeout 300 "$@"
    local b=$RUN_PID
    start_run "$tag-a1" $A run --replay "$DATA" --realtime --capture-only --publish ros2 --publish-frames \
        --ros-domain $DOMAIN --publish-wait 120
    wait $RUN_PID || true
    start_run "$tag-a" $A run --replay "$DATA" --realtime --capture-only --publish ros2 --publish-frames \
        --ros-domain $DOMAIN
    local a=$RUN_PID
    await "$WORK/$tag-a.err" "cycle 1/" 600 || true
    local probe=""
    if [ "$tag" = publish ]; then
        ip netns exec $B "$PROBE" --ros-domain $DOMAIN --seconds 8 >"$WORK/probe.json" &
        probe=$!
    fi
    local b_before b_cycles_before a_cpu b_after start_s end_s
    b_before=$(cpu_of $b)
    b_cycles_before=$(cycles_of "$WORK/$tag-b.err")
    b_cycles_before=${b_cycles_before:-0}
    start_s=$(date +%s.%N)
    a_cpu=$(steady_cpu $a "$tag-a")
    end_s=$(date +%s.%N)
    b_after=$(cpu_of $b)
    local b_cycles
    b_cycles=$(cycles_of "$WORK/$tag-b.err")
    kill -TERM $b 2>/dev/null || true
    wait $b || true
    [ -z "$probe" ] || wait $probe
    echo "two hosts, B $tag: CPU while A played: A $a_cpu s, B $(awk -v a="$b_after" -v b="$b_before" \
        'BEGIN { printf "%.2f", a - b }') s over $(awk -v s="$start_s" -v e="$end_s" 'BEGIN { printf "%.1f", e - s }') s" \
        "(B's rig cycles: $(( ${b_cycles:-0} - b_cycles_before )), late sensors included)"
}
distributed quiet
distributed publish --publish ros2
echo "subscriber on B (fused images of B publishing, 8 s from A's first cycle): $(cat "$WORK/probe.json")"
