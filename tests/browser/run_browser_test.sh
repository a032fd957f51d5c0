#!/bin/sh
# CTest entry of the browser tests: [--script NAME.mjs] HQVIEW SOURCE_DIR OUT_DIR
# (default report_test.mjs).
# Exit 77 (CTest SKIP) only when Node.js or Chromium is absent; a missing
# playwright-core is a failure (scripts/test runs `npm ci` here).
here="$(cd "$(dirname "$0")" && pwd)"
script=report_test.mjs
if [ "$1" = "--script" ]; then script="$2"; shift 2; fi
if ! command -v node >/dev/null 2>&1; then
  echo "SKIP: node not found (Debian: apt-get install nodejs npm)"
  exit 77
fi
if [ ! -x "${HQVIEW_CHROMIUM:-/usr/bin/chromium}" ]; then
  echo "SKIP: chromium not found (Debian: apt-get install chromium)"
  exit 77
fi
if [ ! -d "$here/node_modules/playwright-core" ]; then
  echo "FAIL: $here/node_modules/playwright-core is missing: run 'npm ci' in $here (scripts/test does)"
  exit 1
fi
exec node "$here/$script" "$@"
