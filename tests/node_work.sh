# Sourced by the checks that run node programs (tests/mcap, tests/serve):
# node_work SRC WORK installs SRC's pinned npm packages (SRC/package-lock.json)
# into WORK once, and again only when the lock file changes, and copies SRC's
# scripts (*.mjs) beside them.
node_work() {
    local src=$1 work=$2
    mkdir -p "$work"
    if ! cmp -s "$src/package-lock.json" "$work/package-lock.json" || [ ! -d "$work/node_modules" ]; then
        rm -rf "$work/node_modules"
        cp "$src/package.json" "$src/package-lock.json" "$work/"
        (cd "$work" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
    fi
    cp "$src"/*.mjs "$work/"
}
