// What the browser tests share: Chromium's path (exit 77 when absent),
// playwright-core, and the failure list behind check().
import fs from 'node:fs';

export const chromiumPath = process.env.HQVIEW_CHROMIUM || '/usr/bin/chromium';
if (!fs.existsSync(chromiumPath)) {
  console.log(`SKIP: no Chromium at ${chromiumPath} (install Debian's chromium, or set HQVIEW_CHROMIUM)`);
  process.exit(77);
}
export const { chromium } = await import('playwright-core');

export const failures = [];
// Records a failed check (printed at once); `verbose` also prints passes.
export function check(condition, message, verbose = false) {
  if (!condition) {
    failures.push(message);
    console.log(`FAIL: ${message}`);
  } else if (verbose) {
    console.log(`ok: ${message}`);
  }
}
