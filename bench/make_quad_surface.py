#!/usr/bin/env python3
"""Issue 47: a refined real quad surface for the surface-mesh speed item.

Reads a MEDIT hex mesh (Dolphin_padded.mesh), takes its boundary quads
(the hex faces used by one hex, in the hex's outward order), splits each
into N x N quads by bilinear interpolation of its corners (the points on an
edge shared by both of its quads: the surface stays conforming, no new
boundary), and writes the quads as a binary VTU (appended raw data, UInt64
headers, Float64 points, Int64 connectivity and offsets, UInt8 types).
Dolphin_padded has 6,464 boundary quads: N = 13 gives 1,092,416 quads.

usage: make_quad_surface.py MESH.mesh N OUT.vtu
"""
import struct
import sys

# The hex's faces, outward (MEDIT / VTK node order 0..7).
HEX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))


def read_medit(path):
    """Vertices and hexahedra (0-based) of a MEDIT .mesh file."""
    tokens = open(path).read().split()
    points, hexes = [], []
    i = 0
    while i < len(tokens):
        word = tokens[i]
        if word == "Vertices":
            n = int(tokens[i + 1])
            i += 2
            for _ in range(n):
                points.append((float(tokens[i]), float(tokens[i + 1]), float(tokens[i + 2])))
                i += 4
        elif word == "Hexahedra":
            n = int(tokens[i + 1])
            i += 2
            for _ in range(n):
                hexes.append(tuple(int(t) - 1 for t in tokens[i:i + 8]))
                i += 9
        else:
            i += 1
    return points, hexes


def boundary_quads(hexes):
    """The faces of one hex only, each in its hex's outward order."""
    seen = {}
    for h in hexes:
        for f in HEX_FACES:
            q = tuple(h[k] for k in f)
            key = tuple(sorted(q))
            seen[key] = None if key in seen else q
    return [q for q in seen.values() if q is not None]


def refine(points, quads, n):
    """Each quad split into n x n; shared edges get the same points."""
    out = list(points)
    edge_points = {}  # (a, b) with a < b -> the n - 1 inner points from a to b

    def lerp(p, q, t):
        return (p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2]))

    def edge(a, b):
        key = (min(a, b), max(a, b))
        ids = edge_points.get(key)
        if ids is None:
            ids = []
            for k in range(1, n):
                ids.append(len(out))
                out.append(lerp(points[key[0]], points[key[1]], k / n))
            edge_points[key] = ids
        return ids if a < b else ids[::-1]

    cells = []
    for q in quads:
        p0, p1, p2, p3 = (points[v] for v in q)
        grid = [[0] * (n + 1) for _ in range(n + 1)]  # grid[j][i]: i along q0->q1, j along q0->q3
        grid[0][0], grid[0][n], grid[n][n], grid[n][0] = q[0], q[1], q[2], q[3]
        for k, v in enumerate(edge(q[0], q[1]), 1):
            grid[0][k] = v
        for k, v in enumerate(edge(q[3], q[2]), 1):
            grid[n][k] = v
        for k, v in enumerate(edge(q[0], q[3]), 1):
            grid[k][0] = v
        for k, v in enumerate(edge(q[1], q[2]), 1):
            grid[k][n] = v
        for j in range(1, n):
            for i in range(1, n):
                grid[j][i] = len(out)
                out.append(lerp(lerp(p0, p1, i / n), lerp(p3, p2, i / n), j / n))
        for j in range(n):
            for i in range(n):
                cells.append((grid[j][i], grid[j][i + 1], grid[j + 1][i + 1], grid[j + 1][i]))
    return out, cells


def write_vtu(path, points, quads):
    arrays = [
        ("Points", "Float64", 3, b"".join(struct.pack("<3d", *p) for p in points)),
        ("connectivity", "Int64", 1, struct.pack("<%dq" % (4 * len(quads)), *(v for q in quads for v in q))),
        ("offsets", "Int64", 1, struct.pack("<%dq" % len(quads), *range(4, 4 * len(quads) + 1, 4))),
        ("types", "UInt8", 1, bytes([9]) * len(quads)),
    ]
    offsets, offset = [], 0
    for _, _, _, data in arrays:
        offsets.append(offset)
        offset += 8 + len(data)

    def tag(k):
        name, kind, comps, _ = arrays[k]
        return '<DataArray type="%s" Name="%s" NumberOfComponents="%d" format="appended" offset="%d"/>\n' % (
            kind, name, comps, offsets[k])

    head = ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" '
            'header_type="UInt64">\n<UnstructuredGrid>\n<Piece NumberOfPoints="%d" NumberOfCells="%d">\n'
            '<Points>\n%s</Points>\n<Cells>\n%s%s%s</Cells>\n</Piece>\n</UnstructuredGrid>\n'
            '<AppendedData encoding="raw">\n_' % (len(points), len(quads), tag(0), tag(1), tag(2), tag(3)))
    with open(path, "wb") as f:
        f.write(head.encode())
        for _, _, _, data in arrays:
            f.write(struct.pack("<Q", len(data)))
            f.write(data)
        f.write(b"\n</AppendedData>\n</VTKFile>\n")


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    points, hexes = read_medit(sys.argv[1])
    quads = boundary_quads(hexes)
    n = int(sys.argv[2])
    # Only the points the surface uses (the hexes' inner nodes are left out).
    used = sorted({v for q in quads for v in q})
    index = {v: k for k, v in enumerate(used)}
    points = [points[v] for v in used]
    quads = [tuple(index[v] for v in q) for q in quads]
    points, cells = refine(points, quads, n)
    write_vtu(sys.argv[3], points, cells)
    print("make_quad_surface: %d boundary quads split %d x %d: %d quads, %d points -> %s"
          % (len(quads), n, n, len(cells), len(points), sys.argv[3]), file=sys.stderr)


if __name__ == "__main__":
    main()
