#!/usr/bin/env bash
# Runs one browser test (tests/browser/NAME.mjs) with node, after checking
# that what it needs is there (tests/browser/install.sh installs it).
#   run.sh NAME TISSUEFEM SCENE WORKDIR
set -u
here=$(cd "$(dirname "$0")" && pwd)
name=$1
shift
missing=""
command -v node > /dev/null || missing="$missing node"
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || missing="$missing chromium"
[ -d "$here/node_modules/puppeteer-core" ] || missing="$missing puppeteer-core"
if [ -n "$missing" ]; then
  echo "browser test '$name' cannot run: missing$missing; run" \
    "'bash tests/browser/install.sh' first (README's test command does)"
  exit 1
fi
exec node "$here/$name.mjs" "$@"
