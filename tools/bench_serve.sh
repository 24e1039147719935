#!/usr/bin/env bash
# What a live page costs the rig (issue: "the rig's fused fps with a page open
# is within 5 % of without"): `vkfuse run` on 4 simulated DIGITs at their own
# pace (real clock) for SECONDS, once alone and once with --serve and the page
# open in a headless chromium (tests/serve/browse_page.mjs --watch) the whole
# time; prints both fused fps per sensor and their ratio. After the quick
# start's test build (it installs chromium and the page test's npm packages).
#
#   bash tools/bench_serve.sh [SECONDS] [BACKEND]    (default 60, auto)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60} backend=${2:-auto}
vkfuse=build/vkfuse work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
source tests/node_work.sh
node_work tests/serve build/tests/serve/node
fps() { sed -n 's/.*"fused_fps_per_sensor": \([0-9.]*\).*/\1/p' "$1"; }

"$vkfuse" run --sensors 4 --duration "$seconds" --backend "$backend" >"$work/alone.json" 2>/dev/null
"$vkfuse" run --sensors 4 --duration "$seconds" --backend "$backend" --serve 127.0.0.1:0 >"$work/served.json" 2>"$work/served.err" &
run=$!
for _ in $(seq 100); do grep -aq "serving http" "$work/served.err" && break; sleep 0.1; done
url=$(grep -ao "http://127.0.0.1:[0-9]*/" "$work/served.err" | head -1)
node build/tests/serve/node/browse_page.mjs "$url" "$work" --watch "$((seconds - 15))"
wait "$run"
alone=$(fps "$work/alone.json") served=$(fps "$work/served.json")
awk -v a="$alone" -v s="$served" 'BEGIN { printf "fused fps per sensor: alone %s, with the page open %s, ratio %.3f\n", a, s, s / a }'
