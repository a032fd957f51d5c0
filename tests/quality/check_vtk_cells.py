#!/usr/bin/python3
"""HQView's cell kernels against VTK 9.1's vtkMeshQuality on real meshes.

Debian's Gmsh (built-in geometry kernel) makes, in OUTPUT_DIR:
  - a unit box meshed with tetrahedra, graded from h = 0.03 at one corner to
    0.15 (a few thousand tets; its boundary triangles, in 3-D, are kept);
  - a warped (non-planar) ruled surface recombined into quads (Frontal-
    Delaunay, Mesh.Algorithm = 6), and the same surface left as triangles.
Each kind's cells are put in a grid of their own and run through
vtkMeshQuality (Debian's python3-vtk9 9.1) once per measure; the size
metrics' mean is the filter's own (the mean over the cells of that kind).
HQView's kernels (the cell_metrics_dump helper) get the same corners and
that mean, and every cell's value must agree to 1e-9 relative (absolute
below 1e-12) for every metric VTK 9.1 has and agrees with Verdict 1.4.5 on:
  tet: all 15 of VTK's (inradius, mean_ratio, normalized_inradius,
       equivolume_skew, squish_index, equiangle_skew are not in VTK 9.1;
       its aspect_beta is not in Verdict 1.4.5);
  triangle: all 13 of VTK's (not in VTK 9.1: equiangle_skew,
       normalized_inradius);
  quad: VTK's 23 less aspect_ratio (another formula in VTK 9.1),
       relative_size_squared, shape_and_size and shear_and_size (VTK 9.1
       resets the mean to the cell's own area) -- see quirks.quad of
       ../shared/data/verdict/cell_oracle_cases.json; equiangle_skew is not
       in VTK 9.1.
Prints per kind and metric the number of cells and the largest relative
difference. Usage: check_vtk_cells.py CELL_METRICS_DUMP OUTPUT_DIR
Exit 0: passed; 1: failed; 77: gmsh or VTK's Python module missing.
"""

import math
import os
import shutil
import subprocess
import sys

try:
    from vtkmodules.vtkCommonCore import vtkIdList
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
    from vtkmodules.vtkFiltersVerdict import vtkMeshQuality
    from vtkmodules.vtkIOLegacy import vtkUnstructuredGridReader
except ImportError:
    print("VTK's Python module (python3-vtk9) is missing: skipped")
    sys.exit(77)

GMSH = shutil.which("gmsh") or "/usr/bin/gmsh"

BOX_GEO = """
Point(1) = {0, 0, 0, 0.03}; Point(2) = {1, 0, 0, 0.15};
Point(3) = {1, 1, 0, 0.15}; Point(4) = {0, 1, 0, 0.15};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Extrude {0, 0, 1} { Surface{1}; }
"""

WARPED_GEO = """
Point(1) = {0, 0, 0, 0.08}; Point(2) = {1, 0, 0.3, 0.08};
Point(3) = {1.2, 1, 0, 0.08}; Point(4) = {0, 0.9, 0.4, 0.08};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Surface(1) = {1};
Mesh.Algorithm = 6;
"""

# HQView name -> vtkMeshQuality measure setter suffix, per kind.
TET = {
    "aspect_frobenius": "AspectFrobenius", "aspect_gamma": "AspectGamma", "aspect_ratio": "AspectRatio",
    "collapse_ratio": "CollapseRatio", "condition": "Condition", "distortion": "Distortion",
    "edge_ratio": "EdgeRatio", "jacobian": "Jacobian", "minimum_angle": "MinAngle", "radius_ratio": "RadiusRatio",
    "relative_size_squared": "RelativeSizeSquared", "scaled_jacobian": "ScaledJacobian", "shape": "Shape",
    "shape_and_size": "ShapeAndSize", "volume": "Volume",
}
TRIANGLE = {
    "area": "Area", "aspect_frobenius": "AspectFrobenius", "aspect_ratio": "AspectRatio", "condition": "Condition",
    "distortion": "Distortion", "edge_ratio": "EdgeRatio", "maximum_angle": "MaxAngle", "minimum_angle": "MinAngle",
    "radius_ratio": "RadiusRatio", "relative_size_squared": "RelativeSizeSquared",
    "scaled_jacobian": "ScaledJacobian", "shape": "Shape", "shape_and_size": "ShapeAndSize",
}
QUAD = {
    "area": "Area", "condition": "Condition", "distortion": "Distortion", "edge_ratio": "EdgeRatio",
    "jacobian": "Jacobian", "maximum_angle": "MaxAngle", "max_aspect_frobenius": "MaxAspectFrobenius",
    "max_edge_ratio": "MaxEdgeRatios", "med_aspect_frobenius": "MedAspectFrobenius", "minimum_angle": "MinAngle",
    "oddy": "Oddy", "radius_ratio": "RadiusRatio", "scaled_jacobian": "ScaledJacobian", "shape": "Shape",
    "shear": "Shear", "skew": "Skew", "stretch": "Stretch", "taper": "Taper", "warpage": "Warpage",
}
SETTER = {"tet": "SetTetQualityMeasureTo", "triangle": "SetTriangleQualityMeasureTo", "quad": "SetQuadQualityMeasureTo"}
SIZE = {"tet": "Volume", "triangle": "Area", "quad": "Area"}
VTK_TYPE = {"tet": 10, "triangle": 5, "quad": 9}


def gmsh(geo_text, path, dimension, extra=()):
    geo = path + ".geo"
    with open(geo, "w") as f:
        f.write(geo_text)
    out = path + ".vtk"
    subprocess.run([GMSH, "-%d" % dimension, geo, "-format", "vtk", "-o", out, *extra], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=300)
    reader = vtkUnstructuredGridReader()
    reader.SetFileName(out)
    reader.Update()
    return reader.GetOutput()


def cells_of(grid, kind):
    """A grid with only the cells of one kind (same points), and their corners."""
    out = vtkUnstructuredGrid()
    out.SetPoints(grid.GetPoints())
    corners = []
    ids = vtkIdList()
    for c in range(grid.GetNumberOfCells()):
        if grid.GetCellType(c) != VTK_TYPE[kind]:
            continue
        grid.GetCellPoints(c, ids)
        out.InsertNextCell(VTK_TYPE[kind], ids)
        corners.append([grid.GetPoint(ids.GetId(i)) for i in range(ids.GetNumberOfIds())])
    return out, corners


def vtk_quality(grid, kind, measure):
    q = vtkMeshQuality()
    q.SetInputData(grid)
    getattr(q, SETTER[kind] + measure)()
    q.Update()
    array = q.GetOutput().GetCellData().GetArray("Quality")
    return [array.GetValue(i) for i in range(array.GetNumberOfTuples())]


def hqview_values(helper, kind, corners, average):
    text = "\n".join(" ".join("%.17g" % x for p in cell for x in p) for cell in corners) + "\n"
    run = subprocess.run([helper, kind, "%.17g" % average], input=text, capture_output=True, text=True, check=True)
    lines = run.stdout.strip().split("\n")
    names = lines[0].split(",")
    rows = [[float(v) for v in line.split(",")] for line in lines[1:]]
    return {name: [row[i] for row in rows] for i, name in enumerate(names)}


def compare(helper, kind, grid, table, label):
    sub, corners = cells_of(grid, kind)
    n = len(corners)
    if n < 100:
        print("FAIL %s: only %d %s cells" % (label, n, kind))
        return False
    sizes = vtk_quality(sub, kind, SIZE[kind])
    average = math.fsum(sizes) / n  # vtkMeshQuality's mean of the kind's size
    ours = hqview_values(helper, kind, corners, average)
    ok = True
    for name, measure in sorted(table.items()):
        theirs = vtk_quality(sub, kind, measure)
        worst = 0.0
        bad = 0
        for a, b in zip(ours[name], theirs):
            scale = max(abs(a), abs(b))
            diff = abs(a - b)
            rel = diff / scale if scale > 0 else 0.0
            if diff > 1e-12 and rel > 1e-9:
                bad += 1
            worst = max(worst, rel)
        status = "ok" if bad == 0 else "FAIL (%d cells)" % bad
        print("%-9s %-8s %-22s %6d cells in [%.4g, %.4g], largest relative difference %.3g %s" %
              (label, kind, name, n, min(theirs), max(theirs), worst, status))
        ok = ok and bad == 0
    return ok


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    helper, out = sys.argv[1], sys.argv[2]
    if not os.path.exists(GMSH):
        print("gmsh is missing: skipped")
        return 77
    os.makedirs(out, exist_ok=True)
    box = gmsh(BOX_GEO, os.path.join(out, "box"), 3)
    quads = gmsh(WARPED_GEO, os.path.join(out, "warped_quads"), 2, ("-setnumber", "Mesh.RecombineAll", "1"))
    tris = gmsh(WARPED_GEO, os.path.join(out, "warped_tris"), 2)
    ok = compare(helper, "tet", box, TET, "box")
    ok = compare(helper, "triangle", box, TRIANGLE, "box") and ok
    ok = compare(helper, "triangle", tris, TRIANGLE, "warped") and ok
    ok = compare(helper, "quad", quads, QUAD, "warped") and ok
    print("passed" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
