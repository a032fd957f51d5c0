#!/usr/bin/python3
"""Writes a quad-dominant surface mesh with Debian's python3-meshio as OBJ,
ASCII PLY and binary PLY (meshio's OFF writer keeps only triangles), for
tests/io/polygon_reader_test.cpp to read back with HQView's polygon reader.

Usage: meshio_polygon_write.py DUMP OUT_DIR

DUMP: "V Q T" on the first line, then V lines "x y z" (shortest round-trip
floats), Q lines of 4 and T lines of 3 0-based vertex ids. Writes
OUT_DIR/mesh.obj, OUT_DIR/mesh_ascii.ply and OUT_DIR/mesh_binary.ply.
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

dump, out = sys.argv[1], sys.argv[2]
with open(dump) as f:
    v, q, t = (int(w) for w in f.readline().split())
    points = np.array([[float(w) for w in f.readline().split()] for _ in range(v)], dtype=np.float64)
    quads = np.array([[int(w) for w in f.readline().split()] for _ in range(q)], dtype=np.int32).reshape(q, 4)
    triangles = np.array([[int(w) for w in f.readline().split()] for _ in range(t)], dtype=np.int32).reshape(t, 3)
mesh = meshio.Mesh(points, [("quad", quads), ("triangle", triangles)])
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    meshio.write(os.path.join(out, "mesh.obj"), mesh)
    meshio.write(os.path.join(out, "mesh_ascii.ply"), mesh, binary=False)
    meshio.write(os.path.join(out, "mesh_binary.ply"), mesh, binary=True)
