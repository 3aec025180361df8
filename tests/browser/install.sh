#!/usr/bin/env bash
# What the browser tests (tests/browser) need, installed where missing:
# Debian's Chromium, Node.js and npm, and puppeteer-core (pinned in
# package-lock.json; it never downloads a browser) under
# tests/browser/node_modules. Machines that already carry a Node.js with
# its own npm keep them: Debian's npm package would conflict with it, so
# node and npm are looked for on PATH, not asked of dpkg.
# A user who only runs scenes needs none of this.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
need=""
command -v chromium > /dev/null || need="$need chromium"
command -v node > /dev/null || need="$need nodejs"
command -v npm > /dev/null || need="$need npm"
if [ -n "$need" ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends $need
fi
if [ ! -d "$here/node_modules/puppeteer-core" ]; then
  (cd "$here" && npm ci --no-audit --no-fund --loglevel=error)
fi
