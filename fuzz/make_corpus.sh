#!/usr/bin/env bash
# Writes the seed corpus of every fuzz target into OUT/<target>/ (default
# build-fuzz/corpus): the MEDIT meshes of examples/ plus small valid files of
# each format generated here (a unit cube, mostly, as in tests/io/). Nothing
# is copied from ../shared/data; everything goes into the build tree.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/build-fuzz/corpus}"
mkdir -p "$out"
python3 - "$root" "$out" <<'PY'
import base64, os, struct, sys, zlib
root, out = sys.argv[1], sys.argv[2]

def put(target, name, data):
    d = os.path.join(out, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)

P = [(0,0,0),(1,0,0),(1,1,0),(0,1,0),(0,0,1),(1,0,1),(1,1,1),(0,1,1)]
ex = os.path.join(root, "examples")
for f in sorted(os.listdir(ex)):
    if f.endswith(".mesh"):
        with open(os.path.join(ex, f), "rb") as src:
            data = src.read()
        for t in ("medit", "medit_triangles"):
            put(t, f, data)

# MEDIT
verts = "".join(f"{x} {y} {z} 0\n" for x, y, z in P)
medit = ("MeshVersionFormatted 2\nDimension\n3\n# comment\nVertices 9\n" + verts + "2 2 2 1\n"
         "Triangles 1\n1 2 3 0\nQuads 1\n1 2 3 4 0\nTetrahedra 1\n1 2 3 9 0\nFoo 1\nbar\n"
         "Hexahedra 1\n1 2 3 4 5 6 7 8 0\nEnd\n")
for t in ("medit", "medit_triangles"):
    put(t, "cube.mesh", medit)
    put(t, "cube_v1.mesh", "MeshVersionFormatted 1\nDimension 3\nVertices\n8\n" + verts +
        "Triangles\n2\n1 2 3 0\n1 3 4 0\nHexahedra\n1\n1 2 3 4 5 6 7 8 1\nEnd\n")

# legacy VTK: ASCII 4.2, ASCII 5.1, binary 3.0 and 5.1
pts = " ".join(f"{x} {y} {z}" for x, y, z in P)
put("vtk_legacy", "cube42.vtk", "# vtk DataFile Version 4.2\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 float\n"
    + pts + "\nCELLS 2 14\n8 0 1 2 3 4 5 6 7\n4 0 1 2 4\nCELL_TYPES 2\n12\n10\nCELL_DATA 2\n"
    "SCALARS q float 1\nLOOKUP_TABLE default\n0.5\n1\n")
put("vtk_legacy", "cube51.vtk", "# vtk DataFile Version 5.1\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n"
    + pts + "\nMETADATA\nINFORMATION 0\n\nCELLS 3 12\nOFFSETS vtktypeint64\n0 8 12\nCONNECTIVITY vtktypeint64\n"
    "0 1 2 3 4 5 6 7 0 1 2 4\nCELL_TYPES 2\n11\n10\n")
for v5 in (False, True):
    b = (f"# vtk DataFile Version {'5.1' if v5 else '3.0'}\ncube\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
         "FIELD FieldData 1\nTIME 1 1 double\n").encode() + struct.pack(">d", 2.5) + b"\nPOINTS 8 float\n"
    b += b"".join(struct.pack(">3f", *p) for p in P)
    if v5:
        b += b"\nCELLS 2 8\nOFFSETS vtktypeint32\n" + struct.pack(">2i", 0, 8) + b"\nCONNECTIVITY vtktypeint32\n" + struct.pack(">8i", *range(8))
    else:
        b += b"\nCELLS 1 9\n" + struct.pack(">9i", 8, *range(8))
    b += b"\nCELL_TYPES 1\n" + struct.pack(">i", 12) + b"\n"
    put("vtk_legacy", f"cube_binary{'51' if v5 else '30'}.vtk", b)

# VTU: ascii, binary (one base64 block), zlib, raw appended
xyz = [c for p in P for c in p]
def vtu(arrays, extra="", appended=b""):
    head = ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian"'
            + extra + ' header_type="UInt32">\n<UnstructuredGrid>\n<Piece NumberOfPoints="8" NumberOfCells="1">\n')
    s = head + "<Points>\n" + arrays[0] + "</Points>\n<Cells>\n" + "".join(arrays[1:]) + "</Cells>\n</Piece>\n</UnstructuredGrid>\n"
    if appended:
        return s.encode() + b'<AppendedData encoding="raw">\n_' + appended + b"\n</AppendedData>\n</VTKFile>\n"
    return (s + "</VTKFile>\n").encode()
def da(typ, name, fmt, body, comps="", attrs=""):
    c = f' NumberOfComponents="{comps}"' if comps else ""
    if body is None:
        return f'<DataArray type="{typ}" Name="{name}"{c} format="{fmt}"{attrs}/>\n'
    return f'<DataArray type="{typ}" Name="{name}"{c} format="{fmt}">\n{body}\n</DataArray>\n'
raw = {"Points": ("Float64", struct.pack("<24d", *xyz), "3"), "connectivity": ("Int64", struct.pack("<8q", *range(8)), ""),
       "offsets": ("Int64", struct.pack("<q", 8), ""), "types": ("UInt8", bytes([12]), "")}
txt = {"Points": " ".join(map(str, xyz)), "connectivity": "0 1 2 3 4 5 6 7", "offsets": "8", "types": "12"}
order = ["Points", "connectivity", "offsets", "types"]
put("vtu", "cube_ascii.vtu", vtu([da(raw[n][0], n, "ascii", txt[n], raw[n][2]) for n in order]))
put("vtu", "cube_binary.vtu", vtu([da(raw[n][0], n, "binary", base64.b64encode(struct.pack("<I", len(raw[n][1])) + raw[n][1]).decode(), raw[n][2]) for n in order]))
def zblock(data):
    z = zlib.compress(data)
    return base64.b64encode(struct.pack("<4I", 1, 32768, len(data), len(z))).decode() + base64.b64encode(z).decode()
put("vtu", "cube_zlib.vtu", vtu([da(raw[n][0], n, "binary", zblock(raw[n][1]), raw[n][2]) for n in order], ' compressor="vtkZLibDataCompressor"'))
app, arrs = b"", []
for n in order:
    arrs.append(da(raw[n][0], n, "appended", None, raw[n][2], f' offset="{len(app)}"'))
    app += struct.pack("<I", len(raw[n][1])) + raw[n][1]
put("vtu", "cube_appended.vtu", vtu(arrs, "", app))

# Gmsh 2.2 ASCII, 4.1 ASCII, 2.2 binary
put("gmsh", "cube22.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n9\n" + "".join(f"{i+1} {x} {y} {z}\n" for i, (x, y, z) in enumerate(P))
    + "19 2 2 2\n$EndNodes\n$Elements\n2\n1 3 2 0 1 1 2 3 4\n2 5 2 0 1 1 2 3 4 5 6 7 8\n$EndElements\n")
put("gmsh", "cube41.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 8 1 8\n3 1 0 8\n" + "".join(f"{i}\n" for i in range(1, 9))
    + "".join(f"{x} {y} {z}\n" for x, y, z in P) + "$EndNodes\n$Elements\n2 2 1 2\n2 1 3 1\n1 1 2 3 4\n3 1 5 1\n"
    "2 1 2 3 4 5 6 7 8\n$EndElements\n")
b = b"$MeshFormat\n2.2 1 8\n" + struct.pack("<i", 1) + b"\n$EndMeshFormat\n$Nodes\n8\n"
b += b"".join(struct.pack("<i3d", i + 1, *p) for i, p in enumerate(P))
b += b"\n$EndNodes\n$Elements\n1\n" + struct.pack("<5i", 5, 1, 1, 1, 0) + struct.pack("<8i", *range(1, 9)) + b"\n$EndElements\n"
put("gmsh", "cube22_binary.msh", b)

# OVM ASCII
put("ovm", "cube.ovm", "OVM ASCII\nVertices\n8\n" + "".join(f"{x} {y} {z}\n" for x, y, z in P)
    + "Edges\n12\n3 2\n2 1\n1 0\n0 3\n5 6\n6 7\n7 4\n4 5\n2 6\n5 1\n7 3\n0 4\nFaces\n6\n4 0 2 4 6\n4 8 10 12 14\n"
    "4 3 16 9 18\n4 13 20 7 22\n4 19 15 23 5\n4 1 21 11 17\nPolyhedra\n1\n6 0 2 4 6 8 10\n")

# Abaqus
put("abaqus", "cube.inp", "*HEADING\ncube\n*NODE\n" + "".join(f"{i+1}, {x}, {y}, {z}\n" for i, (x, y, z) in enumerate(P))
    + "*ELEMENT, TYPE=S4\n2, 1, 2, 3, 4\n*ELEMENT, TYPE=C3D8R\n1, 1, 2, 3, 4,\n5, 6, 7, 8\n"
    "*NSET, NSET=all, GENERATE\n1, 8, 1\n*ELSET, ELSET=hex\n1\n")

# Exodus II: classic netCDF (CDF-1) written by hand, so no netCDF Python
# module is needed: separate coordx/y/z and one combined coord variable.
def cdf_name(n):
    b = n.encode()
    return struct.pack(">i", len(b)) + b + b"\0" * (-len(b) % 4)
def cdf1(dims, variables):
    # dims: [(name, len)]; variables: [(name, [dim ids], nc_type, fmt, values, {att: text})]
    head = b"CDF\x01" + struct.pack(">i", 0)
    head += struct.pack(">ii", 0x0A, len(dims)) + b"".join(cdf_name(n) + struct.pack(">i", l) for n, l in dims)
    head += struct.pack(">ii", 0, 0)
    datas = [struct.pack(">%d%s" % (len(v[4]), v[3]), *v[4]) for v in variables]
    datas = [d + b"\0" * (-len(d) % 4) for d in datas]
    def var_list(begins):
        b = struct.pack(">ii", 0x0B, len(variables))
        for (name, dimids, typ, _, _, atts), data, begin in zip(variables, datas, begins):
            b += cdf_name(name) + struct.pack(">i", len(dimids)) + b"".join(struct.pack(">i", d) for d in dimids)
            if atts:
                b += struct.pack(">ii", 0x0C, len(atts))
                for an, av in atts.items():
                    ab = av.encode()
                    b += cdf_name(an) + struct.pack(">ii", 2, len(ab)) + ab + b"\0" * (-len(ab) % 4)
            else:
                b += struct.pack(">ii", 0, 0)
            b += struct.pack(">iii", typ, len(data), begin)
        return b
    size = len(head) + len(var_list([0] * len(variables)))
    begins, off = [], size
    for d in datas:
        begins.append(off); off += len(d)
    return head + var_list(begins) + b"".join(datas)
dims = [("num_nodes", 8), ("num_dim", 3), ("num_el_blk", 1), ("num_el_in_blk1", 1), ("num_nod_per_el1", 8)]
cols = [list(map(float, c)) for c in zip(*P)]
connect = ("connect1", [3, 4], 4, "i", list(range(1, 9)), {"elem_type": "HEX8"})
put("exodus", "cube_coordxyz.e", cdf1(dims, [(n, [0], 6, "d", cols[k], {}) for k, n in enumerate(("coordx", "coordy", "coordz"))] + [connect]))
put("exodus", "cube_coord.e", cdf1(dims, [("coord", [1, 0], 6, "d", cols[0] + cols[1] + cols[2], {}), connect]))

# OBJ, OFF, PLY (polygon_reader.h): a quad, a triangle and a pentagon
Q = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (2, 0, 0)]
put("obj", "quads.obj", "".join(f"v {x} {y} {z}\n" for x, y, z in Q) + "vt 0 0\nvn 0 0 1\n"
    "f 1 2/1 3//1 4/1/1\nf -4 5 -3\nf 1 2 5 \\\n 3 4\n")
put("off", "quads.off", "COFF\n5 3 0\n" + "".join(f"{x} {y} {z} 1 0 0 1\n" for x, y, z in Q) +
    "4 0 1 2 3\n3 1 4 2 0.5 0.5 0.5\n5 0 1 4 2 3\n")
for fmt in ("ascii", "binary_little_endian", "binary_big_endian"):
    head = (f"ply\nformat {fmt} 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
            "element face 2\nproperty list uchar int vertex_indices\nend_header\n").encode()
    faces = [[0, 1, 2, 3], [1, 4, 2]]
    if fmt == "ascii":
        body = "".join(f"{x} {y} {z}\n" for x, y, z in Q) + "".join(f"{len(f)} " + " ".join(map(str, f)) + "\n" for f in faces)
        put("ply", "quads_ascii.ply", head + body.encode())
    else:
        e = "<" if fmt == "binary_little_endian" else ">"
        body = b"".join(struct.pack(e + "3f", *p) for p in Q)
        body += b"".join(struct.pack(e + "B%di" % len(f), len(f), *f) for f in faces)
        put("ply", f"quads_{fmt}.ply", head + body)
PY
for d in "$out"/*/; do echo "corpus: $(basename "$d"): $(ls "$d" | wc -l) files" >&2; done
