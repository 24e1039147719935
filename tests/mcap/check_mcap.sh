#!/usr/bin/env bash
# vkfuse's MCAP files against an independent reader (ctest io.mcap_independent):
# the sample (mcap_sample.hpp) written in one chunk and in many small ones,
# uncompressed, zstd and lz4 (@mcap/support's decompressors),
# read back by @mcap/core (npm, pinned by package-lock.json, installed once
# into WORK) indexed and streamed with CRCs checked; every message must come
# back as written, and the statistics must count them.
#
#   check_mcap.sh SAMPLE_PROGRAM WORK
set -euo pipefail
sample=$1 work=$2
source "$(dirname "$0")/../node_work.sh"
node_work "$(cd "$(dirname "$0")" && pwd)" "$work"
for compression in none zstd lz4; do
    for chunk in 1000000 2048; do
        what="$compression, chunk $chunk"
        "$sample" "$work/sample.mcap" "$chunk" "$compression" >"$work/want.txt"
        node "$work/read_mcap.mjs" "$work/sample.mcap" >"$work/got.txt"
        tail -1 "$work/got.txt"
        head -n -1 "$work/got.txt" | diff "$work/want.txt" - >/dev/null ||
            { echo "$what: @mcap/core read other messages than were written"; diff "$work/want.txt" <(head -n -1 "$work/got.txt") | head; exit 1; }
        grep -q "^statistics messages 120 schemas 2 channels 3 .* compression ${compression/none/}\$" "$work/got.txt" ||
            { echo "$what: statistics or compression disagree"; exit 1; }
    done
done
echo "mcap: @mcap/core reads the samples (uncompressed, zstd, lz4; one chunk and many) back message for message"
