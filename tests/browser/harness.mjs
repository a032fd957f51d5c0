// What the browser tests share: Chromium's path (exit 77 when absent),
// playwright-core, the Firefox driver of the viewer test, and the failure
// list behind check().
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

// The viewer test runs in Chromium (playwright-core, headless, SwiftShader
// WebGL) or in Debian's firefox-esr (puppeteer-core over WebDriver BiDi:
// playwright-core's BiDi Firefox needs a newer Firefox than ESR). Headless
// Firefox has no WebGL here, so Firefox runs on an X server (run_browser_test.sh
// starts it with xvfb-run) and draws with Mesa's llvmpipe. Both drivers give
// the page calls the test uses: evaluate, mouse.click, screenshot, close.
export const firefoxPath = process.env.HQVIEW_FIREFOX || '/usr/bin/firefox-esr';

export async function launchBrowser(kind) {
  if (kind === 'chromium') {
    const browser = await chromium.launch({
      executablePath: chromiumPath,
      // File access from files: the silhouette check reads views/main_1.png's pixels.
      args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
        '--allow-file-access-from-files'],
    });
    return {
      close: () => browser.close(),
      async newPage(viewport, onNetwork) {
        const page = await browser.newPage({ viewport });
        await page.route('**/*', (route) => {
          if (route.request().url().startsWith('file:')) return route.continue();
          onNetwork();
          return route.abort();
        });
        return page;
      },
      waitFor: (page, fn, timeout) => page.waitForFunction(fn, null, { timeout }),
    };
  }
  if (!fs.existsSync(firefoxPath)) {
    console.log(`SKIP: no Firefox at ${firefoxPath} (install Debian's firefox-esr, or set HQVIEW_FIREFOX)`);
    process.exit(77);
  }
  const { default: puppeteer } = await import('puppeteer-core');
  const browser = await puppeteer.launch({
    browser: 'firefox', executablePath: firefoxPath, headless: false,
    // The silhouette check reads views/main_1.png into a canvas from file://.
    extraPrefsFirefox: { 'webgl.force-enabled': true, 'security.fileuri.strict_origin_policy': false },
  });
  return {
    close: () => browser.close(),
    async newPage(viewport, onNetwork) {
      const page = await browser.newPage();
      await page.setViewport(viewport);
      await page.setRequestInterception(true);
      page.on('request', (request) => {
        if (request.url().startsWith('file:')) return request.continue();
        onNetwork();
        return request.abort();
      });
      return page;
    },
    waitFor: (page, fn, timeout) => page.waitForFunction(fn, { timeout }),
  };
}

// A checkbox or select changed as a person would (the page's listeners run).
export async function setChecked(page, selector, checked) {
  await page.evaluate(([s, c]) => {
    const e = document.querySelector(s);
    if (e.checked !== c) { e.checked = c; e.dispatchEvent(new Event('change', { bubbles: true })); }
  }, [selector, checked]);
}
export async function selectValue(page, selector, value) {
  await page.evaluate(([s, v]) => {
    const e = document.querySelector(s);
    e.value = v;
    e.dispatchEvent(new Event('change', { bubbles: true }));
  }, [selector, value]);
}
