#!/bin/sh
# CTest entry of the browser tests: [--firefox] [--script NAME.mjs] HQVIEW
# SOURCE_DIR OUT_DIR (default report_test.mjs). --firefox runs the script
# with HQVIEW_VIEWER_BROWSER=firefox on a virtual X server (xvfb-run):
# headless Firefox has no WebGL, Firefox on X draws with Mesa's llvmpipe.
# Exit 77 (CTest SKIP) only when Node.js or Chromium is absent; a missing
# playwright-core is a failure (scripts/test runs `npm ci` here).
here="$(cd "$(dirname "$0")" && pwd)"
script=report_test.mjs
firefox=0
if [ "$1" = "--firefox" ]; then firefox=1; shift; fi
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
if [ "$firefox" = 1 ]; then
  if ! command -v xvfb-run >/dev/null 2>&1; then
    echo "FAIL: xvfb-run is missing (Debian: apt-get install xvfb xauth; scripts/setup does)"
    exit 1
  fi
  if [ ! -d "$here/node_modules/puppeteer-core" ]; then
    echo "FAIL: $here/node_modules/puppeteer-core is missing: run 'npm ci' in $here (scripts/test does)"
    exit 1
  fi
  HQVIEW_VIEWER_BROWSER=firefox exec xvfb-run -a -s "-screen 0 1920x1200x24" node "$here/$script" "$@"
fi
exec node "$here/$script" "$@"
