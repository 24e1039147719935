#!/usr/bin/env bash
# A rig recorded as MCAP, checked end to end (ctest io.mcap_recording):
#  1. `vkfuse run` records 4 simulated DIGITs for 60 cycles into rig.mcap;
#  2. replaying rig.mcap fuses every cycle bit for bit as the live run did;
#  3. an independent reader (read_recording.mjs: @mcap/core with CRCs, the
#     summary and the index; each message decoded by Foxglove's CDR reader
#     from the schema in the file) validates it, and finds every sensor's 60
#     cycles whole, one frame per setting;
#  4. rig.mcap -> folder -> MCAP (lz4) loses nothing: the second file reads
#     back message for message as the first;
#  5. a copy cut in half replays the whole cycles before the cut, says where
#     it stopped, and fuses them as the live run did.
#
#   check_recording.sh VKFUSE WORK
set -euo pipefail
vkfuse=$1 work=$2
source "$(dirname "$0")/../node_work.sh"
node_work "$(cd "$(dirname "$0")" && pwd)" "$work"
run=$work/recording
rm -rf "$run" && mkdir -p "$run" && cd "$run"
fail() { echo "mcap recording: $*"; exit 1; }

"$vkfuse" run --sensors 4 --cycles 60 --virtual-clock --backend cpu --record rig.mcap --out live >/dev/null 2>live.err ||
    { cat live.err; fail "the recording run failed"; }
"$vkfuse" run --replay rig.mcap --backend cpu --out replay >/dev/null 2>replay.err ||
    { cat replay.err; fail "the replay failed"; }
grep -q "rig.mcap" replay.err && { cat replay.err; fail "the replay called a whole recording incomplete"; }
diff -r -x summary.json live replay >/dev/null || fail "the replay fused other images or metrics than the live run"
[ "$(ls replay/fused/SIM-0004 | wc -l)" = 60 ] || fail "the replay did not fuse 60 cycles"

node "$work/read_recording.mjs" rig.mcap >rig.txt || fail "@mcap/core refused rig.mcap"
tail -2 rig.txt
grep -q '^sensors SIM-0001,SIM-0002,SIM-0003,SIM-0004 source "vkfuse run"$' rig.txt || fail "the manifest is not the run's"
# /vkfuse/rig: once, the four sensors and the run's sequence and method.
sensors=$(for i in 1 2 3 4; do printf 'SIM-000%s:SIM_000%s:DIGIT_(simulated):320x240:DIGIT:r/g/b:15,' $i $i; done)
[ "$(grep -c '^rig ' rig.txt)" = 1 ] &&
    grep -qx "rig ${sensors%,} 15,15,15+0,15,0 wavelet/bior4.4 fused=false frames=true background_frames=[1-9][0-9]*" rig.txt ||
    { grep '^rig ' rig.txt; fail "/vkfuse/rig does not describe the run's rig"; }
# Every sensor: cycles 0..59, each with one frame of each setting of the sequence.
awk '$1 == "frame" && $5 >= 0 { n[$2 " " $5]++; s[$2 " " $5 " " $8]++ }
     END { if (length(n) != 240) exit 1; for (k in n) if (n[k] != 2) exit 1; if (length(s) != 480) exit 1 }' rig.txt ||
    fail "the recording does not hold 60 whole cycles of 4 sensors"

"$vkfuse" convert rig.mcap folder >/dev/null 2>&1 || fail "convert to a folder failed"
"$vkfuse" convert --compression lz4 folder back.mcap >/dev/null 2>&1 || fail "convert back to MCAP failed"
node "$work/read_recording.mjs" back.mcap >back.txt || fail "@mcap/core refused back.mcap"
grep -q "compression lz4$" back.txt || fail "back.mcap is not lz4"
diff <(head -n -1 rig.txt) <(head -n -1 back.txt) >/dev/null || fail "MCAP -> folder -> MCAP changed the recording"

head -c $(( $(stat -c %s rig.mcap) / 2 )) rig.mcap >half.mcap
"$vkfuse" run --replay half.mcap --backend cpu --out half >/dev/null 2>half.err || { cat half.err; fail "the cut recording did not replay"; }
grep -q "half.mcap: byte [0-9]*: .*truncated.*; using the [0-9]* frames before it ([0-9]* whole cycles)" half.err ||
    { cat half.err; fail "the cut recording's replay did not say where it stopped"; }
cycles=$(ls half/fused/SIM-0001 | wc -l)
[ "$cycles" -gt 10 ] && [ "$cycles" -lt 60 ] || fail "the cut recording replayed $cycles cycles"
for f in half/fused/*/*.png; do cmp -s "$f" "live/${f#half/}" || fail "$f differs from the live run's"; done
diff <(grep -o '"cycle": [0-9]*, "sensor": "[^"]*", "status": "[a-z]*"' half/metrics.jsonl) \
     <(grep -o '"cycle": [0-9]*, "sensor": "[^"]*", "status": "[a-z]*"' live/metrics.jsonl | head -n $((cycles * 4))) >/dev/null ||
    fail "the cut recording's cycles are not the live run's first $cycles"
echo "mcap recording: 4 sensors x 60 cycles replay bit for bit; @mcap/core and Foxglove's CDR reader validate it;" \
     "folder round trip lossless; cut in half, $cycles whole cycles replay"
