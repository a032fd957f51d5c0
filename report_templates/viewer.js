// HQView's interactive viewer (viewer.html): a classic script over
// three.js r111 and window.HQ_VIEWER_DATA (viewer/data.js, docs/viewer.md).
// No modules, no fetch: it runs from file://.
(function () {
  'use strict';
  var D = window.HQ_VIEWER_DATA;
  var view = document.getElementById('view');
  var info = document.getElementById('info');

  function bytes(b64) {
    var s = atob(b64), out = new Uint8Array(s.length);
    for (var i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
    return out;
  }
  function typed(Type, b64) { var b = bytes(b64); return new Type(b.buffer, 0, b.length / Type.BYTES_PER_ELEMENT); }
  function text(s) { return document.createTextNode(String(s)); }
  function el(tag, attrs, children) {
    var e = document.createElement(tag);
    for (var k in attrs || {}) e.setAttribute(k, attrs[k]);
    (children || []).forEach(function (c) { e.appendChild(c instanceof Node ? c : text(c)); });
    return e;
  }
  // One normal per quad (the cross product of its diagonals) for its 6
  // triangle corners: a non-planar quad is shaded flat, without a diagonal.
  function quadNormals(tri, count) {
    var n = new Float32Array(count * 18);
    for (var f = 0; f < count; ++f) {
      var o = 18 * f, d1 = [], d2 = [];
      // corners a b c | a c d: a = 0, b = 3, c = 6, d = 15 (floats)
      for (var k = 0; k < 3; ++k) { d1.push(tri[o + 6 + k] - tri[o + k]); d2.push(tri[o + 15 + k] - tri[o + 3 + k]); }
      var x = d1[1] * d2[2] - d1[2] * d2[1], y = d1[2] * d2[0] - d1[0] * d2[2], z = d1[0] * d2[1] - d1[1] * d2[0];
      var len = Math.hypot(x, y, z) || 1;
      for (var c = 0; c < 6; ++c) { n[o + 3 * c] = x / len; n[o + 3 * c + 1] = y / len; n[o + 3 * c + 2] = z / len; }
    }
    return n;
  }
  function show(x) { return typeof x === 'number' ? String(Number(x.toPrecision(6))) : String(x); }

  function unavailable() { document.getElementById('controls').hidden = true; }
  if (!D || !window.THREE) {
    unavailable();
    view.appendChild(el('p', { id: 'nogl' }, ['The viewer data did not load. The report: ', el('a', { href: 'index.html' }, ['index.html'])]));
    return;
  }
  var renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    unavailable();
    view.appendChild(el('p', { id: 'nogl' }, ['This browser cannot draw WebGL. The report: ', el('a', { href: 'index.html' }, ['index.html'])]));
    return;
  }
  renderer.setPixelRatio(1);
  renderer.setClearColor(0xffffff, 1);
  renderer.localClippingEnabled = true;
  view.appendChild(renderer.domElement);

  // ---- the data ----
  var V = D.vertices, q = typed(Uint16Array, V.quantised), nv = V.count;
  var pos = new Float32Array(3 * nv);
  for (var i = 0; i < nv; ++i)
    for (var k = 0; k < 3; ++k) pos[3 * i + k] = V.lo[k] + q[3 * i + k] * V.step[k];
  var quads = typed(Uint32Array, D.faces.quads), faceHex = typed(Uint32Array, D.faces.hex), nf = D.faces.count;
  var faceSj = typed(Float64Array, D.face_scaled_jacobian);
  var faceCorners = D.face_corners ? typed(Float32Array, D.face_corners) : null;
  // Meshes of several kinds: each face's cell kind (absent: every face is a hex's).
  var faceKind = D.faces.kind ? typed(Uint8Array, D.faces.kind) : null;
  var lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (i = 0; i < nv; ++i)
    for (k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], pos[3 * i + k]); hi[k] = Math.max(hi[k], pos[3 * i + k]); }
  if (nv === 0) { lo = [0, 0, 0]; hi = [1, 1, 1]; }
  var center = new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2);
  var diagonal = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;

  var scene = new THREE.Scene();
  scene.add(new THREE.AmbientLight(0xffffff, 0.45));
  var light = new THREE.DirectionalLight(0xffffff, 0.65);
  var cut = new THREE.Plane(new THREE.Vector3(1, 0, 0), 0);
  var clipping = [];

  // Boundary: two triangles per quad, unindexed so that a face field colours a quad flat.
  // Each corner carries (x, below, undefined) of the shown field (setField)
  // and the colour is looked up per fragment: mapped AFTER interpolation.
  var triPos = new Float32Array(nf * 18), triMap = new Float32Array(nf * 18);
  var corners = [0, 1, 2, 0, 2, 3];
  for (var f = 0; f < nf; ++f)
    for (var c = 0; c < 6; ++c) {
      var v = quads[4 * f + corners[c]];
      for (k = 0; k < 3; ++k) triPos[18 * f + 3 * c + k] = pos[3 * v + k];
    }
  var boundaryGeometry = new THREE.BufferGeometry();
  boundaryGeometry.setAttribute('position', new THREE.BufferAttribute(triPos, 3));
  boundaryGeometry.setAttribute('hqMap', new THREE.BufferAttribute(triMap, 3));
  boundaryGeometry.setAttribute('normal', new THREE.BufferAttribute(quadNormals(triPos, nf), 3));
  // The field's 256 colours as a 256 x 1 texture; the fragment shader looks
  // up the interpolated x (index / 254 on texel centres, linear between
  // neighbouring entries), so a face never shows a blend of two colours of
  // the table that is not in it (the purple of inverted blue and orange).
  // Where the interpolated 'undefined' or 'below' weight is over one half
  // the fragment takes the 'no value' (255) or the inverted (0) entry: an
  // inverted vertex keeps the inverted colour on the part of each triangle
  // where its barycentric weight is above one half, as in the PNG overview
  // (render/osmesa_renderer.cpp). Lighting multiplies the looked-up colour.
  var lutBytes = new Uint8Array(256 * 4);
  var lutTexture = new THREE.DataTexture(lutBytes, 256, 1, THREE.RGBAFormat);
  lutTexture.magFilter = THREE.LinearFilter;
  lutTexture.minFilter = THREE.LinearFilter;
  lutTexture.generateMipmaps = false;
  var boundaryMaterial = new THREE.MeshLambertMaterial({
    side: THREE.DoubleSide, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    clippingPlanes: clipping, transparent: true, depthWrite: false
  });
  boundaryMaterial.onBeforeCompile = function (shader) {
    shader.uniforms.hqLut = { value: lutTexture };
    shader.vertexShader = 'attribute vec3 hqMap;\nvarying vec3 vHqMap;\n' +
      shader.vertexShader.replace('#include <begin_vertex>', '#include <begin_vertex>\n  vHqMap = hqMap;');
    shader.fragmentShader = 'uniform sampler2D hqLut;\nvarying vec3 vHqMap;\n' +
      shader.fragmentShader.replace('#include <color_fragment>', [
        'float hqIndex = vHqMap.z > 0.5 ? 255.0 : vHqMap.y > 0.5 ? 0.0 : clamp(vHqMap.x, 0.0, 1.0) * 254.0;',
        'diffuseColor.rgb *= texture2D(hqLut, vec2((hqIndex + 0.5) / 256.0, 0.5)).rgb;'].join('\n'));
  };
  var boundary = new THREE.Mesh(boundaryGeometry, boundaryMaterial);
  boundary.userData.legend = 'field';  // its colours are the field's bar and entries
  // The faces are see-through while there are glyphs inside (as view A's
  // wireframe is), opaque otherwise; the opacity slider changes it.
  var opacity = document.getElementById('opacity');
  function setOpacity() {
    var a = Number(opacity.value) / 100;
    boundaryMaterial.opacity = a;
    boundaryMaterial.transparent = a < 1;
    boundaryMaterial.depthWrite = a >= 1;
    boundaryMaterial.needsUpdate = true;
  }
  opacity.value = D.clusters.length ? 35 : 100;
  setOpacity();
  opacity.addEventListener('input', function () { setOpacity(); draw(); });
  scene.add(boundary);

  // Edges: each unique quad edge once.
  var seen = {}, edgePos = [];
  for (f = 0; f < nf; ++f)
    for (c = 0; c < 4; ++c) {
      var a = quads[4 * f + c], b = quads[4 * f + (c + 1) % 4];
      var key = a < b ? a + ',' + b : b + ',' + a;
      if (a === b || seen[key]) continue;  // a reduced boundary's triangle repeats its last corner
      seen[key] = 1;
      for (k = 0; k < 3; ++k) edgePos.push(pos[3 * a + k]);
      for (k = 0; k < 3; ++k) edgePos.push(pos[3 * b + k]);
    }
  var edgeGeometry = new THREE.BufferGeometry();
  edgeGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(edgePos), 3));
  var edges = new THREE.LineSegments(edgeGeometry, new THREE.LineBasicMaterial({
    color: 0x28282e, transparent: true, opacity: nf > 20000 ? 0.25 : 0.55, clippingPlanes: clipping
  }));
  scene.add(edges);

  // Glyphs: one sphere per listed cluster in its colour (its tie class's:
  // clusters tied with a labelled one wear its colour, issue 44 part T);
  // as in view A every glyph keeps its severity radius, the grey
  // (unlabelled) ones are fainter (kGreyOpacity), a ring in the
  // inverted colour goes round each cluster with an inverted vertex
  // (min < 0) and a dark ring round cluster #0, outside it, each on a white
  // halo. The rings face the camera (turned in draw()).
  // Draw order (issue 44): the see-through faces write no depth, and what
  // three.js draws before them is washed out by them. The spheres go after
  // the faces (transparent pass, opacity 1, renderOrder 5: their own colour,
  // still hidden by opaque faces), the rings after everything with no depth
  // test (renderOrder 20+: an overlay, as view A draws them).
  var colors = D.colors, kDarkRing = colors.worst_ring;
  var labelled = D.labelled_clusters === undefined ? D.top_clusters || 0 : D.labelled_clusters;
  // Tie classes (report.json glyphs.clusters[].tie_class): a cluster is
  // coloured when its class is among the labelled ones; the first of a
  // class carries its label; #0 tied with others gets no "worst" ring.
  function tieClass(cl, rank) { return cl.tie_class === undefined ? rank : cl.tie_class; }
  var colouredClasses = D.coloured_classes === undefined ? labelled : D.coloured_classes;
  function isColoured(cl, rank) { return tieClass(cl, rank) < colouredClasses; }
  function isClassFirst(cl, rank) { return rank === 0 || tieClass(D.clusters[rank - 1], rank - 1) !== tieClass(cl, rank); }
  var worstTied = D.clusters.length > 0 && (D.clusters[0].tied || 1) > 1;
  var glyphs = new THREE.Group(), sphere = new THREE.SphereGeometry(1, 24, 16), rings = [];
  var invertedColor = (function () {
    var lut = bytes(D.fields[0].lut), h = '#';
    for (var q = 0; q < 3; ++q) h += (lut[q] < 16 ? '0' : '') + lut[q].toString(16);
    return h;
  })();
  // Rings (issue 44 review): a fixed width on screen, whatever the glyph's
  // size or the zoom: from inner to outer CSS pixels outside the drawn
  // glyph radius, on a white halo of kHaloPx each side; the positions are
  // rewritten at every frame (sizeRings) from the pixels per model unit.
  var kRingPx = { inverted: [2, 6], worstOutside: [8, 12], worst: [2, 6] }, kHaloPx = 1;
  function ringGeometry(n) {
    var gm = new THREE.BufferGeometry(), index = [];
    gm.setAttribute('position', new THREE.BufferAttribute(new Float32Array(6 * (n + 1)), 3));
    for (var i = 0; i < n; ++i) index.push(2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 1, 2 * i + 3, 2 * i + 2);
    gm.setIndex(index);
    return gm;
  }
  // A ring of n segments (64: a circle; 4: a diamond, the overlap markers'
  // outline, corners on the screen axes).
  function addRing(group, r, px, color, order, n) {
    n = n || 64;
    [[px[0] - kHaloPx, px[1] + kHaloPx, '#ffffff', order], [px[0], px[1], color, order + 1]].forEach(function (d) {
      var ring = new THREE.Mesh(ringGeometry(n), new THREE.MeshBasicMaterial({ color: new THREE.Color(d[2]),
        side: THREE.DoubleSide, depthWrite: false, depthTest: false, transparent: true, clippingPlanes: clipping }));
      ring.renderOrder = d[3];
      ring.userData.ring = { r: r, inner: d[0], outer: d[1], n: n };
      group.add(ring);
    });
  }
  function sizeRings(pxPerUnit) {
    rings.forEach(function (g) {
      g.children.forEach(function (ring) {
        var d = ring.userData.ring;
        if (!d) return;
        var a = d.r + d.inner / pxPerUnit, b = d.r + d.outer / pxPerUnit, p = ring.geometry.attributes.position;
        // A diamond's band is as wide as a circle's across its edges.
        if (d.n === 4) { a *= Math.SQRT2; b *= Math.SQRT2; }
        for (var i = 0; i <= d.n; ++i) {
          var t = 2 * Math.PI * i / d.n, x = Math.cos(t), y = Math.sin(t);
          p.setXYZ(2 * i, a * x, a * y, 0);
          p.setXYZ(2 * i + 1, b * x, b * y, 0);
        }
        p.needsUpdate = true;
        ring.geometry.computeBoundingSphere();
      });
    });
  }
  // Glyph size on screen (issue 44 review): the drawn radii keep report.json's
  // ratios but are scaled down so that the largest is at most
  // kMaxGlyphFraction of the bounding diagonal. The overlap markers are
  // drawn over them.
  // The coloured spheres are drawn over the faces whatever their depth
  // (depthTest off, as view A draws its ranked glyphs over the wireframe),
  // so a glyph in front of a face and one behind it show the same colour
  // (the 44t review: the red #0 class looked pink in front of the faces and
  // brown behind them), opaque (see-through, they took the colour of what
  // lay behind: pink over the background, dark red over the faces), each on
  // a white rim kRimPx wide that parts it from the red-to-orange faces
  // under it (issue 44 part P). The grey glyphs stay see-through and behind
  // opaque faces; an inverted grey one (min < 0) at kGlyphOpacity, not faint,
  // so its inverted ring does not read as an empty circle (44t review).
  var kMaxGlyphFraction = 0.03, kGlyphOpacity = 0.55, kGreyOpacity = 0.22, kRimPx = [0, 2];
  var largestRadius = D.clusters.reduce(function (m, cl) { return Math.max(m, cl.radius); }, 0);
  var glyphScale = largestRadius > kMaxGlyphFraction * diagonal ? kMaxGlyphFraction * diagonal / largestRadius : 1;
  D.clusters.forEach(function (cl, rank) {
    var g = new THREE.Group();
    g.position.set(cl.position[0], cl.position[1], cl.position[2]);
    var r = Math.max(cl.radius * glyphScale, 1e-6 * diagonal);
    var coloured = isColoured(cl, rank);
    var m = new THREE.Mesh(sphere, new THREE.MeshLambertMaterial({ color: new THREE.Color(cl.color), transparent: true,
      opacity: coloured ? 1 : cl.min_quality < 0 ? kGlyphOpacity : kGreyOpacity, depthWrite: false, depthTest: !coloured }));
    // Coloured after the grey, worse ranks last (on top), as in view A.
    m.renderOrder = coloured ? 7 + (D.clusters.length - rank) / (D.clusters.length + 1) : 5;
    m.scale.set(r, r, r);
    m.userData.cluster = cl;
    m.userData.drawnRadius = r;
    g.add(m);
    g.userData.cluster = cl;
    g.userData.drawnRadius = r;
    var inverted = cl.min_quality < 0;
    if (coloured) addRing(g, r, kRimPx, '#ffffff', 6);
    if (inverted) addRing(g, r, kRingPx.inverted, invertedColor, 20);
    if (cl.id === 0 && !worstTied) addRing(g, r, inverted ? kRingPx.worstOutside : kRingPx.worst, kDarkRing, 22);
    if (g.children.length > 1) rings.push(g);
    glyphs.add(g);
  });
  scene.add(glyphs);
  // The glyph spheres (picking): each group's first child.
  var glyphSpheres = glyphs.children.map(function (g) { return g.children[0]; });
  // Pixels per model unit of the orthographic camera.
  function pxPerUnit() { return Math.max(1, view.clientHeight) * camera.zoom / (camera.top - camera.bottom); }
  function faceRings() {
    rings.forEach(function (g) {
      g.quaternion.copy(camera.quaternion);
      // A ring whose glyph centre the cut removes goes with it.
      g.children.forEach(function (ring) { if (ring.userData.ring) ring.visible = clipping.length === 0 || clipping[0].distanceToPoint(g.position) >= 0; });
    });
    // A glyph goes whole with its centre (the 44w review: the cut left
    // lenses and half spheres inside whole rings and labels).
    glyphs.children.forEach(function (g) { g.children[0].visible = clipping.length === 0 || clipping[0].distanceToPoint(g.position) >= 0; });
    sizeRings(pxPerUnit());
  }

  // Overlap markers and intersecting cells.
  // Each marker a hollow diamond (issue 44 part P, the 44t review: the
  // earlier dot in a ring chained into interlocking rings on rockarm, a
  // third meaning of "ring" beside the worst and inverted rings): its
  // outline kMarkerPx CSS pixels wide, kMarkerPx[0] outside a centre
  // 0.005 of the diagonal across, on a white halo, facing the camera like
  // the rings; the legend's swatch is the same diamond. An overlay (issue
  // 44 review): after the see-through faces and the glyphs, no depth test,
  // so neither washes it nor hides it.
  var markers = new THREE.Group(), markerRadius = 0.005 * diagonal, kMarkerPx = [1, 4];
  D.markers.forEach(function (mk) {
    var colour = mk.kind === 'coincident' ? colors.coincident : colors.intersection, g = new THREE.Group();
    g.position.set(mk.position[0], mk.position[1], mk.position[2]);
    g.userData.marker = mk;
    addRing(g, markerRadius, kMarkerPx, colour, 27, 4);
    rings.push(g);
    markers.add(g);
  });
  scene.add(markers);
  var intersectingGeometry = new THREE.BufferGeometry();
  intersectingGeometry.setAttribute('position', new THREE.BufferAttribute(typed(Float32Array, D.intersecting_edges), 3));
  var intersecting = new THREE.LineSegments(intersectingGeometry, new THREE.LineBasicMaterial({ color: new THREE.Color(colors.intersecting_cells), clippingPlanes: clipping }));
  intersecting.userData.empty = intersectingGeometry.attributes.position.count === 0;
  intersecting.visible = !intersecting.userData.empty;
  scene.add(intersecting);

  // Non-conforming faces (a hex's quad against two triangles, inside the
  // mesh): the overview's frame (0.15 of the way from each corner to the
  // centre) and the triangles' edges (their diagonal is the cause), unlit,
  // over everything as the overview draws them (no depth test).
  var NC = D.non_conforming || { count: 0, quads: '', triangles: '' };
  var ncQuads = typed(Float32Array, NC.quads), ncTris = typed(Float32Array, NC.triangles), ncFrame = [], ncLines = [];
  for (f = 0; f < NC.count; ++f) {
    var pq = [], mid = [0, 0, 0];
    for (c = 0; c < 4; ++c) {
      pq.push([ncQuads[12 * f + 3 * c], ncQuads[12 * f + 3 * c + 1], ncQuads[12 * f + 3 * c + 2]]);
      for (k = 0; k < 3; ++k) mid[k] += pq[c][k] / 4;
    }
    var inner = pq.map(function (pt) { return pt.map(function (x, k) { return x + 0.15 * (mid[k] - x); }); });
    for (c = 0; c < 4; ++c) {
      var n1 = (c + 1) % 4;
      [pq[c], pq[n1], inner[n1], pq[c], inner[n1], inner[c]].forEach(function (pt) { ncFrame.push(pt[0], pt[1], pt[2]); });
    }
    for (var t2 = 0; t2 < 2; ++t2)
      for (c = 0; c < 3; ++c)
        for (var e2 = 0; e2 < 2; ++e2) {
          var o2 = 18 * f + 9 * t2 + 3 * ((c + e2) % 3);
          ncLines.push(ncTris[o2], ncTris[o2 + 1], ncTris[o2 + 2]);
        }
  }
  var nonConforming = new THREE.Group();
  if (NC.count) {
    var ncColor = new THREE.Color(colors.non_conforming);
    var frameGeometry = new THREE.BufferGeometry();
    frameGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(ncFrame), 3));
    var lineGeometry = new THREE.BufferGeometry();
    lineGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(ncLines), 3));
    // Twice (issue 44 review): the parts behind opaque faces faint (no depth
    // test, kNcHiddenOpacity), then the visible parts full (depth test), so
    // the hidden edges no longer read as a slab standing out of the face.
    var kNcHiddenOpacity = 0.3;
    [[false, kNcHiddenOpacity, 15], [true, 1, 16]].forEach(function (d) {
      var frameMesh = new THREE.Mesh(frameGeometry, new THREE.MeshBasicMaterial({ color: ncColor, side: THREE.DoubleSide,
        depthTest: d[0], depthWrite: false, transparent: true, opacity: d[1], polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -2 }));
      var ncEdges = new THREE.LineSegments(lineGeometry, new THREE.LineBasicMaterial({ color: ncColor, depthTest: d[0], transparent: true, opacity: d[1] }));
      frameMesh.renderOrder = d[2]; ncEdges.renderOrder = d[2];
      frameMesh.userData.hiddenPart = !d[0]; ncEdges.userData.hiddenPart = !d[0];
      nonConforming.add(frameMesh);
      nonConforming.add(ncEdges);
    });
  }
  scene.add(nonConforming);

  // Cells under the threshold, of every kind: their faces (the kind's face
  // table, L.kind_faces, from the C++ cell tables), coloured by the cell
  // scaled Jacobian; shown while a cut is active (the boundary hides them
  // otherwise). A triangle is drawn as a quad that repeats its last corner.
  var L = D.low_cells, lowCorners = typed(Float32Array, L.corners), lowSj = typed(Float64Array, L.scaled_jacobian);
  var lowKinds = L.kinds ? typed(Uint8Array, L.kinds) : new Uint8Array(L.count);
  var kindFaces = L.kind_faces ? L.kind_faces.faces : [[[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]];
  var kindCorners = L.kind_faces ? L.kind_faces.corners : [8];
  var lowFaces = 0;
  for (var h = 0; h < L.count; ++h) lowFaces += kindFaces[lowKinds[h]].length;
  var lowPos = new Float32Array(lowFaces * 18), lowCol = new Float32Array(lowFaces * 18);
  var sjField = D.fields.filter(function (fd) { return fd.id === 'scaled_jacobian'; })[0];
  var sjLut = bytes(sjField.lut);
  function qualityIndex(s) {
    if (!isFinite(s) || Math.abs(s) >= 1e30) return 255;
    return Math.round((Math.min(1, Math.max(-1, s)) + 1) / 2 * 254);
  }
  var o = 0;  // the cell's first corner in lowCorners (floats)
  for (h = 0, lowFaces = 0; h < L.count; ++h) {
    var qi = qualityIndex(lowSj[h]), cellFaces = kindFaces[lowKinds[h]];
    for (var fc = 0; fc < cellFaces.length; ++fc, ++lowFaces) {
      var fv = cellFaces[fc].length === 4 ? cellFaces[fc] : cellFaces[fc].concat([cellFaces[fc][2]]);
      for (c = 0; c < 6; ++c) {
        var corner = fv[corners[c]], out = (lowFaces * 6 + c) * 3;
        for (k = 0; k < 3; ++k) {
          lowPos[out + k] = lowCorners[o + 3 * corner + k];
          lowCol[out + k] = sjLut[3 * qi + k] / 255;
        }
      }
    }
    o += 3 * kindCorners[lowKinds[h]];
  }
  // " (3 hex, 1 tet)" on a mesh whose cells under the threshold are of several kinds.
  var lowKindCount = [], lowKindsText = '';
  for (h = 0; h < L.count; ++h) lowKindCount[lowKinds[h]] = (lowKindCount[lowKinds[h]] || 0) + 1;
  if (L.kind_faces && lowKindCount.filter(Boolean).length > 1)
    lowKindsText = ' (' + lowKindCount.map(function (n, kd) { return n ? n + ' ' + L.kind_faces.names[kd] : ''; })
      .filter(Boolean).join(', ') + ')';
  // Per cell kind, one mesh of its inverted cells (scaled Jacobian < 0),
  // always drawn by the cut, and one of the rest, drawn while the kind's
  // check box is ticked (issue 44 review: one threshold floods a Delaunay
  // tet region, whose tets sit well under 0.5). Ticked at first: hexes, and
  // every kind with an inverted cell or a cell with a vertex of cluster #0
  // (L.worst); with no hex among the cells, every kind. The note gives every
  // kind's count and the inverted count.
  var lowNormals = quadNormals(lowPos, lowFaces), low = new THREE.Group(), lowKindBoxes = document.getElementById('cut-kinds');
  var kindNames = L.kind_faces ? L.kind_faces.names : ['hex'], lowWorst = L.worst ? typed(Uint8Array, L.worst) : new Uint8Array(L.count);
  var cellFace = new Uint32Array(L.count + 1), lowInverted = 0, kindTicked = [];
  for (h = 0; h < L.count; ++h) {
    cellFace[h + 1] = cellFace[h] + kindFaces[lowKinds[h]].length;
    if (lowSj[h] < 0) lowInverted += 1;
    if (lowSj[h] < 0 || lowWorst[h] || lowKinds[h] === 0) kindTicked[lowKinds[h]] = true;
  }
  function lowPart(kd, inverted) {
    var cells = [];
    for (var i = 0; i < L.count; ++i) if (lowKinds[i] === kd && (lowSj[i] < 0) === inverted) cells.push(i);
    if (!cells.length) return;
    var n = cells.reduce(function (m, i) { return m + cellFace[i + 1] - cellFace[i]; }, 0), at = 0;
    var pos = new Float32Array(18 * n), col = new Float32Array(18 * n), nor = new Float32Array(18 * n);
    cells.forEach(function (i) {
      var a = 18 * cellFace[i], b = 18 * cellFace[i + 1];
      pos.set(lowPos.subarray(a, b), at); col.set(lowCol.subarray(a, b), at); nor.set(lowNormals.subarray(a, b), at);
      at += b - a;
    });
    var gm = new THREE.BufferGeometry();
    gm.setAttribute('position', new THREE.BufferAttribute(pos, 3));
    gm.setAttribute('color', new THREE.BufferAttribute(col, 3));
    gm.setAttribute('normal', new THREE.BufferAttribute(nor, 3));
    var part = new THREE.Mesh(gm, new THREE.MeshLambertMaterial({ vertexColors: THREE.VertexColors, side: THREE.DoubleSide, clippingPlanes: clipping }));
    part.userData.legend = 'field';  // the quality colours of the bar
    part.userData.kind = kd;
    part.userData.inverted = inverted;
    part.userData.cells = cells.length;
    low.add(part);
  }
  var kindShown = {};
  lowKindCount.forEach(function (n, kd) {
    if (!n) return;
    lowPart(kd, true);
    lowPart(kd, false);
    kindShown[kd] = !lowKindCount[0] || !!kindTicked[kd];
    var box = el('input', { type: 'checkbox', 'data-kind': kindNames[kd] });
    box.checked = kindShown[kd];
    box.addEventListener('change', function () { kindShown[kd] = box.checked; updateCut(); });
    lowKindBoxes.appendChild(el('label', { class: 'kind' }, [box, ' ' + n + ' ' + kindNames[kd]]));
  });
  low.visible = false;
  scene.add(low);
  var kCutPlaneColor = '#6b6b6b';
  // The cut plane's outline: the plane's rectangle across the bounding box.
  var planeGeometry = new THREE.BufferGeometry();
  planeGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(12), 3));
  var planeOutline = new THREE.LineLoop(planeGeometry, new THREE.LineBasicMaterial({ color: new THREE.Color(kCutPlaneColor) }));
  planeOutline.visible = false;
  scene.add(planeOutline);

  // ---- colour fields ----
  var fieldSelect = document.getElementById('field');
  D.fields.forEach(function (fd, n) { fieldSelect.appendChild(el('option', { value: String(n) }, [fd.label])); });
  // Per corner (x, below, undefined): x = index / 254 of the colour table; a
  // quality index below 127 (quality < 0) is 'below' with x at quality 0
  // (the map's end: a neighbour's colour never runs through the inverted
  // entries), index 255 'undefined' with x at the field's neutral index.
  function mapTriple(idx, isQuality) {
    if (idx === 255) return [isQuality ? 1 : 127 / 254, 0, 1];
    if (isQuality && idx < 127) return [127 / 254, 1, 0];
    return [idx / 254, 0, 0];
  }
  function setField(n) {
    var fd = D.fields[n], values = bytes(fd.values), lut = bytes(fd.lut);
    // Quality fields show [0, 1] (below 0 is the one inverted colour); the
    // others their whole range.
    var isQuality = fd.id === 'vertex_quality' || fd.id === 'scaled_jacobian';
    for (var f = 0; f < nf; ++f)
      for (var c = 0; c < 6; ++c) {
        // per vertex, per face corner (a mesh of several kinds: the face's own
        // kind's vertex quality) or per face
        var t = mapTriple(fd.per === 'vertex' ? values[quads[4 * f + corners[c]]] : fd.per === 'corner' ? values[4 * f + corners[c]] : values[f], isQuality);
        for (var k = 0; k < 3; ++k) triMap[18 * f + 3 * c + k] = t[k];
      }
    boundaryGeometry.attributes.hqMap.needsUpdate = true;
    for (var e = 0; e < 256; ++e) {
      for (k = 0; k < 3; ++k) lutBytes[4 * e + k] = lut[3 * e + k];
      lutBytes[4 * e + 3] = 255;
    }
    lutTexture.needsUpdate = true;
    var bar = document.getElementById('legend-bar'), g = bar.getContext('2d'), img = g.createImageData(256, 1);
    var first = isQuality ? 127 : 0, last = isQuality || fd.id === 'boundary_error' ? 254 : 253;
    for (var i = 0; i < 256; ++i) {
      var j = Math.round(first + i / 255 * (last - first));
      img.data[4 * i] = lut[3 * j]; img.data[4 * i + 1] = lut[3 * j + 1]; img.data[4 * i + 2] = lut[3 * j + 2]; img.data[4 * i + 3] = 255;
    }
    g.putImageData(img, 0, 0);
    document.getElementById('legend-min').textContent = show(isQuality ? 0 : fd.min);
    document.getElementById('legend-max').textContent = show(fd.max);
    var extra = document.getElementById('legend-extra');
    extra.textContent = '';
    var entries = fd.legend.concat([{ label: 'no value', index: 255 }]);
    if (fd.id === 'vertex_quality' || fd.id === 'scaled_jacobian') entries.unshift({ label: fd.below_zero || 'inverted (< 0)', index: 0 });
    entries.forEach(function (e) {
      var sw = el('span', { class: 'swatch' });
      sw.style.background = 'rgb(' + lut[3 * e.index] + ',' + lut[3 * e.index + 1] + ',' + lut[3 * e.index + 2] + ')';
      extra.appendChild(el('div', {}, [sw, e.label]));
    });
    draw();
  }
  fieldSelect.addEventListener('change', function () { setField(Number(fieldSelect.value)); });
  // The whole name under the box (a select cannot wrap its text).
  function nameField() { document.getElementById('field-name').textContent = D.fields[Number(fieldSelect.value)].label; }
  fieldSelect.addEventListener('change', nameField);

  // ---- camera ----
  var camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 1e-4 * diagonal, 100 * diagonal);
  // OrbitControls orbits about the camera's up at its construction: the
  // model's up axis (--up), so turning keeps the model upright.
  camera.up.fromArray(D.up);
  var controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.screenSpacePanning = true;
  var frameHeight = diagonal, frameAspect = 1;
  function resize() {
    var w = Math.max(1, view.clientWidth), hgt = Math.max(1, view.clientHeight), aspect = w / hgt;
    renderer.setSize(w, hgt, false);
    // Keep the framed height; widen it when the window is narrower than the frame.
    var h = aspect >= frameAspect ? frameHeight : frameHeight * frameAspect / aspect;
    camera.left = -h * aspect / 2; camera.right = h * aspect / 2; camera.top = h / 2; camera.bottom = -h / 2;
    camera.updateProjectionMatrix();
    draw();
  }
  function place(eye, target, up, height, aspect) {
    var e = new THREE.Vector3().fromArray(eye), t = new THREE.Vector3().fromArray(target);
    // Far enough back that near/far enclose the model whatever the zoom.
    var dir = e.clone().sub(t).normalize();
    camera.position.copy(t.clone().add(dir.multiplyScalar(2 * diagonal + t.distanceTo(center))));
    camera.near = 1e-3 * diagonal; camera.far = 6 * diagonal + 2 * t.distanceTo(center);
    controls.target.copy(t);
    camera.zoom = 1;
    frameHeight = height; frameAspect = aspect;
    camera.lookAt(t);
    controls.update();
    resize();
  }
  function reset() {
    if (D.camera && D.camera.orthographic) {
      place(D.camera.eye, D.camera.target, D.camera.up, D.camera.height, D.camera.aspect);
    } else {
      // The three-quarter view of --up (render/upright.h): azimuth 30, elevation 25.
      var up = new THREE.Vector3().fromArray(D.up).normalize();
      var front = Math.abs(up.z) >= Math.abs(up.x) && Math.abs(up.z) >= Math.abs(up.y) ? new THREE.Vector3(0, -1, 0) : new THREE.Vector3(0, 0, 1);
      var side = up.clone().cross(front), az = 30 * Math.PI / 180, el = 25 * Math.PI / 180;
      var eyeDir = front.multiplyScalar(Math.cos(az)).add(side.multiplyScalar(Math.sin(az))).multiplyScalar(Math.cos(el)).add(up.clone().multiplyScalar(Math.sin(el)));
      place(center.clone().add(eyeDir).toArray(), center.toArray(), D.up, 1.1 * diagonal, 1);
    }
  }
  document.getElementById('reset').addEventListener('click', function () { location.hash = ''; reset(); });

  // The cut removes the part between the eye and the plane (it follows the
  // camera as the model turns): the plane at the slider's position across
  // the chosen axis keeps the side away from the eye.
  function orientCut() {
    var axis = Number(document.getElementById('cut-axis').value);
    if (axis < 0) return;
    var t = Number(document.getElementById('cut').value) / 1000, at = lo[axis] + t * (hi[axis] - lo[axis]);
    var eyeSide = camera.position.getComponent(axis) - controls.target.getComponent(axis);
    var n = new THREE.Vector3(0, 0, 0);
    n.setComponent(axis, eyeSide >= 0 ? -1 : 1);
    cut.set(n, eyeSide >= 0 ? at : -at);
    var u = (axis + 1) % 3, w = (axis + 2) % 3, p = planeGeometry.attributes.position;
    [[lo[u], lo[w]], [hi[u], lo[w]], [hi[u], hi[w]], [lo[u], hi[w]]].forEach(function (uv, i) {
      var pt = [0, 0, 0];
      pt[axis] = at; pt[u] = uv[0]; pt[w] = uv[1];
      p.setXYZ(i, pt[0], pt[1], pt[2]);
    });
    p.needsUpdate = true;
    planeGeometry.computeBoundingSphere();
  }
  // ---- #k labels (issue 44) ----
  // View A's labels in the viewer: "#k (n)", the cluster's rank and member
  // count (report.json glyphs.clusters id and size), beside the glyph of
  // each labelled cluster (the first labelled_clusters ranks, the coloured
  // ones), placed again at every frame: the first of 8 places round the
  // glyph (outside its rings) that overlaps no label placed before it (rank
  // order) and no other labelled glyph or its rings, else the first place.
  var labelLayer = el('div', { id: 'glyph-labels' });
  view.appendChild(labelLayer);
  // One label per coloured tie class, on its first cluster: "#k (n)", or
  // "#k (n) +m tied" for a tie.
  var labels = [];
  D.clusters.forEach(function (cl, rank) {
    if (!isColoured(cl, rank) || !isClassFirst(cl, rank)) return;
    var tied = cl.tied || 1;
    var e = el('div', { class: 'glyph-label', 'data-cluster': String(cl.id) },
      ['#' + cl.id + ' (' + cl.size + ')' + (tied > 1 ? ' +' + (tied - 1) + ' tied' : '')]);
    e.style.borderLeftColor = cl.color;
    labelLayer.appendChild(e);
    labels.push({ cl: cl, e: e, rank: rank });
  });
  function placeLabels() {
    labelLayer.hidden = !glyphs.visible;
    if (!glyphs.visible || !labels.length) return;
    var w = view.clientWidth, hgt = view.clientHeight;
    var ppu = pxPerUnit();
    var discs = labels.map(function (l, i) {
      var gi = glyphs.children[l.rank];
      var p = new THREE.Vector3().fromArray(l.cl.position).project(camera), r = gi.userData.drawnRadius * ppu;
      // Outside the rings (fixed pixels outside the glyph) and their halo.
      var ringPx = l.cl.id === 0 && !worstTied ? (l.cl.min_quality < 0 ? kRingPx.worstOutside[1] : kRingPx.worst[1]) : l.cl.min_quality < 0 ? kRingPx.inverted[1] : 0;
      var outer = r + ringPx + kHaloPx + 2;
      var cutAway = clipping.length > 0 && clipping[0].distanceToPoint(gi.position) < 0;
      return { x: (p.x + 1) / 2 * w, y: (1 - p.y) / 2 * hgt, r: r, outer: outer, z: p.z, cutAway: cutAway };
    });
    var placed = [];
    function free(b, self) {
      for (var i = 0; i < placed.length; ++i) {
        var q = placed[i];
        if (b[0] < q[2] && q[0] < b[2] && b[1] < q[3] && q[1] < b[3]) return false;
      }
      for (i = 0; i < discs.length; ++i) {
        if (i === self) continue;
        var d = discs[i], cx = Math.max(b[0], Math.min(d.x, b[2])), cy = Math.max(b[1], Math.min(d.y, b[3]));
        if (Math.hypot(cx - d.x, cy - d.y) < d.outer) return false;  // its glyph and rings
      }
      return true;
    }
    labels.forEach(function (l, i) {
      var d = discs[i], lw = l.e.offsetWidth, lh = l.e.offsetHeight;
      var shown = !d.cutAway && Math.abs(d.z) <= 1 && d.x >= 0 && d.x <= w && d.y >= 0 && d.y <= hgt;
      l.e.hidden = !shown;
      if (!shown) return;
      var o = d.outer, s = 0.71 * o;
      var spots = [[d.x + o, d.y - lh / 2], [d.x + s, d.y - s - lh], [d.x - lw / 2, d.y - o - lh], [d.x - s - lw, d.y - s - lh],
        [d.x - o - lw, d.y - lh / 2], [d.x - s - lw, d.y + s], [d.x - lw / 2, d.y + o], [d.x + s, d.y + s]];
      var box = null;
      for (var k = 0; k < spots.length && !box; ++k) {
        var b = [spots[k][0], spots[k][1], spots[k][0] + lw, spots[k][1] + lh];
        if (free(b, i)) box = b;
      }
      box = box || [spots[0][0], spots[0][1], spots[0][0] + lw, spots[0][1] + lh];
      placed.push(box);
      l.e.style.left = Math.round(box[0]) + 'px';
      l.e.style.top = Math.round(box[1]) + 'px';
    });
  }

  // ---- thinning (issue 44 part P) ----
  // As view A thins its glyphs (views/main_views.h main_view_glyphs_drawn,
  // the same constants): in rank order, a grey glyph is left out of this
  // frame when at least kThinnedCoverage of its disc on screen (measured on
  // kThinSamples points spread evenly over it, Vogel's sunflower) lies in
  // the discs of glyphs drawn before it; the coloured glyphs are always
  // drawn. Redone at every frame, since turning and zooming move the discs;
  // the cluster legend says how many are left out.
  var kThinnedCoverage = 0.5, kThinSamples = 32, thinnedNow = 0;
  function thinGlyphs() {
    thinnedNow = 0;
    if (!glyphs.visible) return;
    var w = view.clientWidth, hgt = view.clientHeight, ppu = pxPerUnit(), cell = 1, discs = [];
    glyphs.children.forEach(function (g) {
      var p = g.position.clone().project(camera);
      var d = { x: (p.x + 1) / 2 * w, y: (1 - p.y) / 2 * hgt, r: g.userData.drawnRadius * ppu };
      cell = Math.max(cell, d.r);
      discs.push(d);
    });
    var grid = {};
    function key(gx, gy) { return gx + ',' + gy; }
    glyphs.children.forEach(function (g, rank) {
      var sphereMesh = g.children[0], d = discs[rank];
      if (!sphereMesh.visible) return;  // cut away
      var cx = Math.floor(d.x / cell), cy = Math.floor(d.y / cell);
      if (!isColoured(g.userData.cluster, rank)) {
        var covered = 0;
        for (var k = 0; k < kThinSamples; ++k) {
          var rr = d.r * Math.sqrt((k + 0.5) / kThinSamples), an = k * 2.399963229728653;
          var x = d.x + rr * Math.cos(an), y = d.y + rr * Math.sin(an), inside = false;
          for (var gy = cy - 1; gy <= cy + 1 && !inside; ++gy)
            for (var gx = cx - 1; gx <= cx + 1 && !inside; ++gx)
              (grid[key(gx, gy)] || []).forEach(function (j) {
                if (!inside && Math.hypot(x - discs[j].x, y - discs[j].y) < discs[j].r) inside = true;
              });
          if (inside) covered += 1;
        }
        if (covered >= kThinnedCoverage * kThinSamples) {
          g.children.forEach(function (o) { o.visible = false; });  // its rings too
          thinnedNow += 1;
          return;
        }
      }
      (grid[key(cx, cy)] = grid[key(cx, cy)] || []).push(rank);
    });
    var note = document.getElementById('legend-thinned');
    if (note) {
      note.hidden = thinnedNow === 0;
      note.textContent = counted(thinnedNow, 'grey glyph', 'grey glyphs') + ' not drawn in this view: >50% behind glyphs drawn (turn or zoom to see them)';
    }
  }
  function draw() { orientCut(); faceRings(); thinGlyphs(); renderer.render(scene, camera); placeLabels(); }
  // The light moves with the camera: from above-left of the eye.
  camera.add(light);
  camera.add(light.target);
  light.position.set(-0.3, 0.5, 1);
  light.target.position.set(0, 0, -1);
  scene.add(camera);
  controls.addEventListener('change', draw);

  // ---- layers and the cut ----
  function layer(id, object) {
    var box = document.getElementById(id);
    box.addEventListener('change', function () { object.visible = box.checked && !object.userData.empty; updateCut(); });
  }
  layer('layer-boundary', boundary);
  layer('layer-edges', edges);
  if (D.boundary_reduced) {
    // The edges of a reduced boundary are the clustering's, not the mesh's: off until asked for.
    var edgesBox = document.getElementById('layer-edges');
    edgesBox.checked = false;
    edges.visible = false;
    edgesBox.parentNode.appendChild(document.createTextNode(' (of the reduced drawing, not the mesh)'));
  }
  layer('layer-glyphs', glyphs);
  layer('layer-markers', markers);
  layer('layer-intersecting', intersecting);
  layer('layer-nonconforming', nonConforming);
  // Every colour drawn has a legend entry (issue 44): a swatch beside each
  // layer of one colour, with its count (the quality colours of the faces
  // and of the cut's cells are the bar's).
  // A filled square, a ring or a hollow diamond (the overlap markers' shape).
  function swatch(color, shape) {
    var sw = el('span', { class: shape ? 'swatch ' + shape : 'swatch' });
    if (shape) sw.style.borderColor = color; else sw.style.background = color;
    return sw;
  }
  function layerLegend(id, entries) {
    var row = document.getElementById(id).parentNode, list = el('div', { class: 'layer-legend' });
    // A layer with nothing in it: no row at all (issue 44 review), and nothing drawn.
    if (entries.every(function (e) { return /^0 /.test(e[1]); })) { row.style.display = 'none'; return; }
    entries.forEach(function (e) {
      var entry = el('div', { 'data-legend': e[2] }, [swatch(e[0], e[3]), e[1]]);
      if (/^0 /.test(e[1])) return;  // nothing of it drawn: no row (issue 44 review)
      list.appendChild(entry);
    });
    row.appendChild(list);
  }
  function counted(n, one, many) { return n + ' ' + (n === 1 ? one : many); }
  var byKind = { coincident: 0, intersection: 0 };
  D.markers.forEach(function (mk) { byKind[mk.kind === 'coincident' ? 'coincident' : 'intersection'] += 1; });
  layerLegend('layer-edges', [['#' + edges.material.color.getHexString(), 'edges', 'edges']]);
  // A marker stands for a group (report.json overlap.markers[].count): of
  // coincident vertices, or of intersecting cell pairs.
  var grouped = { coincident: 0, intersection: 0 };
  D.markers.forEach(function (mk) { grouped[mk.kind === 'coincident' ? 'coincident' : 'intersection'] += mk.count || 0; });
  layerLegend('layer-markers', [[colors.coincident, counted(byKind.coincident, 'marker', 'markers') + ' of ' +
      counted(grouped.coincident, 'coincident vertex', 'coincident vertices') + ' (one per group)', 'coincident', 'diamond'],
    [colors.intersection, counted(byKind.intersection, 'marker', 'markers') + ' of ' +
      counted(grouped.intersection, 'intersecting cell pair', 'intersecting cell pairs') + ' (one per group)', 'intersection', 'diamond']]);
  layerLegend('layer-intersecting', [[colors.intersecting_cells,
    counted(D.num_intersecting_cells || 0, 'intersecting cell', 'intersecting cells') + ' (edges)', 'intersecting_cells']]);
  layerLegend('layer-nonconforming', [[colors.non_conforming, counted(NC.count, 'non-conforming face', 'non-conforming faces') +
    ' (inside: a quad against two triangles; frame and diagonal drawn over the model, faint where hidden)', 'non_conforming']]);
  var axisSelect = document.getElementById('cut-axis'), slider = document.getElementById('cut');
  function updateCut() {
    var axis = Number(axisSelect.value);
    clipping.length = 0;
    if (axis >= 0) clipping.push(cut);
    low.visible = axis >= 0 && document.getElementById('layer-low').checked;
    planeOutline.visible = axis >= 0;
    var drawn = 0;
    low.children.forEach(function (part) {
      part.visible = part.userData.inverted || !!kindShown[part.userData.kind];
      if (part.visible) drawn += part.userData.cells;
    });
    document.getElementById('cut-note').textContent = axis >= 0
      ? L.count + ' cells with scaled Jacobian under ' + show(L.threshold) + lowKindsText + '; ' + drawn + ' drawn inside (the kinds ticked below; ' +
        lowInverted + ' inverted always drawn)'
      : '';
    document.getElementById('cut-legend').hidden = axis < 0;
    lowKindBoxes.hidden = axis < 0;
    scene.traverse(function (o) { if (o.material) o.material.needsUpdate = true; });
    draw();
  }
  axisSelect.addEventListener('change', updateCut);
  slider.addEventListener('input', updateCut);
  document.getElementById('layer-low').addEventListener('change', updateCut);

  // ---- picking ----
  var raycaster = new THREE.Raycaster(), pointer = new THREE.Vector2(), down = null;
  function row(label, value, attr) {
    var td = el('td', {}, [value]);
    if (attr) td.setAttribute(attr, String(value));
    return el('tr', {}, [el('td', {}, [label]), td]);
  }
  function showCluster(cl) {
    info.textContent = '';
    var links = el('p', {}, [el('a', { href: 'index.html#cluster-row-' + cl.id }, ['table row'])]);
    if (cl.is_top) {
      links.appendChild(text(' · '));
      links.appendChild(el('a', { href: 'index.html#cluster-' + cl.id }, ['C: sub-region']));
      links.appendChild(text(' · '));
      links.appendChild(el('a', { href: 'index.html#vertex-' + cl.vertex }, ['D: local view']));
      links.appendChild(text(' · '));
      links.appendChild(el('a', { href: 'index.html#corners-' + cl.vertex }, ['E: corner chart']));
    }
    info.appendChild(el('table', { id: 'picked-cluster' }, [
      row('cluster', cl.id, 'data-cluster'), row('size', cl.size, 'data-size'),
      row('min quality', show(cl.min_quality), 'data-min-quality'), row('vertex', cl.vertex, 'data-vertex')]));
    info.appendChild(links);
  }
  function showFace(f) {
    info.textContent = '';
    info.appendChild(el('table', { id: 'picked-face' }, [
      faceKind ? row('cell', D.faces.kind_names[faceKind[f]] + ' ' + faceHex[f], 'data-cell') : row('hex', faceHex[f], 'data-hex'),
      row('scaled Jacobian', show(faceSj[f]), 'data-sj'),
      row(D.cell_word === 'face' ? 'face' : 'boundary face', f, 'data-face')]));
    if (faceCorners) {
      var values = [];
      for (var c = 0; c < 8; ++c) values.push(show(faceCorners[8 * f + c]));
      info.appendChild(el('p', { 'data-corners': values.join(' ') }, ['corner scaled Jacobians: ' + values.join(', ')]));
    }
    if (D.cell_data) info.appendChild(el('p', {}, ['every metric of the ' + (D.cell_word || 'hex') + ': ', el('a', { href: D.cell_data }, [D.cell_data])]));
  }
  function pick(x, y) {
    var r = renderer.domElement.getBoundingClientRect();
    pointer.set((x - r.left) / r.width * 2 - 1, -((y - r.top) / r.height) * 2 + 1);
    raycaster.setFromCamera(pointer, camera);
    // Glyphs first: they show through the see-through faces.
    function hitsOf(objects) {
      return raycaster.intersectObjects(objects, false).filter(function (hit) {
        return hit.object.visible && (clipping.length === 0 || clipping[0].distanceToPoint(hit.point) >= 0);
      });
    }
    var glyphHits = glyphs.visible ? hitsOf(glyphSpheres) : [];
    if (glyphHits.length) { showCluster(glyphHits[0].object.userData.cluster); return; }
    var faceHits = boundary.visible ? hitsOf([boundary]) : [];
    if (faceHits.length) { showFace(Math.floor(faceHits[0].faceIndex / 2)); return; }
    info.textContent = 'Nothing here.';
  }
  renderer.domElement.addEventListener('pointerdown', function (e) { down = [e.clientX, e.clientY]; });
  renderer.domElement.addEventListener('pointerup', function (e) {
    if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) < 4) pick(e.clientX, e.clientY);
    down = null;
  });

  // ---- #cluster-K ----
  function focusFromHash() {
    var m = /^#cluster-(\d+)$/.exec(location.hash);
    if (!m) return false;
    var cl = D.clusters.filter(function (c) { return c.id === Number(m[1]); })[0];
    if (!cl) { info.textContent = 'Cluster ' + m[1] + ' is not among the listed clusters.'; return false; }
    var t = new THREE.Vector3().fromArray(cl.position);
    var eye = camera.position.clone().sub(controls.target).add(t);
    camera.position.copy(eye);
    controls.target.copy(t);
    camera.zoom = Math.max(1, frameHeight / Math.max(12 * cl.radius, 0.05 * diagonal));
    camera.updateProjectionMatrix();
    controls.update();
    showCluster(cl);
    draw();
    return true;
  }
  window.addEventListener('hashchange', focusFromHash);
  window.addEventListener('resize', resize);

  // The cluster legend: the labelled clusters' colours, then the one grey of
  // all others; an entry focuses its cluster.
  // One entry per coloured tie class ("#k-#m  N tied at q" for a tie),
  // then the grey ones with the range of their min quality.
  var legend = document.getElementById('clusters'), others = [];
  D.clusters.forEach(function (cl, rank) {
    if (!isColoured(cl, rank)) { others.push(cl); return; }
    if (!isClassFirst(cl, rank)) return;
    var sw = el('span', { class: 'swatch' }), tied = cl.tied || 1, q = show(Number(cl.min_quality.toPrecision(3)));
    sw.style.background = cl.color;
    legend.appendChild(el('a', { href: '#cluster-' + cl.id, class: tied > 1 ? 'tie' : '' }, [sw, tied > 1
      ? '#' + cl.id + '-#' + (cl.id + tied - 1) + '  ' + tied + ' tied at ' + q + ' (within ' + D.tie_tolerance + ')'
      : '#' + cl.id + '  ' + counted(cl.size, 'vertex', 'vertices') + ', min ' + q]));
  });
  if (others.length) {
    var sw = el('span', { class: 'swatch' });
    sw.style.background = others[0].color;
    sw.style.opacity = String(0.5);
    var othersLo = show(Number(others[0].min_quality.toPrecision(2)));
    var othersHi = show(Number(others[others.length - 1].min_quality.toPrecision(2)));
    legend.appendChild(el('div', { id: 'legend-others' }, [sw, counted(others.length, 'other cluster', 'other clusters') +
      ', min ' + othersLo + (others.length > 1 ? ' to ' + othersHi : '') + ': faint grey spheres (full radius)' +
      (others.some(function (cl) { return cl.min_quality < 0; }) ? '; the inverted ones less faint' : '')]));
    var thinnedNote = el('div', { id: 'legend-thinned', class: 'small' }, []);
    thinnedNote.hidden = true;
    legend.appendChild(thinnedNote);
  }
  // The rings, with ring swatches (view A's legend says the same).
  function ringEntry(color, label, id) {
    var sw = el('span', { class: 'swatch ring' });
    sw.style.borderColor = color;
    legend.appendChild(el('div', { id: id }, [sw, label]));
  }
  if (D.clusters.length && !worstTied) ringEntry(kDarkRing, 'ring: worst cluster #0', 'legend-ring-worst');
  if (D.clusters.some(function (cl) { return cl.min_quality < 0; }))
    ringEntry(invertedColor, 'ring: inverted (min < 0)', 'legend-ring-inverted');
  if (!D.clusters.length) legend.appendChild(text('no glyph: every vertex is above the threshold'));
  else legend.appendChild(el('div', { id: 'legend-label-rule', class: 'small' }, ['label: #rank (vertices in the cluster)' +
    (glyphScale < 1 ? '; glyphs drawn at ' + show(Number(glyphScale.toPrecision(3))) + ' of their radius (largest = ' +
      kMaxGlyphFraction * 100 + ' % of the model diagonal)' : '')]));

  var reduced = document.getElementById('reduced');
  D.reduced.forEach(function (r) { reduced.appendChild(el('p', { class: 'note' }, ['Reduced: ' + r])); });

  setField(0);
  nameField();
  updateCut();
  reset();
  focusFromHash();
  window.hqViewer = { camera: camera, renderer: renderer, scene: scene, controls: controls, data: D, draw: draw,
    glyphScale: glyphScale, ringPx: kRingPx, markerPx: kMarkerPx, markerRadiusPx: function () { return markerRadius * pxPerUnit(); },
    thinned: function () { return thinnedNow; }, ready: true };
})();
