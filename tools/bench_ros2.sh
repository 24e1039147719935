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

# The subscriber's window on B's fused images: from the first image it hears
# to 2 s after A's last cycle; ages also without the first SETTLE s.
SETTLE=2
TAIL=2
# Starts the subscriber (in namespace $1, or here when it is "-") and waits
# until it is matched to all 16 sensors' fused topics; sets PROBE_PID.
start_probe() {
    local ns=()
    [ "$1" = - ] || ns=(ip netns exec "$1")
    # A ROS 2 subscriber of large images is given a large receive buffer
    # too, as ROS 2's documentation advises for Cyclone DDS.
    CYCLONEDDS_URI="<Internal><SocketReceiveBufferSize max=\"64MB\"/></Internal>${CYCLONEDDS_URI:+,$CYCLONEDDS_URI}" \
        VKFUSE_PROBE_TRACE="$WORK/probe-$2.trace" "${ns[@]}" "$PROBE" --ros-domain $DOMAIN --sensors 16 \
        --seconds $(( CYCLES / 15 + TAIL )) --settle $SETTLE >"$WORK/probe-$2.json" 2>"$WORK/probe-$2.err" &
    PROBE_PID=$!
    await "$WORK/probe-$2.err" ready 120 || echo "bench_ros2: the subscriber heard of no 16 sensors" >&2
}

# The baselines: one process, no DDS; one process publishing, with the
# subscriber beside it (what fusing and publishing alone add to the age).
start_run local - run --replay "$DATA" --realtime
local_cpu=$(steady_cpu $RUN_PID local)
echo "local (one process): $(fps "$WORK/local.json") fused fps per sensor; CPU from the first cycle $local_cpu s"
start_run local-publish - run --replay "$DATA" --realtime --publish ros2 --ros-domain $DOMAIN
local_publish=$RUN_PID
start_probe - local
local_publish_cpu=$(steady_cpu $local_publish local-publish)
wait $PROBE_PID || true
echo "local publishing: CPU from the first cycle $local_publish_cpu s; subscriber beside it: $(cat "$WORK/probe-local.json")"

# B fuses (publishing or not) what A plays. A plays the recording twice: the
# first time B starts (takes the background, builds its plans) and falls
# behind; the second, B is a fusion host already running when its capture
# host starts, and that is what is measured: B's CPU from A's first cycle to
# TAIL s after A's last (what B still had queued), and, when B publishes, a
# subscriber on B that is matched to all 16 sensors' fused topics before A
# starts and hears every image stamped after that.
# Datagrams dropped in B's namespace so far because a socket's buffer was full.
rcvbuf_errors() { ip netns exec $B awk '/^Udp:/ { n++ } /^Udp:/ && n == 2 { print $6 }' /proc/net/snmp; }
distributed() {
    local tag=$1; shift
    start_run "$tag-b" $B run --source ros2 --ros-domain $DOMAIN --timeout 2 --startup-timeout 300 "$@"
    local b=$RUN_PID
    start_run "$tag-a1" $A run --replay "$DATA" --realtime --capture-only --publish ros2 --publish-frames \
        --ros-domain $DOMAIN --publish-wait 120
    wait $RUN_PID || true
    local probe=""
    if [ "$tag" = publish ]; then
        start_probe $B two-hosts
        probe=$PROBE_PID
    fi
    start_run "$tag-a" $A run --replay "$DATA" --realtime --capture-only --publish ros2 --publish-frames \
        --ros-domain $DOMAIN
    local a=$RUN_PID
    await "$WORK/$tag-a.err" "cycle 1/" 600 || true
    local b_before a_cpu b_after start_s end_s drops_before
    drops_before=$(rcvbuf_errors)
    b_before=$(cpu_of $b)
    start_s=$(date +%s.%N)
    a_cpu=$(steady_cpu $a "$tag-a")
    sleep $TAIL
    end_s=$(date +%s.%N)
    b_after=$(cpu_of $b)
    kill -TERM $b 2>/dev/null || true
    wait $b || true
    [ -z "$probe" ] || wait $probe || true
    B_CPU=$(awk -v a="$b_after" -v b="$b_before" 'BEGIN { printf "%.2f", a - b }')
    local drops=$(( $(rcvbuf_errors) - drops_before ))
    echo "two hosts, B $tag: CPU from A's first cycle to ${TAIL} s after its last: A $a_cpu s, B $B_CPU s" \
        "over $(awk -v s="$start_s" -v e="$end_s" 'BEGIN { printf "%.1f", e - s }') s;" \
        "datagrams B's full socket buffers dropped: $drops"
}
# Alternate rounds (ROUNDS, default 3) of B quiet and B publishing: this
# host's CPU times vary from run to run by more than publishing costs.
: >"$WORK/rounds.txt"
for round in $(seq "${ROUNDS:-3}"); do
    distributed quiet
    quiet_cpu=$B_CPU
    distributed publish --publish ros2
    echo "$quiet_cpu $B_CPU $(cat "$WORK/probe-two-hosts.json")" >>"$WORK/rounds.txt"
    echo "round $round: publishing costs B $(awk -v p="$B_CPU" -v q="$quiet_cpu" \
        'BEGIN { printf "%+.1f", 100 * (p - q) / q }') % CPU; subscriber on B: $(cat "$WORK/probe-two-hosts.json")"
done
# Over the rounds: the median of each figure, and the worst.
python3 - "$WORK/rounds.txt" <<'PY'
import json, statistics, sys
rounds = []
for line in open(sys.argv[1]):
    quiet, publish, probe = line.split(" ", 2)
    rounds.append((float(quiet), float(publish), json.loads(probe)))
cost = [100 * (p - q) / q for q, p, _ in rounds]
fewest = [min(s["images"] for s in r["sensors"].values()) if r["sensors_heard"] else 0 for _, _, r in rounds]
def figure(name, values, unit):
    print(f"{name}: median {statistics.median(values):.1f}{unit}, rounds " + ", ".join(f"{v:.1f}" for v in values))
figure("publishing costs B (CPU over B quiet)", cost, " %")
figure("slowest sensor's fused images per s at the subscriber", [r["slowest_fps"] for _, _, r in rounds], "")
figure("fewest fused images of one sensor (of its cycles played)", fewest, "")
for key in ("age_ms", "age_ms_settled"):
    for q in ("p50", "p99"):
        figure(f"capture to subscriber, {q} in ms ({'all images' if key == 'age_ms' else 'after the first %g s' % rounds[0][2]['settle_s']})",
               [r[key][q] for _, _, r in rounds], "")
PY
