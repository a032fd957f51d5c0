#!/usr/bin/python3
"""Writes a hex mesh in every format meshio (Debian's python3-meshio) can
write and HQView reads, and what meshio itself reads back from each file.

Usage: meshio_write.py DUMP OUT_DIR

DUMP: "V H" on the first line, then V lines "x y z" (shortest round-trip
floats) and H lines of 8 0-based vertex ids (VTK_HEXAHEDRON order), as
written by tests/io/meshio_roundtrip_test.cpp.

For each variant it writes OUT_DIR/<variant>.<ext> and
OUT_DIR/<variant>.<ext>.expect, a dump (same layout) of meshio's own reading
of that file: its points and its hexahedra. OUT_DIR/files.txt lists one line
per variant: the file written, or "skip <variant>: <reason>" for a variant
that this meshio cannot write (e.g. Exodus without python3-netcdf4).

Exit code 0; 2 when meshio is not installed (the test then skips).
"""

import os
import sys
import warnings

try:
    import meshio
    import numpy as np
except ImportError as error:
    print(f"meshio not available: {error}", file=sys.stderr)
    sys.exit(2)


def read_dump(path):
    with open(path) as f:
        v, h = (int(t) for t in f.readline().split())
        points = np.array([[float(t) for t in f.readline().split()] for _ in range(v)], dtype=np.float64)
        hexes = np.array([[int(t) for t in f.readline().split()] for _ in range(h)], dtype=np.int64)
    return points.reshape(v, 3), hexes.reshape(h, 8)


def write_dump(path, points, hexes):
    # tolist() gives Python floats and ints at once: the same repr and str
    # as element by element, in a fifth of the time (this was half of the
    # round-trip test's Python time).
    with open(path, "w") as f:
        f.write(f"{len(points)} {len(hexes)}\n")
        f.writelines(" ".join(map(repr, p)) + "\n" for p in points.tolist())
        f.writelines(" ".join(map(str, h)) + "\n" for h in hexes.tolist())


VARIANTS = [
    # name, extension, writer
    ("vtu_ascii", "vtu", lambda f, m: meshio.vtu.write(f, m, binary=False)),
    ("vtu_binary", "vtu", lambda f, m: meshio.vtu.write(f, m, binary=True, compression=None)),
    ("vtu_binary_zlib", "vtu", lambda f, m: meshio.vtu.write(f, m, binary=True, compression="zlib")),
    ("gmsh22_ascii", "msh", lambda f, m: meshio.gmsh.write(f, m, fmt_version="2.2", binary=False)),
    ("gmsh22_binary", "msh", lambda f, m: meshio.gmsh.write(f, m, fmt_version="2.2", binary=True)),
    ("gmsh41_ascii", "msh", lambda f, m: meshio.gmsh.write(f, m, fmt_version="4.1", binary=False)),
    ("gmsh41_binary", "msh", lambda f, m: meshio.gmsh.write(f, m, fmt_version="4.1", binary=True)),
    ("abaqus", "inp", lambda f, m: meshio.abaqus.write(f, m)),
    ("exodus", "e", lambda f, m: meshio.exodus.write(f, m)),
]


def main():
    dump, out_dir = sys.argv[1], sys.argv[2]
    os.makedirs(out_dir, exist_ok=True)
    points, hexes = read_dump(dump)
    mesh = meshio.Mesh(points, [("hexahedron", hexes)])
    warnings.simplefilter("ignore")
    listing = []
    for name, ext, write in VARIANTS:
        path = os.path.join(out_dir, f"{name}.{ext}")
        try:
            write(path, mesh)
        except Exception as error:  # e.g. Exodus without netCDF4
            listing.append(f"skip {name}: {type(error).__name__}: {error}")
            continue
        back = meshio.read(path)
        blocks = [c.data for c in back.cells if c.type == "hexahedron"]
        back_hexes = np.concatenate(blocks) if blocks else np.zeros((0, 8), dtype=np.int64)
        write_dump(path + ".expect", back.points, back_hexes)
        listing.append(path)
    with open(os.path.join(out_dir, "files.txt"), "w") as f:
        f.write("".join(line + "\n" for line in listing))


if __name__ == "__main__":
    main()
