# Runs inside the HIL virtual machine (tests/hil/run_hil.sh): one emulated
# DIGIT at a time, first firmware 2.00, then 1.00; the DIGIT tests against
# each; `vkfuse devices`, v4l2-compliance and `vkfuse run` on the first.
failed=0
export GTEST_COLOR=no
latency_ms=25
start_unit() {  # serial, bcdDevice, extra emulator options
    vkfuse-digit-emulator --serial "$1" --firmware "$2" --latency-ms $latency_ms \
        --prerender 0,0,0+15,0,0+0,15,0+0,0,15+5,5,5 $3 >/tmp/emulator.log 2>&1 &
    emulator=$!
    for i in $(seq 1 300); do grep -q ready /tmp/emulator.log && break; sleep 0.1; done
    grep ready /tmp/emulator.log || { cat /tmp/emulator.log; dmesg | tail -20; return 1; }
    node=$(awk '/ready/ {print $4}' /tmp/emulator.log)
    export VKFUSE_HIL_SERIAL=$1 VKFUSE_HIL_LATENCY_MS=$latency_ms
    export VKFUSE_HIL_UNPLUG="kill -USR1 $emulator" VKFUSE_HIL_REPLUG="kill -USR2 $emulator"
    export VKFUSE_HIL_PAUSE="kill -HUP $emulator" VKFUSE_HIL_RESUME="kill -HUP $emulator"
}
stop_unit() {
    kill $emulator
    for i in $(seq 1 50); do kill -0 $emulator 2>/dev/null || break; sleep 0.1; done
    kill -0 $emulator 2>/dev/null && { echo "hil: the emulator did not exit on SIGTERM"; kill -9 $emulator; failed=1; }
    wait $emulator 2>/dev/null
    sleep 0.5
}

export VKFUSE_EMULATOR_TRACE=1
start_unit D20001 0200 || exit 1
vkfuse devices
v4l2-compliance -d "$node" 2>&1 | grep -E "^Total for|FAIL|warn" | sed 's/^/v4l2-compliance: /'
VKFUSE_HIL_FIRMWARE=2.00 vkfuse_hil_tests --gtest_filter='HilDigit.Discovery*:HilDigit.Each*:HilDigit.SwitchTiming*:HilDigit.ASilent*:HilDigit.Unplug*' || { failed=1; tail -20 /tmp/emulator.log | sed 's/^/hil: emulator: /'; dmesg | tail -8; }
vkfuse run --backend cpu --cycles 20 --background-frames 2 --method brovey >/tmp/run.json 2>/tmp/run.err || failed=1
sed 's/^/hil: vkfuse run: /' /tmp/run.err | head -3
echo "hil: vkfuse run: $(cut -c1-160 /tmp/run.json)"
grep -q '"fused": 20' /tmp/run.json || failed=1
stop_unit

start_unit D10001 0100 "--corrupt-mjpeg-every 5" || exit 1
export VKFUSE_HIL_CORRUPT_EVERY=5
VKFUSE_HIL_FIRMWARE=1.00 vkfuse_hil_tests --gtest_filter='HilDigit.Discovery*:HilDigit.OldFirmware*:HilDigit.ACorrupt*' || failed=1
stop_unit
exit $failed
