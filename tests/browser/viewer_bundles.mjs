// The bundles of the viewer test (tests/browser/viewer_test.mjs), made once
// for both browsers: the CTest fixture browser.viewer.bundles runs this
// before browser.viewer and browser.viewer.firefox (FIXTURES_REQUIRED), so
// the hqview runs are not repeated per browser. Each bundle draws view A
// only (the viewer takes view A's camera; the reset test compares with
// main_1.png) and writes data/cells.csv (the clicks are checked against
// it): no other view or data file is needed.
//
// usage: node viewer_bundles.mjs HQVIEW SOURCE_DIR BUNDLE_DIR
// exit 0 made, 1 an hqview run failed.

import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';

const [hqview, sourceDir, outDir] = process.argv.slice(2);
const started = Date.now();
fs.rmSync(outDir, { recursive: true, force: true });
fs.mkdirSync(outDir, { recursive: true });
const example = (name) => path.join(sourceDir, 'examples', name);
function analyze(args) {
  const t = Date.now();
  execFileSync(hqview, ['analyze', ...args, '--views', 'main', '--data', 'csv', '--size', '640x480', '-j', '2', '--quiet'], { stdio: 'inherit' });
  console.log(`${path.basename(args[args.indexOf('-o') + 1])}: ${((Date.now() - t) / 1000).toFixed(1)} s`);
}

// An n x n x n grid of unit cells written as Medit, vertex (i, j, k) at
// place(i, j, k).
function gridMesh(file, n, place) {
  const id = (i, j, k) => 1 + i + (n + 1) * (j + (n + 1) * k);
  let s = `MeshVersionFormatted 1\nDimension 3\nVertices\n${(n + 1) ** 3}\n`;
  for (let k = 0; k <= n; ++k)
    for (let j = 0; j <= n; ++j)
      for (let i = 0; i <= n; ++i) s += `${place(i, j, k).join(' ')} 0\n`;
  s += `Hexahedra\n${n ** 3}\n`;
  for (let k = 0; k < n; ++k)
    for (let j = 0; j < n; ++j)
      for (let i = 0; i < n; ++i)
        s += `${id(i, j, k)} ${id(i + 1, j, k)} ${id(i + 1, j + 1, k)} ${id(i, j + 1, k)} ${id(i, j, k + 1)} ${id(i + 1, j, k + 1)} ${id(i + 1, j + 1, k + 1)} ${id(i, j + 1, k + 1)} 0\n`;
  fs.writeFileSync(file, s + 'End\n');
  return file;
}
// The central vertex (n/2, n/2, n/2) pulled: 8 interior cells under the
// threshold, none on the boundary.
function interiorBadMesh(file, n = 4) {
  return gridMesh(file, n, (i, j, k) => {
    const d = i === n / 2 && j === n / 2 && k === n / 2 ? 0.85 : 0;
    return [i + d, j + d, k + d];
  });
}
// A 4^3 grid whose top vertex (2, 2, 4) is pushed down to z = 2.5, below
// the layer under it: that boundary vertex is inverted (its 4 cells' corner
// there is negative), its 8 neighbours on the top are not.
function dentedMesh(file) {
  return gridMesh(file, 4, (i, j, k) => [i, j, i === 2 && j === 2 && k === 4 ? 2.5 : k]);
}

// The twisted bar under a hostile file name: one run serves the bar's
// checks (its name only reaches the page's title) and the name's.
const evilName = `"q'&amp;<script>window.hqPwned=1<img src=x onerror="window.hqPwned=2">.mesh`;
const evilDir = path.join(outDir, 'evil-input');
fs.mkdirSync(evilDir, { recursive: true });
fs.copyFileSync(example('twisted_bar.mesh'), path.join(evilDir, evilName));
analyze([path.join(evilDir, evilName), '-o', path.join(outDir, 'bar')]);
// 20^3 cells, 2,400 boundary faces (over the 2,000 a reduced boundary
// keeps): the tiny budget reduces the boundary too.
analyze([interiorBadMesh(path.join(outDir, 'dense.mesh'), 20), '-o', path.join(outDir, 'tiny'), '--viewer-max-mb', '0.01']);
analyze([interiorBadMesh(path.join(outDir, 'inner.mesh')), '-o', path.join(outDir, 'inner')]);
analyze([dentedMesh(path.join(outDir, 'dented.mesh')), '-o', path.join(outDir, 'dented')]);
// Rings and grey glyphs (issue 44, as view A draws them): a 6^3 grid with
// its top vertex (2, 2, 6) pushed below the layer under it (inverted:
// cluster #0) and its top vertex (5, 5, 6) moved by 0.4 along x and y (a
// poor cluster, min 0.33, not inverted), analysed with --top-clusters 1 so
// that the second is grey.
analyze([gridMesh(path.join(outDir, 'ringed.mesh'), 6, (i, j, k) => {
  if (k === 6 && i === 2 && j === 2) return [i, j, 4.6];
  if (k === 6 && i === 5 && j === 5) return [i + 0.4, j + 0.4, k];
  return [i, j, k];
}), '-o', path.join(outDir, 'ringed'), '--top-clusters', '1']);

// A legacy VTK file of points and cells [VTK cell type, point indices].
function writeVtk(file, title, points, cells) {
  let s = `# vtk DataFile Version 3.0\n${title}\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS ${points.length} double\n`;
  s += points.map((p) => p.join(' ')).join('\n') + '\n';
  s += `CELLS ${cells.length} ${cells.reduce((n, [, v]) => n + 1 + v.length, 0)}\n`;
  s += cells.map(([, v]) => `${v.length} ${v.join(' ')}`).join('\n') + '\n';
  s += `CELL_TYPES ${cells.length}\n${cells.map(([t]) => t).join('\n')}\n`;
  fs.writeFileSync(file, s);
  return file;
}

// A hex [0,1]^3 next to a tet box [1,2]x[0,1]^2 (6 tets around its
// diagonal), legacy VTK: the tets' triangles are boundary faces the viewer
// must draw (their x = 1 face, split in two against the hex's quad, is a
// non-conforming interface: inside, not boundary).
function hexTetBoxMesh(file) {
  const points = [];
  const id = (x, y, z) => {
    const k = points.findIndex((p) => p[0] === x && p[1] === y && p[2] === z);
    return k >= 0 ? k : points.push([x, y, z]) - 1;
  };
  const cells = [[12, [id(0, 0, 0), id(1, 0, 0), id(1, 1, 0), id(0, 1, 0), id(0, 0, 1), id(1, 0, 1), id(1, 1, 1), id(0, 1, 1)]]];
  const c = (i, j, k) => id(1 + i, j, k);
  for (const [a, b] of [[[1, 0, 0], [1, 1, 0]], [[1, 0, 0], [1, 0, 1]], [[0, 1, 0], [1, 1, 0]],
    [[0, 1, 0], [0, 1, 1]], [[0, 0, 1], [1, 0, 1]], [[0, 0, 1], [0, 1, 1]]]) {
    const t = [c(0, 0, 0), c(...a), c(...b), c(1, 1, 1)];
    const P = t.map((v) => points[v]), d = (u, w) => [0, 1, 2].map((k) => u[k] - w[k]);
    const [u, v, w] = [d(P[1], P[0]), d(P[2], P[0]), d(P[3], P[0])];
    const det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
    cells.push([10, det > 0 ? t : [t[0], t[2], t[1], t[3]]]);
  }
  return writeVtk(file, 'hex and tet box', points, cells);
}
analyze([hexTetBoxMesh(path.join(outDir, 'hex_tet_box.vtk')), '-o', path.join(outDir, 'hybrid')]);

// One poor cell of each kind, apart (a hex with a top corner pushed down, a
// flat inverted tet (apex under its base), a wedge with a top corner pushed down, a flat pyramid), and two
// unit hexes that intersect: the cut draws every kind, the legend has an
// entry for the overlap markers and the intersecting cells (issue 44).
function kindsMesh(file) {
  const points = [], cells = [];
  const add = (type, corners) => { cells.push([type, corners.map((p) => points.push(p) - 1)]); };
  add(12, [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, -0.2], [0, 1, 1]]);
  add(10, [[3, 0, 0], [4, 0, 0], [3, 1, 0], [3.3, 0.3, -0.08]]);
  add(13, [[6, 0, 0], [7, 0, 0], [6, 1, 0], [6, 0, 1], [7, 0, 1], [6.1, 0.9, 0.1]]);
  add(14, [[9, 0, 0], [10, 0, 0], [10, 1, 0], [9, 1, 0], [9.5, 0.5, 0.05]]);
  const cube = (x, y, z) => [[x, y, z], [x + 1, y, z], [x + 1, y + 1, z], [x, y + 1, z],
    [x, y, z + 1], [x + 1, y, z + 1], [x + 1, y + 1, z + 1], [x, y + 1, z + 1]];
  add(12, cube(12, 0, 0));
  add(12, cube(12.5, 0.5, 0.5));
  return writeVtk(file, 'one cell of each kind', points, cells);
}
analyze([kindsMesh(path.join(outDir, 'kinds.vtk')), '-o', path.join(outDir, 'kinds')]);

console.log(`viewer bundles made in ${((Date.now() - started) / 1000).toFixed(1)} s`);
