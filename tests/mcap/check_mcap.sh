#!/usr/bin/env bash
# vkfuse's MCAP files against an independent reader (ctest io.mcap_independent):
# the sample (mcap_sample.hpp) written in one chunk and in many small ones,
# read back by @mcap/core (npm, pinned by package-lock.json, installed once
# into WORK) indexed and streamed with CRCs checked; every message must come
# back as written, and the statistics must count them.
#
#   check_mcap.sh SAMPLE_PROGRAM WORK
set -euo pipefail
sample=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$work"
if ! cmp -s "$here/package-lock.json" "$work/package-lock.json" || [ ! -d "$work/node_modules/@mcap/core" ]; then
    cp "$here/package.json" "$here/package-lock.json" "$work/"
    (cd "$work" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
fi
cp "$here/read_mcap.mjs" "$work/"
for chunk in 1000000 2048; do
    "$sample" "$work/sample.mcap" "$chunk" >"$work/want.txt"
    node "$work/read_mcap.mjs" "$work/sample.mcap" >"$work/got.txt"
    tail -1 "$work/got.txt"
    head -n -1 "$work/got.txt" | diff "$work/want.txt" - >/dev/null ||
        { echo "chunk $chunk: @mcap/core read other messages than were written"; diff "$work/want.txt" <(head -n -1 "$work/got.txt") | head; exit 1; }
    grep -q "^statistics messages 120 schemas 2 channels 3 " "$work/got.txt" ||
        { echo "chunk $chunk: statistics disagree"; exit 1; }
done
echo "mcap: @mcap/core reads both samples back message for message"
