#!/usr/bin/python3
"""The hex structure of report.json and data/edges.csv, recounted without HQView.

An independent implementation (numpy, meshes read by meshio, nothing of
lib/hqview) of docs/contract.md's definitions:
  - edge valence = number of hexes with that edge (12 VTK_HEXAHEDRON edges
    a hex, vertex pairs sorted); boundary faces = quads used by one hex;
  - an edge on no boundary face is interior (singular if valence != 4), on
    two boundary faces boundary (singular if valence != 2), else non-manifold;
  - irregular boundary edge: valence != max(1, round(theta / 90)), theta the
    dihedral angle inside the mesh between its two boundary faces;
  - singular vertices touch a singular edge; nodes have != 2 singular edges;
  - curves = groups of singular edges joined through non-node vertices
    (union-find), which is the number of maximal chains.
It runs `hqview analyze --no-render --no-overlap` on the two examples and on
every hex mesh of ../shared/data and compares every count of
report.json's `structure`, the rows of data/edges.csv and the `singular`
column of data/vertices.csv.

Usage: check_structure.py HQVIEW OUTPUT_DIR SOURCE_DIR [SHARED_DATA_DIR]
Exit 0: passed; 1: failed; 77: numpy or meshio missing (skipped).
"""

import csv
import json
import os
import shutil
import subprocess
import sys

try:
    import meshio
    import numpy as np
except ImportError as e:
    print(f"SKIP: {e}; scripts/setup installs python3-numpy and python3-meshio")
    sys.exit(77)

HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
# Faces of VTK_HEXAHEDRON, outward for a positive hex.
HEX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from oracle_support import check, failures, read_medit  # noqa: E402


def read_legacy_vtk(path):
    """ASCII legacy VTK by tokens: the 8-point cells (hqview loads an 8-point cell
    of another type as a hexahedron, with a warning; hex_cube_coarse.vtk says 10)."""
    with open(path) as f:
        tokens = f.read().split()
    i = tokens.index("POINTS")
    n = int(tokens[i + 1])
    points = np.array(tokens[i + 3:i + 3 + 3 * n], dtype=float).reshape(n, 3)
    i = tokens.index("CELLS")
    num_cells, size = int(tokens[i + 1]), int(tokens[i + 2])
    entries = [int(t) for t in tokens[i + 3:i + 3 + size]]
    cells, k = [], 0
    for _ in range(num_cells):
        cells.append(entries[k + 1:k + 1 + entries[k]])
        k += 1 + entries[k]
    return points, np.array([c for c in cells if len(c) == 8], dtype=np.int64)


def read_hexes(path):
    if path.endswith(".mesh"):
        return read_medit(path)
    try:
        mesh = meshio.read(path)
    except BaseException as e:  # meshio 7 refuses some legacy files (hex_cube_coarse.vtk)
        print(f"note: meshio cannot read {os.path.basename(path)} ({str(e).strip()}): token reader")
        return read_legacy_vtk(path)
    hexes = [c.data for c in mesh.cells if c.type == "hexahedron"]
    return np.asarray(mesh.points, dtype=float)[:, :3], np.concatenate(hexes).astype(np.int64)


def structure(points, hexes):
    nv = len(points)
    edges = np.sort(hexes[:, HEX_EDGES].reshape(-1, 2), axis=1)
    edges = edges[edges[:, 0] != edges[:, 1]]
    uniq, valence = np.unique(edges, axis=0, return_counts=True)
    key = uniq[:, 0] * nv + uniq[:, 1]

    # Boundary faces: a sorted 4-tuple used once; keep the oriented quad.
    quads = hexes[:, HEX_FACES].reshape(-1, 4)
    sorted_quads = np.sort(quads, axis=1)
    _, inverse, counts = np.unique(sorted_quads, axis=0, return_inverse=True, return_counts=True)
    boundary = quads[counts[inverse.ravel()] == 1]
    # Each boundary face's 4 edges, mapped to unique-edge ids.
    bedges = np.sort(np.stack([boundary, np.roll(boundary, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
    face_of = np.repeat(np.arange(len(boundary)), 4)
    keep = bedges[:, 0] != bedges[:, 1]
    bedges, face_of = bedges[keep], face_of[keep]
    ids = np.searchsorted(key, bedges[:, 0] * nv + bedges[:, 1])
    num_faces = np.bincount(ids, minlength=len(uniq))

    interior = num_faces == 0
    bnd = num_faces == 2
    nonmanifold = ~interior & ~bnd
    singular = (interior & (valence != 4)) | (bnd & (valence != 2))

    # Dihedral angles of the two-face boundary edges (the first two faces).
    order = np.argsort(ids, kind="stable")
    sid, sface = ids[order], face_of[order]
    starts = np.searchsorted(sid, np.arange(len(uniq)))
    bidx = np.nonzero(bnd)[0]
    f1, f2 = boundary[sface[starts[bidx]]], boundary[sface[starts[bidx] + 1]]
    p = points

    def normal(q):
        n = np.cross(p[q[:, 2]] - p[q[:, 0]], p[q[:, 3]] - p[q[:, 1]])
        length = np.linalg.norm(n, axis=1, keepdims=True)
        return np.where(length > 0, n / np.where(length > 0, length, 1), n)

    n1, n2 = normal(f1), normal(f2)
    c1, c2 = p[f1].mean(axis=1), p[f2].mean(axis=1)
    phi = np.degrees(np.arccos(np.clip(np.sum(n1 * n2, axis=1), -1, 1)))
    convex = np.sum(n1 * (c2 - c1), axis=1) < 0
    theta = np.where(convex, 180 - phi, 180 + phi)
    ideal = np.maximum(1, np.floor(theta / 90 + 0.5)).astype(np.int64)  # round half away from 0 (theta > 0)
    irregular = np.zeros(len(uniq), dtype=bool)
    irregular[bidx] = valence[bidx] != ideal
    ideal_all = np.zeros(len(uniq), dtype=np.int64)
    ideal_all[bidx] = ideal

    sing = uniq[singular]
    degree = np.bincount(sing.ravel(), minlength=nv)
    vertex_singular = degree > 0
    node = vertex_singular & (degree != 2)
    # Curves: union-find over singular edges joined at non-node vertices.
    parent = list(range(len(sing)))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    at_vertex = {}
    for i, (a, b) in enumerate(sing):
        for v in (int(a), int(b)):
            if not node[v]:
                if v in at_vertex:
                    parent[find(i)] = find(at_vertex[v])
                else:
                    at_vertex[v] = i
    curves = len({find(i) for i in range(len(sing))})
    lengths = np.bincount([find(i) for i in range(len(sing))]) if len(sing) else np.array([])
    lengths = lengths[lengths > 0]

    def by_valence(mask):
        vals, cnt = np.unique(valence[mask & singular], return_counts=True)
        return {str(int(v)): int(c) for v, c in zip(vals, cnt)}

    counts = {
        "num_edges": len(uniq),
        "num_singular_edges_interior": int(np.sum(singular & interior)),
        "num_singular_edges_boundary": int(np.sum(singular & bnd)),
        "num_irregular_edges_boundary": int(np.sum(irregular)),
        "num_nonmanifold_edges": int(np.sum(nonmanifold)),
        "num_singular_vertices": int(np.sum(vertex_singular)),
        "num_singularity_nodes": int(np.sum(node)),
        "num_singular_curves": curves,
        "singular_edges_by_valence": {"interior": by_valence(interior), "boundary": by_valence(bnd)},
    }
    listed = singular | irregular | nonmanifold
    kind = np.where(interior, "interior", np.where(bnd, "boundary", "nonmanifold"))
    rows = {(int(a), int(b)): (int(valence[i]), str(kind[i]), int(singular[i]), int(ideal_all[i]), int(irregular[i]))
            for i, (a, b) in zip(np.nonzero(listed)[0], uniq[listed])}
    return counts, rows, vertex_singular, lengths


def compare(name, path, hqview, out):
    before = len(failures)
    bundle = os.path.join(out, name)
    shutil.rmtree(bundle, ignore_errors=True)
    result = subprocess.run([hqview, "analyze", path, "--no-render", "--no-overlap", "-q", "--data", "csv", "-o", bundle],
                            capture_output=True, text=True)
    if result.returncode not in (0, 1):
        check(False, f"{name}: hqview exited {result.returncode}: {result.stderr}")
        return
    with open(os.path.join(bundle, "report.json")) as f:
        report = json.load(f)["structure"]
    points, hexes = read_hexes(path)
    counts, rows, vertex_singular, lengths = structure(points, hexes)
    for k, v in counts.items():
        check(report[k] == v, f"{name}: structure.{k}: hqview {report[k]}, oracle {v}")
    if len(lengths):
        cl = report["curve_length"]
        check(cl["min"] == int(lengths.min()) and cl["max"] == int(lengths.max()),
              f"{name}: curve_length min/max: hqview {cl['min']}/{cl['max']}, oracle {lengths.min()}/{lengths.max()}")
    with open(os.path.join(bundle, "data", "edges.csv"), newline="") as f:
        table = list(csv.DictReader(f))
    got = {(int(r["v0"]), int(r["v1"])): (int(r["valence"]), r["kind"], int(r["singular"]),
                                          int(r["ideal_valence"] or 0), int(r["irregular"] or 0)) for r in table}
    check(len(got) == len(table), f"{name}: edges.csv repeats an edge")
    differ = sorted(set(got.items()) ^ set(rows.items()))
    check(not differ, f"{name}: edges.csv: {len(differ)} rows differ from the oracle, e.g. {differ[:4]}")
    check(all((r["curve"] != "-1") == (r["singular"] == "1") for r in table),
          f"{name}: edges.csv: a singular edge without a curve, or a curve on a regular edge")
    # Pure-hex meshes: no edge touches a non-hex cell.
    check(report["num_edges_touching_non_hex"] == 0 and all(r["touches_non_hex"] == "0" for r in table),
          f"{name}: a pure-hex mesh has edges touching non-hex cells")
    with open(os.path.join(bundle, "data", "vertices.csv"), newline="") as f:
        column = [r["singular"] == "1" for r in csv.DictReader(f)]
    check(column == list(vertex_singular), f"{name}: vertices.csv singular differs from the oracle")
    print(f"{name}: {counts['num_edges']} edges, {counts['num_singular_edges_interior']} singular interior, "
          f"{counts['num_singular_edges_boundary']} boundary, {counts['num_irregular_edges_boundary']} irregular, "
          f"{counts['num_singular_curves']} curves" + ("" if len(failures) > before else ": agree"))


def main():
    hqview, out, source = sys.argv[1], sys.argv[2], sys.argv[3]
    shared = sys.argv[4] if len(sys.argv) > 4 else os.path.join(source, "..", "shared", "data")
    os.makedirs(out, exist_ok=True)
    meshes = [os.path.join(source, "examples", n) for n in ("ball.mesh", "twisted_bar.mesh")]
    root = os.path.join(shared, "meshes")
    if os.path.isdir(root):
        for d, _, files in sorted(os.walk(root)):
            meshes += [os.path.join(d, f) for f in sorted(files) if f.endswith((".mesh", ".vtk"))]
    else:
        print(f"note: {root} absent: the examples only")
    for path in meshes:
        compare(os.path.splitext(os.path.basename(path))[0], path, hqview, out)
    print(f"{len(meshes)} meshes, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
