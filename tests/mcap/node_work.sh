# Sourced by the tests/mcap checks: node_work WORK installs the pinned npm
# packages (package-lock.json) into WORK once, and again only when the lock
# file changes; the scripts are copied beside them.
node_work() {
    local work=$1 here
    here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
    mkdir -p "$work"
    if ! cmp -s "$here/package-lock.json" "$work/package-lock.json" || [ ! -d "$work/node_modules/@mcap/support" ]; then
        cp "$here/package.json" "$here/package-lock.json" "$work/"
        (cd "$work" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
    fi
    cp "$here"/*.mjs "$work/"
}
