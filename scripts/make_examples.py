#!/usr/bin/env python3
"""Generates the small meshes in examples/ (committed with this script).

  ball.mesh            a cube grid mapped onto the unit ball, a few vertices perturbed
  ball.off             its reference surface: an icosphere of radius 1
  twisted_bar.mesh     a 3x3x16 bar twisted along its axis, folded at one layer (inverted hexes)
  duplicated_vertex.mesh  a 4x4x4 grid whose centre vertex is duplicated and split from 4 of its hexes

Run: python3 scripts/make_examples.py   (no dependencies beyond Python 3)
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "examples")


def fmt(x):
    return "%.12g" % x


def grid(nx, ny, nz):
    """Point ids and hexes (0-based, VTK order) of an nx*ny*nz grid, x fastest."""
    def vid(i, j, k):
        return i + (nx + 1) * (j + (ny + 1) * k)
    hexes = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                hexes.append([vid(i, j, k), vid(i + 1, j, k), vid(i + 1, j + 1, k), vid(i, j + 1, k),
                              vid(i, j, k + 1), vid(i + 1, j, k + 1), vid(i + 1, j + 1, k + 1), vid(i, j + 1, k + 1)])
    return vid, hexes


def write_medit(path, points, hexes, comment):
    with open(path, "w") as f:
        f.write("MeshVersionFormatted 1\n# %s\nDimension 3\n" % comment)
        f.write("Vertices\n%d\n" % len(points))
        for p in points:
            f.write("%s %s %s 0\n" % tuple(fmt(c) for c in p))
        f.write("Hexahedra\n%d\n" % len(hexes))
        for h in hexes:
            f.write(" ".join(str(v + 1) for v in h) + " 0\n")
        f.write("End\n")


def ball():
    n = 10
    vid, hexes = grid(n, n, n)
    points = []
    for k in range(n + 1):
        for j in range(n + 1):
            for i in range(n + 1):
                p = [-1 + 2 * i / n, -1 + 2 * j / n, -1 + 2 * k / n]
                inf = max(abs(c) for c in p)
                two = math.sqrt(sum(c * c for c in p))
                s = inf / two if two > 0 else 0.0
                points.append([c * s for c in p])
    # A few interior vertices pushed off their place: bad elements of several
    # sizes, one pushed far enough to fold (inverted corners).
    for (i, j, k), d in [((3, 4, 6), (0.09, -0.07, 0.05)),
                         ((7, 3, 4), (-0.14, 0.12, 0.0)), ((2, 7, 3), (0.22, 0.2, -0.18))]:
        v = vid(i, j, k)
        points[v] = [points[v][a] + d[a] for a in range(3)]
    write_medit(os.path.join(OUT, "ball.mesh"), points, hexes,
                "HQView example: a 10x10x10 cube grid mapped onto the unit ball, 3 interior vertices perturbed")


def icosphere(levels):
    t = (1 + math.sqrt(5)) / 2
    verts = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
             [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
             [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11],
             [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    verts = [[c / math.sqrt(sum(x * x for x in v)) for c in v] for v in verts]
    for _ in range(levels):
        cache = {}
        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(verts[a][i] + verts[b][i]) / 2 for i in range(3)]
                l = math.sqrt(sum(x * x for x in m))
                verts.append([x / l for x in m])
                cache[key] = len(verts) - 1
            return cache[key]
        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = new
    return verts, faces


def ball_reference():
    verts, faces = icosphere(4)
    with open(os.path.join(OUT, "ball.off"), "w") as f:
        f.write("OFF\n%d %d 0\n" % (len(verts), len(faces)))
        for v in verts:
            f.write("%s %s %s\n" % tuple(fmt(c) for c in v))
        for a, b, c in faces:
            f.write("3 %d %d %d\n" % (a, b, c))


def twisted_bar():
    nx, ny, nz = 3, 3, 16
    vid, hexes = grid(nx, ny, nz)
    points = []
    for k in range(nz + 1):
        # A smooth twist of 6 degrees per layer never inverts a corner (the
        # faces stay horizontal); the fold does: layer 9's vertices with
        # x > 0 sink below layer 8, so the 3 hexes of layer 8 under them are
        # inverted and their neighbours have negative corners.
        angle = math.radians(6 * k)
        c, s = math.cos(angle), math.sin(angle)
        for j in range(ny + 1):
            for i in range(nx + 1):
                x, y = i / nx - 0.5, j / ny - 0.5
                z = 8 / 4.0 - 0.08 if (k == 9 and i >= 2) else k / 4.0
                points.append([c * x - s * y, s * x + c * y, z])
    write_medit(os.path.join(OUT, "twisted_bar.mesh"), points, hexes,
                "HQView example: a 3x3x16 bar twisted 6 degrees per layer, folded at layer 9 (inverted hexes)")


def duplicated_vertex():
    n = 4
    vid, hexes = grid(n, n, n)
    points = [[i, j, k] for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)]
    centre = vid(2, 2, 2)
    points.append(list(points[centre]))  # same position, new id
    copy = len(points) - 1
    # The 4 hexes above the centre (z >= 2) use the copy: they no longer share
    # the vertex with the 4 below.
    for h in hexes:
        if centre in h and all(points[v][2] >= 2 for v in h):
            h[h.index(centre)] = copy
    write_medit(os.path.join(OUT, "duplicated_vertex.mesh"), points, hexes,
                "HQView example: 4x4x4 grid; the centre vertex is duplicated and the 4 hexes above it use the copy")


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    ball()
    ball_reference()
    twisted_bar()
    duplicated_vertex()
    print("wrote", ", ".join(sorted(os.listdir(OUT))))
