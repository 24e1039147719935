#!/usr/bin/env bash
# ctest serve.live: check_live.py with its browser driver (puppeteer-core,
# pinned in package-lock.json) installed into WORK/node once.
#
#   check_live.sh VKFUSE PYTHON WORK
set -euo pipefail
vkfuse=$1 python=$2 work=$3
here=$(cd "$(dirname "$0")" && pwd)
source "$here/../node_work.sh"
node_work "$here" "$work/node"
exec "$python" "$here/check_live.py" "$vkfuse" "$work/node" "$work/run"
