# Runs inside the HIL virtual machine (tests/hil/run_hil.sh): two emulated
# DIGITs plugged in at once, D20001 with firmware 2.00 and D10001 with 1.00
# (which also cuts every 5th MJPEG frame short); the DIGIT tests against each
# (the other one plugged in beside it); `vkfuse devices`, v4l2-compliance and
# `vkfuse run` on the first.
failed=0
export GTEST_COLOR=no VKFUSE_EMULATOR_TRACE=1 VKFUSE_USBIP_TRACE=1
latency_ms=25
start_unit() {  # serial, bcdDevice, extra emulator options; sets pid_<serial>
    vkfuse-digit-emulator --serial "$1" --firmware "$2" --latency-ms $latency_ms \
        --prerender 0,0,0+15,0,0+0,15,0+0,0,15+5,5,5 $3 >/tmp/emulator-$1.log 2>&1 &
    eval "pid_$1=$!"
}
wait_unit() {  # serial; sets node_<serial> once the host has its capture node
    log=/tmp/emulator-$1.log
    for i in $(seq 1 600); do grep -q ready "$log" && break; sleep 0.1; done
    grep ready "$log" || { cat "$log"; dmesg | tail -20; return 1; }
    eval "node_$1=$(awk '/ready/ {print $4; exit}' "$log")"
}
unit_under_test() {  # serial, firmware, the other unit's serial
    pid=$(eval echo "\$pid_$1")
    export VKFUSE_HIL_SERIAL=$1 VKFUSE_HIL_FIRMWARE=$2 VKFUSE_HIL_OTHER=$3 VKFUSE_HIL_LATENCY_MS=$latency_ms
    export VKFUSE_HIL_UNPLUG="kill -USR1 $pid" VKFUSE_HIL_REPLUG="kill -USR2 $pid"
    export VKFUSE_HIL_PAUSE="kill -HUP $pid" VKFUSE_HIL_RESUME="kill -HUP $pid"
}
stop_unit() {
    pid=$(eval echo "\$pid_$1")
    kill "$pid"
    for i in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -0 "$pid" 2>/dev/null && { echo "hil: the emulator of $1 did not exit on SIGTERM"; kill -9 "$pid"; failed=1; }
    wait "$pid" 2>/dev/null
}
on_failure() {
    failed=1
    for s in D20001 D10001; do tail -12 /tmp/emulator-$s.log | sed "s/^/hil: emulator $s: /"; done
    dmesg | tail -8
}

start_unit D20001 0200
start_unit D10001 0100 "--corrupt-mjpeg-every 5"
wait_unit D20001 || exit 1
wait_unit D10001 || exit 1
vkfuse devices
v4l2-compliance -d "$node_D20001" 2>&1 | grep -E "^Total for|FAIL|fail:|warn" | sed 's/^/v4l2-compliance: /'

unit_under_test D20001 2.00 D10001
vkfuse_hil_tests --gtest_filter='HilDigit.Discovery*:HilDigit.Each*:HilDigit.SwitchTiming*:HilDigit.ASilent*:HilDigit.Unplug*' || on_failure
vkfuse run --backend cpu --cycles 20 --background-frames 2 --method brovey --sensor D20001 >/tmp/run.json 2>/tmp/run.err || failed=1
sed 's/^/hil: vkfuse run: /' /tmp/run.err | head -3
echo "hil: vkfuse run: $(cut -c1-160 /tmp/run.json)"
grep -q '"fused": 20' /tmp/run.json || failed=1
# Sliding windows on the same unit: every fused window's frames within the
# bound its switch timing gives (the emulator's jitter under QEMU is tens of
# milliseconds, and the CPU fusion here slower than the camera: the contract
# holds whatever the pace).
vkfuse run --backend cpu --cycles 20 --background-frames 2 --method brovey --sensor D20001 --window sliding \
    --out /tmp/slide >/tmp/slide.json 2>/tmp/slide.err || failed=1
bound=$(sed -n 's/.*"window_bound_s": \([0-9.e+-]*\).*/\1/p' /tmp/slide.json)
widest=$(sed -n 's/.*"window_span_s": \([0-9.e+-]*\).*/\1/p' /tmp/slide/metrics.jsonl | awk 'w < $1 + 0 { w = $1 + 0 } END { print w + 0 }')
echo "hil: vkfuse run --window sliding: $(cut -c1-160 /tmp/slide.json); widest window ${widest} s, bound ${bound} s"
grep -q '"fused": 20' /tmp/slide.json && grep -q '"window": "sliding"' /tmp/slide.json || failed=1
awk -v w="$widest" -v b="$bound" 'BEGIN { exit !(b > 0 && w > 0 && w <= b) }' || {
    failed=1; echo "hil: a sliding window spans more than its bound"; }
# The same unit from Python (vkfuse.Rig), where run_hil.sh bundled it.
if [ -x /usr/bin/python3 ]; then
    PYTHONPATH=/hil/python /usr/bin/python3 /hil/rig_from_python.py D20001 >/tmp/python.log 2>&1 || { failed=1; echo "hil: python: failed"; }
    tail -4 /tmp/python.log | sed 's/^\([^h]\)/hil: python: \1/'
fi

unit_under_test D10001 1.00 D20001
export VKFUSE_HIL_CORRUPT_EVERY=5
vkfuse_hil_tests --gtest_filter='HilDigit.Discovery*:HilDigit.OldFirmware*:HilDigit.ACorrupt*' || on_failure

# The rig over both units (settings old firmware can light too), D20001
# unplugged mid-run and plugged back: it fails by serial while D10001 goes on,
# and rejoins. Each step waits for what it needs, not for a time, so a slow
# (loaded) host changes nothing: five cycles in, the unplug; the emulator
# says "unplugged" once the host has let the device go; the replug once the
# rig has reported D20001 failed (each bounded at two minutes).
vkfuse run --backend cpu --cycles 60 --background-frames 0 --method brovey --sequence 15,15,15+5,5,5 \
    --sensor D20001 --sensor D10001 --out /tmp/rig >/tmp/rig.json 2>/tmp/rig.err &
run=$!
staged_metrics() { cat /tmp/.vkfuse-partial-*/metrics.jsonl 2>/dev/null; }
wait_for() {  # what, command: polls command every 0.1 s for two minutes
    for i in $(seq 1 1200); do eval "$2" && return 0; sleep 0.1; done
    echo "hil: rig: $1 did not happen within two minutes"; failed=1; return 1
}
unplugs=$(grep -c "unplugged D20001" /tmp/emulator-D20001.log)
wait_for "five cycles" '[ "$(staged_metrics | wc -l)" -ge 10 ]'
kill -USR1 "$pid_D20001"; echo "hil: rig: D20001 unplugged at $(cut -d' ' -f1 /proc/uptime) s"
wait_for "the unplug" '[ "$(grep -c "unplugged D20001" /tmp/emulator-D20001.log)" -gt "$unplugs" ]'
wait_for "D20001 failed" 'staged_metrics | grep -q "\"sensor\": \"D20001\", \"status\": \"failed\""'
kill -USR2 "$pid_D20001"; echo "hil: rig: D20001 plugged back at $(cut -d' ' -f1 /proc/uptime) s"
wait $run || { failed=1; tail -3 /tmp/rig.err | sed 's/^/hil: rig: /'; }
for s in D20001 D10001; do  # each sensor's statuses, cycle by cycle, runs of one status joined: "ok x12, failed x5, ..."
    runs=$(sed -n "s/.*\"sensor\": \"$s\", \"status\": \"\([a-z]*\)\".*/\1/p" /tmp/rig/metrics.jsonl |
           uniq -c | awk '{printf "%s%s x%d", (NR > 1 ? ", " : ""), $2, $1}')
    echo "hil: rig: $s: $runs"
    eval "runs_$s=\"\$runs\""
done
case $runs_D10001 in "ok x"*[0-9]) case $runs_D10001 in *,*) failed=1 ;; esac ;; *) failed=1 ;; esac
case $runs_D20001 in "ok x"*", failed x"*", ok x"*[0-9]) ;; *) echo "hil: rig: D20001 did not fail and rejoin"; failed=1 ;; esac
# vhci_hcd drops a device that answers a transfer it no longer has: show what
# the emulator did around each such answer.
for n in $(dmesg | sed -n 's/.*cannot find a urb of seqnum \([0-9]*\).*/\1/p'); do
    failed=1
    grep -h -B25 -A5 -w "$n" /tmp/emulator-D*.log | grep -v setup | sed "s/^/hil: usbip trace around $n: /"
done
stop_unit D20001
stop_unit D10001
exit $failed
