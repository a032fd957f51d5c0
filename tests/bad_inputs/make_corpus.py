#!/usr/bin/env python3
"""Writes the small files of tests/bad_inputs/ (run from anywhere; rewrites
them in place). The expected results are in expected.tsv, written by hand:
rerunning this script must not change them. Big, sparse, fifo, directory and
permission cases are made at test time (tests/e2e/bad_inputs_test.cpp), not
here. exodus_fuzz_oom_6f9e6fbb.e is a fuzz finding, kept as found."""
import os
import random
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def put(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


# A unit cube, VTK_HEXAHEDRON order.
P = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
HEAD = "MeshVersionFormatted 2\nDimension 3\n"
VERTS = "Vertices 8\n" + "".join(f"{x} {y} {z} 0\n" for x, y, z in P)
HEX = "Hexahedra 1\n1 2 3 4 5 6 7 8 0\n"

# --- MEDIT -----------------------------------------------------------------
put("medit_one_hex.mesh", HEAD + VERTS + HEX + "End\n")
put("medit_empty.mesh", "")
put("medit_truncated_after_version.mesh", "MeshVersionFormatted 2\n")
put("medit_truncated_after_vertices_count.mesh", HEAD + "Vertices 8\n")
put("medit_truncated_mid_vertices.mesh", HEAD + VERTS[: VERTS.index("1 1 0 0") + 4])
put("medit_truncated_after_hexahedra_count.mesh", HEAD + VERTS + "Hexahedra 1\n")
put("medit_truncated_mid_hexahedra.mesh", HEAD + VERTS + "Hexahedra 2\n1 2 3 4 5 6 7 8 0\n5 6 7 8 1")
put("medit_count_1e12.mesh", HEAD + "Vertices 1000000000000\n0 0 0 0\n")
put("medit_claims_1e9_hexes.mesh", HEAD + VERTS + "Hexahedra 1000000000\n1 2 3 4 5 6 7 8 0\n")
put("medit_negative_count.mesh", HEAD + VERTS + "Hexahedra -1\n")
put("medit_id_out_of_range.mesh", HEAD + VERTS + "Hexahedra 1\n1 2 3 4 5 6 7 9 0\n")
put("medit_id_zero.mesh", HEAD + VERTS + "Hexahedra 1\n0 2 3 4 5 6 7 8 0\n")
put("medit_nan.mesh", HEAD + VERTS.replace("1 1 1 0", "1 nan 1 0") + HEX)
put("medit_inf.mesh", HEAD + VERTS.replace("1 1 1 0", "1 1 -inf 0") + HEX)
put("medit_huge_coordinate.mesh", HEAD + VERTS.replace("1 1 1 0", "1 1 1e400 0") + HEX)
put("medit_text_garbage.mesh", "solid cube\n  facet normal 0 0 1\n")
rng = random.Random(11)
put("medit_binary_garbage.mesh", bytes([0x4D, 0x5A, 0x90, 0x00]) + bytes(rng.randrange(256) for _ in range(4092)))
# Every hex degenerate. All 8 corners one vertex id: not a hexahedron at all
# (refused). Eight distinct vertices at one point, or a flat hex: data to
# report (accepted, counted as degenerate).
put("medit_all_hexes_one_vertex_id.mesh", HEAD + VERTS + "Hexahedra 2\n1 1 1 1 1 1 1 1 0\n2 2 2 2 2 2 2 2 0\n")
same = "Vertices 16\n" + "0.5 0.5 0.5 0\n" * 8 + "2 2 2 0\n" * 8
put("medit_all_hexes_coincident_vertices.mesh",
    HEAD + same + "Hexahedra 2\n1 2 3 4 5 6 7 8 0\n9 10 11 12 13 14 15 16 0\n")
flat = "Vertices 12\n" + "".join(f"{x} {y} 0 0\n" for x in (0, 1, 2) for y in (0, 1)) * 2
put("medit_all_hexes_flat.mesh", HEAD + flat + "Hexahedra 2\n1 3 4 2 7 9 10 8 0\n3 5 6 4 9 11 12 10 0\n")

# --- legacy VTK ------------------------------------------------------------
VTK_HEAD = "# vtk DataFile Version 3.0\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\n"
VTK_POINTS = "POINTS 8 double\n" + "".join(f"{x} {y} {z}\n" for x, y, z in P)
VTK_CELLS = "CELLS 1 9\n8 0 1 2 3 4 5 6 7\nCELL_TYPES 1\n12\n"
put("vtk_one_hex.vtk", VTK_HEAD + VTK_POINTS + VTK_CELLS)
put("vtk_truncated_header.vtk", "# vtk DataFile Version 3.0\ncube\n")
put("vtk_truncated_mid_points.vtk", VTK_HEAD + VTK_POINTS[:40])
put("vtk_truncated_mid_cells.vtk", VTK_HEAD + VTK_POINTS + "CELLS 1 9\n8 0 1 2 3")
put("vtk_truncated_before_cell_types.vtk", VTK_HEAD + VTK_POINTS + "CELLS 1 9\n8 0 1 2 3 4 5 6 7\n")
put("vtk_count_1e12.vtk", VTK_HEAD + "POINTS 1000000000000 double\n0 0 0\n")
put("vtk_negative_count.vtk", VTK_HEAD + VTK_POINTS + "CELLS -1 9\n")
put("vtk_id_out_of_range.vtk", VTK_HEAD + VTK_POINTS + "CELLS 1 9\n8 0 1 2 3 4 5 6 8\nCELL_TYPES 1\n12\n")
put("vtk_nan.vtk", VTK_HEAD + VTK_POINTS.replace("1 1 1\n", "1 nan 1\n") + VTK_CELLS)
binary_points = b"".join(struct.pack(">3f", *p) for p in P)
put("vtk_binary_truncated.vtk",
    b"# vtk DataFile Version 3.0\ncube\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 float\n" + binary_points[:50])

# --- VTU -------------------------------------------------------------------
def vtu(num_points, num_cells, connectivity="0 1 2 3 4 5 6 7", points=None):
    points = points or " ".join(f"{x} {y} {z}" for x, y, z in P)
    return ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0">\n<UnstructuredGrid>\n'
            f'<Piece NumberOfPoints="{num_points}" NumberOfCells="{num_cells}">\n'
            f'<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">{points}</DataArray></Points>\n'
            '<Cells>\n'
            f'<DataArray type="Int64" Name="connectivity" format="ascii">{connectivity}</DataArray>\n'
            '<DataArray type="Int64" Name="offsets" format="ascii">8</DataArray>\n'
            '<DataArray type="UInt8" Name="types" format="ascii">12</DataArray>\n'
            "</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n")
put("vtu_one_hex.vtu", vtu(8, 1))
put("vtu_truncated.vtu", vtu(8, 1)[:300])
put("vtu_count_1e12.vtu", vtu(1000000000000, 1))
put("vtu_claims_1e9_cells.vtu", vtu(8, 1000000000))
put("vtu_negative_count.vtu", vtu(8, -1))
put("vtu_id_out_of_range.vtu", vtu(8, 1, "0 1 2 3 4 5 6 8"))
put("vtu_inf.vtu", vtu(8, 1, points=" ".join(f"{x} {y} {z}" for x, y, z in P[:7]) + " 0 1 inf"))

# --- Gmsh 2.2 --------------------------------------------------------------
MSH_HEAD = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
MSH_NODES = "$Nodes\n8\n" + "".join(f"{i + 1} {x} {y} {z}\n" for i, (x, y, z) in enumerate(P)) + "$EndNodes\n"
MSH_ELEMENTS = "$Elements\n1\n1 5 2 0 1 1 2 3 4 5 6 7 8\n$EndElements\n"
put("gmsh_one_hex.msh", MSH_HEAD + MSH_NODES + MSH_ELEMENTS)
put("gmsh_truncated_mid_nodes.msh", MSH_HEAD + MSH_NODES[:60])
put("gmsh_truncated_mid_elements.msh", MSH_HEAD + MSH_NODES + "$Elements\n1\n1 5 2 0 1 1 2 3")
put("gmsh_count_1e12.msh", MSH_HEAD + "$Nodes\n1000000000000\n1 0 0 0\n$EndNodes\n")
put("gmsh_negative_count.msh", MSH_HEAD + MSH_NODES + "$Elements\n-5\n$EndElements\n")
put("gmsh_unknown_node.msh", MSH_HEAD + MSH_NODES + "$Elements\n1\n1 5 2 0 1 1 2 3 4 5 6 7 99\n$EndElements\n")

# --- Exodus (classic netCDF, written field by field) -----------------------
def cdf1(dims, variables):
    """dims: [(name, length)]; variables: [(name, dim ids, nc_type, data bytes, text attributes)]."""
    def name(s):
        b = s.encode()
        return struct.pack(">i", len(b)) + b + b"\0" * (-len(b) % 4)

    def header(begins):
        h = b"CDF\x01" + struct.pack(">i", 0)
        h += struct.pack(">ii", 0x0A, len(dims)) + b"".join(name(n) + struct.pack(">i", l) for n, l in dims)
        h += struct.pack(">ii", 0, 0)
        h += struct.pack(">ii", 0x0B, len(variables))
        for (vname, ids, nc_type, data, atts), begin in zip(variables, begins):
            h += name(vname) + struct.pack(">i", len(ids)) + b"".join(struct.pack(">i", i) for i in ids)
            if atts:
                h += struct.pack(">ii", 0x0C, len(atts))
                for an, av in atts.items():
                    h += name(an) + struct.pack(">ii", 2, len(av)) + av.encode() + b"\0" * (-len(av) % 4)
            else:
                h += struct.pack(">ii", 0, 0)
            h += struct.pack(">iii", nc_type, len(data) + (-len(data) % 4), begin)
        return h

    size = len(header([0] * len(variables)))
    begins = []
    for v in variables:
        begins.append(size)
        size += len(v[3]) + (-len(v[3]) % 4)
    return header(begins) + b"".join(v[3] + b"\0" * (-len(v[3]) % 4) for v in variables)


def exodus(num_nodes_claimed=8, points=P):
    dims = [("num_nodes", num_nodes_claimed), ("num_dim", 3), ("num_el_blk", 1), ("num_el_in_blk1", 1),
            ("num_nod_per_el1", 8)]
    cols = [struct.pack(">8d", *[p[k] for p in points]) for k in range(3)]
    variables = [(n, [0], 6, cols[k], {}) for k, n in enumerate(("coordx", "coordy", "coordz"))]
    variables.append(("connect1", [3, 4], 4, struct.pack(">8i", *range(1, 9)), {"elem_type": "HEX8"}))
    return cdf1(dims, variables)


put("exodus_one_hex.e", exodus())
put("exodus_truncated.e", exodus()[:-20])
put("exodus_truncated_header.e", exodus()[:100])
put("exodus_claims_1e9_nodes.e", exodus(1000000000))

# --- reference surfaces (--reference, with examples/twisted_bar.mesh) -----
put("reference_empty.off", "OFF\n0 0 0\n")
put("reference_empty_file.obj", "")
put("reference_one_degenerate_triangle.off", "OFF\n3 1 0\n0 0 0\n1 1 1\n2 2 2\n3 0 1 2\n")
put("reference_one_point_triangle.off", "OFF\n3 1 0\n1 1 1\n1 1 1\n1 1 1\n3 0 1 2\n")

# --- Abaqus and OpenVolumeMesh --------------------------------------------
INP_NODES = "*NODE\n" + "".join(f"{i + 1}, {x}, {y}, {z}\n" for i, (x, y, z) in enumerate(P))
put("abaqus_one_hex.inp", "*HEADING\ncube\n" + INP_NODES + "*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4, 5, 6, 7, 8\n")
put("abaqus_truncated_mid_element.inp", INP_NODES + "*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4")
put("abaqus_id_out_of_range.inp", INP_NODES + "*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4, 5, 6, 7, 99\n")
put("abaqus_nan.inp", INP_NODES.replace("7, 1, 1, 1", "7, 1, nan, 1") + "*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4, 5, 6, 7, 8\n")
put("abaqus_binary_garbage.inp", b"*NODE\n1, 0, 0, 0\n\x00\x01\x02\x03")
put("ovm_truncated_mid_vertices.ovm", "OVM ASCII\nVertices\n8\n0 0 0\n1 0 0\n1 1")
put("ovm_count_1e12.ovm", "OVM ASCII\nVertices\n1000000000000\n0 0 0\n")
put("ovm_negative_count.ovm", "OVM ASCII\nVertices\n-8\n")

# netCDF-4 (HDF5) signature, then noise: refused by the HDF5 library.
put("exodus_hdf5_garbage.e", b"\x89HDF\r\n\x1a\n" + bytes(random.Random(5).randrange(256) for _ in range(2000)))
put("reference_off_claims_1e9.off", "OFF\n1000000000 1000000000 0\n0 0 0\n")
put("reference_ply_claims_1e9.ply",
    "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n")
# Binary STL: 80-byte header, uint32 count (1000 here), 50 bytes per triangle (2 here).
put("reference_stl_count_mismatch.stl", b"\0" * 80 + struct.pack("<I", 1000) + b"\0" * 100)
put("reference_binary_garbage.obj", b"v 0 0 0\n\0\1\2\3")

# --- Coordinates of extreme magnitude (issue 22) ---------------------------
# The cube with corner 1 at 1e-124 and corner 6 at 1.3e308: finite, so every
# reader takes them, but no physical mesh has them (squared lengths
# overflow, exact geometry on such numbers crawls): refused after reading,
# with one message for every format. Denormal coordinates are analysed.
X = [(1e-124, 0.0, 0.0) if i == 1 else (1.3e308, 1.0, 1.0) if i == 6 else p for i, p in enumerate(P)]
DENORMAL = [(x * 1e-310, y * 1e-310, z * 1e-310) for x, y, z in P]


def text(v):
    return repr(float(v))


put("medit_extreme_coordinates.mesh",
    HEAD + "Vertices 8\n" + "".join(f"{text(x)} {text(y)} {text(z)} 0\n" for x, y, z in X) + HEX)
put("medit_denormal_coordinates.mesh",
    HEAD + "Vertices 8\n" + "".join(f"{text(x)} {text(y)} {text(z)} 0\n" for x, y, z in DENORMAL) + HEX)
put("vtk_extreme_coordinates.vtk",
    VTK_HEAD + "POINTS 8 double\n" + "".join(f"{text(x)} {text(y)} {text(z)}\n" for x, y, z in X) + VTK_CELLS)
put("vtk_binary_extreme_coordinates.vtk",
    b"# vtk DataFile Version 3.0\ncube\nBINARY\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n"
    + b"".join(struct.pack(">3d", *p) for p in X)
    + b"\nCELLS 1 9\n" + struct.pack(">9i", 8, *range(8)) + b"\nCELL_TYPES 1\n" + struct.pack(">i", 12) + b"\n")
put("vtu_extreme_coordinates.vtu", vtu(8, 1, points=" ".join(f"{text(x)} {text(y)} {text(z)}" for x, y, z in X)))
put("gmsh_extreme_coordinates.msh",
    MSH_HEAD + "$Nodes\n8\n" + "".join(f"{i + 1} {text(x)} {text(y)} {text(z)}\n" for i, (x, y, z) in enumerate(X))
    + "$EndNodes\n" + MSH_ELEMENTS)
put("abaqus_extreme_coordinates.inp",
    "*NODE\n" + "".join(f"{i + 1}, {text(x)}, {text(y)}, {text(z)}\n" for i, (x, y, z) in enumerate(X))
    + "*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4, 5, 6, 7, 8\n")
put("exodus_extreme_coordinates.e", exodus(points=X))

# 1,500 unit cubes, each shifted by 1e-4 along x from the last: every box
# overlaps every other, so the overlap stage meets over a million candidate
# pairs and stops at its work budget instead of testing them (294 KB).
stack = []
for i in range(1500):
    stack += [(x + 1e-4 * i, y, z) for x, y, z in P]
put("medit_overlapping_stack.mesh",
    HEAD + f"Vertices {len(stack)}\n" + "".join(f"{text(x)} {text(y)} {text(z)} 0\n" for x, y, z in stack)
    + "Hexahedra 1500\n" + "".join(" ".join(str(8 * i + k + 1) for k in range(8)) + " 0\n" for i in range(1500)))

# --- Messages are text (issue 46) -------------------------------------------
# A byte that is not UTF-8 (0xA6) and ESC (0x1B) where each reader quotes the
# file in its message: both shown as \xa6\x1b, never raw. The VTU closing
# tag with a flipped byte is the case found by byte mutation.
BAD = b"\xa6\x1b"
put("medit_not_utf8_coordinate.mesh", (HEAD + VERTS).encode().replace(b"1 1 1 0", b"1 " + BAD + b" 1 0") + HEX.encode())
put("vtk_not_utf8_dataset.vtk",
    VTK_HEAD.encode().replace(b"UNSTRUCTURED_GRID", b"UNSTRUCTURED_" + BAD + b"GRID") + (VTK_POINTS + VTK_CELLS).encode())
put("vtu_not_utf8_closing_tag.vtu", vtu(8, 1).encode().replace(b"</DataArray>", b"</D" + BAD + b"taArray>", 1))
put("vtu_not_utf8_attribute.vtu", vtu(8, 1).encode().replace(b'format="ascii"', b'format="asc' + BAD + b'ii"', 1))
put("gmsh_not_utf8_section.msh", (MSH_HEAD + MSH_NODES).encode().replace(b"$EndNodes", b"$End" + BAD + b"Nodes")
    + MSH_ELEMENTS.encode())
put("abaqus_not_utf8_node_id.inp",
    ("*HEADING\ncube\n" + INP_NODES).encode() + b"*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4, 5, 6, " + BAD + b", 8\n")
put("ovm_not_utf8_keyword.ovm", b"OVM ASCII\nVert" + BAD + b"ices\n8\n0 0 0\n")
put("exodus_not_utf8_variable_name.e", exodus()[:-20].replace(b"connect1", b"con" + BAD + b"ct1"))
# --- Cells other than hexahedra (issue 46): a cube plus a tetrahedron, a
# wedge or a pyramid on top of it, each with one fault: a repeated node, a
# node out of range, a node count that does not match the type. (A mesh of
# tetrahedra only is analysed since the pipeline covers every kind.)
APEX = [(0.5, 0.5, 1.5), (0, 0.5, 1.5), (1, 0.5, 1.5)]  # points 9, 10, 11 (1-based)
PA = P + APEX
VERTS_A = f"Vertices {len(PA)}\n" + "".join(f"{x} {y} {z} 0\n" for x, y, z in PA)
put("medit_tet_repeated_vertex.mesh", HEAD + VERTS_A + HEX + "Tetrahedra 1\n5 6 9 9 0\nEnd\n")
put("medit_prism_id_out_of_range.mesh", HEAD + VERTS_A + HEX + "Prisms 1\n5 8 10 6 7 12 0\nEnd\n")
VTK_POINTS_A = f"POINTS {len(PA)} double\n" + "".join(f"{x} {y} {z}\n" for x, y, z in PA)
put("vtk_tet_wrong_point_count.vtk",
    VTK_HEAD + VTK_POINTS_A + "CELLS 2 15\n8 0 1 2 3 4 5 6 7\n5 4 5 6 8 9\nCELL_TYPES 2\n12\n10\n")
put("vtu_pyramid_repeated_point.vtu",
    vtu(11, 2, "0 1 2 3 4 5 6 7 4 5 6 6 8", " ".join(f"{x} {y} {z}" for x, y, z in PA))
    .replace(">8</DataArray>", ">8 13</DataArray>").replace(">12</DataArray>", ">12 14</DataArray>"))
put("gmsh_wedge_wrong_node_count.msh",
    MSH_HEAD + "$Nodes\n11\n" + "".join(f"{i + 1} {x} {y} {z}\n" for i, (x, y, z) in enumerate(PA)) + "$EndNodes\n"
    + "$Elements\n2\n1 5 2 0 1 1 2 3 4 5 6 7 8\n2 6 2 0 1 5 6 10 8 7\n$EndElements\n")
put("abaqus_c3d4_node_out_of_range.inp",
    "*NODE\n" + "".join(f"{i + 1}, {x}, {y}, {z}\n" for i, (x, y, z) in enumerate(PA))
    + "*ELEMENT, TYPE=C3D8\n1, 1, 2, 3, 4, 5, 6, 7, 8\n*ELEMENT, TYPE=C3D4\n2, 5, 6, 7, 12\n")
# Higher-order cells with a node count that does not match their type, and
# a hexahedron whose repeated node is not a collapse pattern (a collapsed
# wedge, pyramid or tetrahedron is read; this is refused as before).
put("vtk_quadratic_hex_wrong_point_count.vtk",
    VTK_HEAD + VTK_POINTS_A + "CELLS 1 20\n19 0 1 2 3 4 5 6 7 8 9 10 0 1 2 3 4 5 6 7\nCELL_TYPES 1\n25\n")
put("vtu_lagrange_wedge_wrong_point_count.vtu",
    vtu(11, 2, "0 1 2 3 4 5 6 7 4 5 9 7 6 10 8", " ".join(f"{x} {y} {z}" for x, y, z in PA))
    .replace(">8</DataArray>", ">8 15</DataArray>").replace(">12</DataArray>", ">12 73</DataArray>"))
put("gmsh_tet10_wrong_node_count.msh",
    MSH_HEAD + "$Nodes\n11\n" + "".join(f"{i + 1} {x} {y} {z}\n" for i, (x, y, z) in enumerate(PA)) + "$EndNodes\n"
    + "$Elements\n2\n1 5 2 0 1 1 2 3 4 5 6 7 8\n2 11 2 0 1 5 6 7 9 1 2 3 4 5\n$EndElements\n")
put("abaqus_c3d20_wrong_node_count.inp",
    "*NODE\n" + "".join(f"{i + 1}, {x}, {y}, {z}\n" for i, (x, y, z) in enumerate(PA))
    + "*ELEMENT, TYPE=C3D20\n1, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 1, 2, 3, 4, 5, 6, 7, 8\n")
put("vtk_hex_repeated_not_collapse.vtk", VTK_HEAD + VTK_POINTS + "CELLS 1 9\n8 0 1 2 3 4 5 6 0\nCELL_TYPES 1\n12\n")
# Six triangular half-faces: not a hexahedron, tetrahedron, wedge or pyramid.
put("ovm_polyhedron_not_a_cell_kind.ovm",
    "OVM ASCII\nVertices\n3\n0 0 0\n1 0 0\n0 1 0\nEdges\n3\n0 1\n1 2\n2 0\n"
    "Faces\n1\n3 0 2 4\nPolyhedra\n1\n6 0 1 0 1 0 1\n")

# --- OBJ, OFF, PLY surface meshes (polygon_reader.h) --------------------------
SQ = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
OBJ_V = "".join(f"v {x} {y} {z}\n" for x, y, z in SQ)
put("obj_id_out_of_range.obj", OBJ_V + "f 1 2 3 9\n")
put("obj_negative_id_before_vertices.obj", "v 0 0 0\nf -1 -2 -3\n" + OBJ_V)
put("obj_nan.obj", OBJ_V.replace("v 1 1 0", "v 1 nan 0") + "f 1 2 3 4\n")
put("obj_not_utf8_corner.obj", OBJ_V.encode() + b"f 1 2 3 \xa6\x1b\n")
put("off_claims_1e9.off", "OFF\n2000000000 1 0\n0 0 0\n")
put("off_truncated_mid_faces.off", "OFF\n4 2 0\n" + "".join(f"{x} {y} {z}\n" for x, y, z in SQ) + "4 0 1 2 3\n3 0 1")
put("off_binary.off", b"OFF BINARY\n" + struct.pack(">3i", 4, 1, 0) + b"\0" * 16)
PLY_HEAD = ("ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n").encode()
PLY_BODY = b"".join(struct.pack("<3f", *p) for p in SQ) + struct.pack("<B4i", 4, 0, 1, 2, 3)
put("ply_truncated_binary.ply", PLY_HEAD + PLY_BODY[:-1])
put("ply_claims_1e9_faces.ply", PLY_HEAD.replace(b"element face 1", b"element face 1000000000") + PLY_BODY)
put("ply_id_out_of_range.ply", PLY_HEAD + PLY_BODY[:-4] + struct.pack("<i", 4))
