// Browser test of --single-file (issue 49): report.html copied alone into an
// empty folder and opened from file:// in headless Chromium with every
// request but the page itself refused (no file access to anything else, no
// network). Checked: every image decodes and is the bundle's own file (the
// data URI's bytes equal views/*.png or *.svg), the boundary page is a
// section with its images, the page holds no src= or href= that leaves it
// but links to the bundle's data files, an injected file name runs no
// script, and --single-file=viewer's embedded viewer draws (a WebGL canvas
// inside the iframe). Batch: OUT/report.html inlines the thumbnails and
// links each mesh's report.html. Screenshots go to OUT/screenshots/.
//
// usage: node single_file_test.mjs HQVIEW SOURCE_DIR OUT_DIR
// exit 0 pass, 1 fail, 77 skipped (no Chromium).

import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

import { check, chromium, chromiumPath, failures } from './harness.mjs';

const [hqview, sourceDir, outDir] = process.argv.slice(2);
if (!hqview || !sourceDir || !outDir) {
  console.error('usage: node single_file_test.mjs HQVIEW SOURCE_DIR OUT_DIR');
  process.exit(2);
}
fs.rmSync(outDir, { recursive: true, force: true });
const shots = path.join(outDir, 'screenshots');
fs.mkdirSync(shots, { recursive: true });
const example = (name) => path.join(sourceDir, 'examples', name);
const run = (args) => execFileSync(hqview, [...args, '-j', '2', '--quiet'], { stdio: 'inherit' });

// The ball with its reference (boundary page) and the viewer embedded; the
// twisted bar under a file name that would run script if not escaped.
const ball = path.join(outDir, 'ball');
run(['analyze', example('ball.mesh'), '--reference', example('ball.off'), '--size', '800x600',
  '--single-file=viewer', '-o', ball]);
const evilName = `"q'&amp;<img src=x onerror="window.hqPwned=1">.mesh`;
const evilDir = path.join(outDir, 'evil-input');
fs.mkdirSync(evilDir, { recursive: true });
fs.copyFileSync(example('twisted_bar.mesh'), path.join(evilDir, evilName));
fs.copyFileSync(example('ball.mesh'), path.join(evilDir, 'ball.mesh'));
// Two methods of one model: the index page shows their thumbnails.
fs.writeFileSync(path.join(evilDir, 'manifest.csv'),
  `mesh,label,model\n"${evilName.replaceAll('"', '""')}",twisted,bar\nball.mesh,mapped,bar\n`);
const batch = path.join(outDir, 'batch');
run(['batch', path.join(evilDir, 'manifest.csv'), '--size', '640x480', '--single-file', '-o', batch]);

// Data files: the only relative links report.html may keep.
const dataFile = (url) => /^(report\.json|summary\.md|timings\.json|data\/[^/]+)$/.test(url);

function attributes(html) {
  return [...html.matchAll(/\s(src|href)="([^"]*)"/g)].map((m) => ({ name: m[1], value: m[2] }));
}

const browser = await chromium.launch({ executablePath: chromiumPath, args: ['--no-sandbox',
  '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'] });

async function open(file, allowed) {
  const page = await browser.newPage({ viewport: { width: 1400, height: 1000 } });
  const refused = [];
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  await page.route('**/*', (route) => {
    const url = route.request().url();
    if (url === pathToFileURL(file).href || allowed(url)) return route.continue();
    refused.push(url);
    return route.abort();
  });
  await page.goto(pathToFileURL(file).href, { waitUntil: 'load' });
  return { page, refused, errors };
}

// ---- one mesh: report.html alone ----
{
  const alone = path.join(outDir, 'alone');
  fs.mkdirSync(alone);
  const file = path.join(alone, 'report.html');
  fs.copyFileSync(path.join(ball, 'report.html'), file);
  const html = fs.readFileSync(file, 'utf8');
  const report = JSON.parse(fs.readFileSync(path.join(ball, 'report.json'), 'utf8'));
  const leaving = attributes(html).filter(({ value }) =>
    !value.startsWith('#') && !value.startsWith('data:') && !dataFile(value));
  check(leaving.length === 0, `report.html: no src/href leaves it but data files (${JSON.stringify(leaving.slice(0, 5))})`);
  check(attributes(html).some(({ value }) => value === 'report.json') &&
    attributes(html).some(({ value }) => value.startsWith('data/')), 'report.html: links to report.json and data/ stay');

  // The budget (docs/contract.md): base64 of what it holds (views, viewer
  // files) plus the pages, no image twice.
  const bytes = (d) => fs.readdirSync(d).reduce((n, f) => n + fs.statSync(path.join(d, f)).size, 0);
  const budget = Math.ceil(4 / 3 * (bytes(path.join(ball, 'views')) + bytes(path.join(ball, 'viewer')) +
    fs.statSync(path.join(ball, 'viewer.html')).size)) + ['index.html', 'boundary.html', 'style.css']
    .reduce((n, f) => n + fs.statSync(path.join(ball, f)).size, 0) + 65536;
  check(fs.statSync(file).size <= budget, `report.html: ${fs.statSync(file).size} bytes within its budget ${budget}`);
  const { page, refused, errors } = await open(file, () => false);
  await page.waitForFunction(() => [...document.images].every((i) => i.complete), null, { timeout: 30000 });
  const images = await page.evaluate(() => [...document.images].map((i) => ({
    ok: i.naturalWidth > 0, src: i.getAttribute('src'), inBoundary: !!i.closest('#boundary') })));
  const broken = images.filter((i) => !i.ok).length;
  check(images.length > 0 && broken === 0, `report.html alone: ${images.length} images, ${broken} not drawn`);
  // Every view file of the bundle's pages is on the page, byte for byte.
  const viewFiles = new Set();
  for (const page of ['index.html', 'boundary.html']) {
    for (const m of fs.readFileSync(path.join(ball, page), 'utf8').matchAll(/<img src="([^"]+)"/g)) viewFiles.add(m[1]);
  }
  const embedded = new Set(images.map((i) => Buffer.from(i.src.split(',')[1] || '', 'base64').toString('base64')));
  const missing = [...viewFiles].filter((f) => !embedded.has(fs.readFileSync(path.join(ball, decodeURIComponent(f))).toString('base64')));
  check(viewFiles.size > 5 && missing.length === 0,
    `report.html: each of the pages' ${viewFiles.size} images is there with the bundle file's bytes (missing ${missing})`);
  const boundaryViews = report.views.filter((v) => v.id.startsWith('boundary_') || v.id === 'uv_error').length;
  check(boundaryViews > 0 && images.filter((i) => i.inBoundary).length >= boundaryViews,
    `report.html: the boundary section holds the boundary views (${images.filter((i) => i.inBoundary).length})`);
  const ids = await page.evaluate(() => { const seen = new Set(); const dup = [];
    for (const e of document.querySelectorAll('[id]')) { if (seen.has(e.id)) dup.push(e.id); seen.add(e.id); } return dup; });
  check(ids.length === 0, `report.html: ids unique across the merged pages (${ids.slice(0, 5)})`);
  const anchors = await page.evaluate(() => [...document.querySelectorAll('a[href^="#"]')]
    .map((a) => a.getAttribute('href')).filter((h) => h.length > 1 && !document.getElementById(h.slice(1))));
  check(anchors.length === 0, `report.html: every in-page link has its target (${[...new Set(anchors)].slice(0, 5)})`);
  // The embedded viewer draws: a canvas with a WebGL context in the iframe.
  const frame = page.frames().find((f) => f !== page.mainFrame());
  let drawn = false;
  if (frame) {
    await frame.waitForFunction(() => !!document.querySelector('canvas'), null, { timeout: 60000 }).catch(() => {});
    drawn = await frame.evaluate(() => { const c = document.querySelector('canvas');
      return !!c && c.width > 0 && c.height > 0; });
  }
  check(drawn, 'report.html: the embedded viewer draws (a canvas in its frame)');
  check(refused.length === 0, `report.html alone: no request off the page (${refused.slice(0, 3)})`);
  check(errors.length === 0, `report.html: no script error (${errors.slice(0, 3)})`);
  await page.screenshot({ path: path.join(shots, 'ball_report_top.png') });
  await page.evaluate(() => document.getElementById('boundary').scrollIntoView());
  await page.screenshot({ path: path.join(shots, 'ball_report_boundary.png') });
  await page.evaluate(() => document.getElementById('viewer').scrollIntoView());
  // The viewer has drawn when it is ready (it draws before setting ready): no fixed 1.5 s wait.
  if (frame) await frame.waitForFunction(() => window.hqViewer && window.hqViewer.ready, null, { timeout: 30000 }).catch(() => {});
  await page.screenshot({ path: path.join(shots, 'ball_report_viewer.png') });
  await page.close();
}

// ---- batch: OUT/report.html ----
{
  const file = path.join(batch, 'report.html');
  const html = fs.readFileSync(file, 'utf8');
  const index = JSON.parse(fs.readFileSync(path.join(batch, 'index.json'), 'utf8'));
  const mesh = index.meshes[0];
  const { page, refused, errors } = await open(file, (url) => url.startsWith(pathToFileURL(batch).href));
  const images = await page.evaluate(() => [...document.images].map((i) => i.naturalWidth > 0));
  check(images.length >= 2 && images.every(Boolean), `batch report.html: ${images.length} images drawn`);
  check(!/src="[^"#d][^"]*\.png"/.test(html), 'batch report.html: thumbnails inline');
  const link = attributes(html).find(({ value }) => value.endsWith('/report.html'));
  check(!!link && fs.existsSync(path.join(batch, decodeURIComponent(link.value))) &&
    fs.existsSync(path.join(batch, mesh.path, 'report.html')), `batch report.html: links each mesh's report.html (${link && link.value})`);
  check(await page.evaluate(() => window.hqPwned === undefined), 'batch report.html: the injected file name ran no script');
  check(refused.length === 0 && errors.length === 0, `batch report.html: no request off the folder, no error (${refused} ${errors})`);
  await page.screenshot({ path: path.join(shots, 'batch_report.png') });
  await page.close();
}
await browser.close();
console.log(failures.length ? `${failures.length} failed` : 'all single-file checks passed');
process.exit(failures.length ? 1 : 0);
