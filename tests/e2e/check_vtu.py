#!/usr/bin/python3
"""data/annotated.vtu read by VTK's own reader (Debian's python3-vtk9).

Runs the built hqview on examples/twisted_bar.mesh (all stages; then with
--metrics/--no-overlap), on examples/ball.mesh with --reference and, when
../shared/data is there, on hand7_1.mesh with --reference, rockarm.vtk and
bunny_in.mesh (one inverted hex), and checks each bundle's annotated.vtu with
vtkXMLUnstructuredGridReader:
  - no reader error or warning; point and cell counts are report.json's;
  - every cell type is 12 (VTK_HEXAHEDRON);
  - the CellData arrays are the cells.csv columns (less `cell`) plus
    min_corner_sj, the PointData arrays the vertices.csv columns (less
    vertex, x, y, z), each with one tuple per cell / point;
  - sampled rows (the worst cells and vertices of report.json and evenly
    spaced ids) equal the CSV rows to 1e-12 (an empty CSV field is NaN), and
    the points equal the CSV's x, y, z;
  - the oracle: vtkMeshQuality's hex scaled Jacobian, computed by VTK from
    the file's points and connectivity, equals the scaled_jacobian array to
    1e-9 for every cell (a wrong corner order would change it);
  - -j1 and -j2 give byte-identical files;
  - compression loses nothing: the default (zlib-compressed,
    vtkZLibDataCompressor) file and the uncompressed one of --data vtu give
    equal arrays (bit for bit, NaN where NaN), points and connectivity;
  - the gzip'ed CSVs of --data csv.gz decompress (Python's gzip, all members)
    to exactly the bytes of the plain CSVs, for -j1 and -j2.

Usage: check_vtu.py HQVIEW OUTPUT_DIR SOURCE_DIR
Exit 0: passed; 1: failed; 77: VTK's Python module is missing (skipped).
"""

import csv
import gzip
import json
import math
import os
import shutil
import subprocess
import sys

try:
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonCore import vtkCommand
    from vtkmodules.vtkFiltersVerdict import vtkMeshQuality
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
except ImportError as e:  # python3-vtk9 (or numpy) not installed: skip
    print(f"SKIP: VTK's Python module cannot be imported ({e}); scripts/setup installs python3-vtk9")
    sys.exit(77)

VTK_HEXAHEDRON = 12
SAMPLE_ROWS = 20
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)
    return condition


def run_hqview(hqview, args, data="csv,vtu.zlib"):
    result = subprocess.run([hqview, "analyze", *args, "--no-render", "--quiet", "--data", data],
                            capture_output=True, text=True)
    if result.returncode not in (0, 1):
        raise SystemExit(f"hqview {' '.join(args)} exited {result.returncode}: {result.stderr}")


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def close(expected, actual, tolerance):
    if math.isnan(expected) or math.isnan(actual):
        return math.isnan(expected) and math.isnan(actual)
    return abs(expected - actual) <= tolerance * max(1.0, abs(expected))


def sample_ids(count, worst):
    """Up to SAMPLE_ROWS ids: the worst ones first, then evenly spaced, then the last."""
    ids = list(dict.fromkeys(worst))[: SAMPLE_ROWS // 2]
    step = max(1, count // (SAMPLE_ROWS - len(ids)))
    ids += range(0, count, step)
    ids.append(count - 1)
    return sorted(set(i for i in ids if 0 <= i < count))


def read_grid(path):
    reader = vtkXMLUnstructuredGridReader()
    problems = []
    for event in (vtkCommand.ErrorEvent, vtkCommand.WarningEvent):
        reader.AddObserver(event, lambda obj, ev: problems.append(ev))
    reader.SetFileName(path)
    reader.Update()
    check(not problems, f"{path}: VTK reader reported {problems}")
    check(reader.GetErrorCode() == 0, f"{path}: VTK reader error code {reader.GetErrorCode()}")
    return reader.GetOutput()


def compare_rows(label, header, rows, skip, data, ids):
    """Each sampled row's columns (less `skip`) against the arrays in `data`."""
    for column, name in enumerate(header):
        if name in skip:
            continue
        array = data.GetArray(name)
        if not check(array is not None, f"{label}: no array {name}"):
            continue
        values = vtk_to_numpy(array)
        for i in ids:
            text = rows[i][column]
            expected = float(text) if text != "" else math.nan
            check(close(expected, float(values[i]), 1e-12), f"{label}: {name}[{i}] is {values[i]}, CSV has {text!r}")


def check_bundle(bundle):
    label = os.path.basename(bundle)
    path = os.path.join(bundle, "data", "annotated.vtu")
    if not check(os.path.isfile(path), f"{label}: no data/annotated.vtu"):
        return
    with open(os.path.join(bundle, "report.json")) as f:
        report = json.load(f)
    # Every point of the file: the vertices cells use and the nodes no cell uses.
    num_points = report["mesh"]["num_vertices"] + report["mesh"]["num_unreferenced_vertices"]
    num_cells = report["mesh"]["num_hexes"]
    grid = read_grid(path)
    check(grid.GetNumberOfPoints() == num_points, f"{label}: {grid.GetNumberOfPoints()} points, report has {num_points}")
    check(grid.GetNumberOfCells() == num_cells, f"{label}: {grid.GetNumberOfCells()} cells, report has {num_cells}")
    types = vtk_to_numpy(grid.GetCellTypesArray())
    check(len(types) == num_cells and (types == VTK_HEXAHEDRON).all(), f"{label}: cell types other than 12")

    cell_header, cell_rows = read_csv(os.path.join(bundle, "data", "cells.csv"))
    vertex_header, vertex_rows = read_csv(os.path.join(bundle, "data", "vertices.csv"))
    check(len(cell_rows) == num_cells and len(vertex_rows) == num_points, f"{label}: CSV row counts")
    cell_data, point_data = grid.GetCellData(), grid.GetPointData()
    cell_names = {cell_data.GetArrayName(i) for i in range(cell_data.GetNumberOfArrays())}
    point_names = {point_data.GetArrayName(i) for i in range(point_data.GetNumberOfArrays())}
    expected_cells = (set(cell_header) - {"cell", "cell_type"}) | {"min_corner_sj"}
    # A column left empty in every row (metric not computed, stage skipped) has no array.
    empty_cell_columns = {n for c, n in enumerate(cell_header) if all(r[c] == "" for r in cell_rows)}
    empty_point_columns = {n for c, n in enumerate(vertex_header) if all(r[c] == "" for r in vertex_rows)}
    check(cell_names == expected_cells - empty_cell_columns,
          f"{label}: CellData {sorted(cell_names)} != {sorted(expected_cells - empty_cell_columns)}")
    expected_points = set(vertex_header) - {"vertex", "x", "y", "z"} - empty_point_columns
    check(point_names == expected_points, f"{label}: PointData {sorted(point_names)} != {sorted(expected_points)}")
    for data, count, names in ((cell_data, num_cells, cell_names), (point_data, num_points, point_names)):
        for name in names:
            array = data.GetArray(name)
            check(array.GetNumberOfTuples() == count and array.GetNumberOfComponents() == 1,
                  f"{label}: {name} has {array.GetNumberOfTuples()}x{array.GetNumberOfComponents()} values")
    check(cell_data.GetScalars() is not None and cell_data.GetScalars().GetName() == "scaled_jacobian",
          f"{label}: active cell scalars are not scaled_jacobian")

    worst_cells = [w["cell"] for w in report["quality"]["worst_cells"]]
    worst_vertices = [w["vertex"] for w in report["quality"]["worst_vertices"]]
    cell_ids = sample_ids(num_cells, worst_cells)
    vertex_ids = sample_ids(num_points, worst_vertices)
    compare_rows(label, cell_header, cell_rows, {"cell", "cell_type"} | empty_cell_columns, cell_data, cell_ids)
    # cells.csv's cell_type is the VTU's cell type (hex 12, tet 10, wedge 13, pyramid 14), not an array.
    type_column = cell_header.index("cell_type")
    vtk_type = {"hex": 12, "tet": 10, "wedge": 13, "pyramid": 14}
    check(all(vtk_type.get(cell_rows[i][type_column]) == types[i] for i in range(min(len(types), len(cell_rows)))),
          f"{label}: cells.csv cell_type differs from the VTU's cell types")
    compare_rows(label, vertex_header, vertex_rows, {"vertex", "x", "y", "z"} | empty_point_columns, point_data,
                 vertex_ids)
    corners = [vtk_to_numpy(cell_data.GetArray(f"corner_sj_{k}")) for k in range(8)]
    min_corner = vtk_to_numpy(cell_data.GetArray("min_corner_sj"))
    for i in cell_ids:
        check(min_corner[i] == min(c[i] for c in corners), f"{label}: min_corner_sj[{i}]")
    for i in vertex_ids:
        point = grid.GetPoint(i)
        for k, axis in enumerate("xyz"):
            text = vertex_rows[i][vertex_header.index(axis)]
            check(close(float(text), point[k], 1e-12), f"{label}: point {i} {axis} is {point[k]}, CSV has {text}")

    # The flag arrays add up to report.json's counts.
    counts = [("inverted", report["quality"]["num_inverted"]), ("degenerate", report["quality"]["num_degenerate"])]
    if report["overlap"] is not None:
        counts.append(("intersecting", report["overlap"]["num_intersecting_cells"]))
    for name, expected in counts:
        total = int(vtk_to_numpy(cell_data.GetArray(name)).astype(int).sum())
        check(total == expected, f"{label}: {name} sums to {total}, report.json has {expected}")

    # The oracle: VTK's own hex scaled Jacobian from the file's connectivity.
    quality = vtkMeshQuality()
    quality.SetInputData(grid)
    quality.SetHexQualityMeasureToScaledJacobian()
    quality.Update()
    vtk_sj = vtk_to_numpy(quality.GetOutput().GetCellData().GetArray("Quality"))
    ours = vtk_to_numpy(cell_data.GetArray("scaled_jacobian"))
    bad = [i for i in range(num_cells) if not close(float(ours[i]), float(vtk_sj[i]), 1e-9)]
    check(not bad, f"{label}: vtkMeshQuality scaled Jacobian differs on {len(bad)} cells, e.g. "
          + ", ".join(f"{i}: {ours[i]} vs {vtk_sj[i]}" for i in bad[:5]))
    print(f"{label}: {num_points} points, {num_cells} hexes, {len(cell_names)} cell and {len(point_names)} "
          f"point arrays, {len(cell_ids)} + {len(vertex_ids)} rows sampled, scaled Jacobian = VTK's on every cell")


def arrays_of(grid):
    """Every array of the grid as numpy, keyed by (section, name), with the points and cells."""
    out = {("Points", "Points"): vtk_to_numpy(grid.GetPoints().GetData()),
           ("Cells", "connectivity"): vtk_to_numpy(grid.GetCells().GetConnectivityArray()),
           ("Cells", "offsets"): vtk_to_numpy(grid.GetCells().GetOffsetsArray()),
           ("Cells", "types"): vtk_to_numpy(grid.GetCellTypesArray())}
    for section, data in (("CellData", grid.GetCellData()), ("PointData", grid.GetPointData())):
        for i in range(data.GetNumberOfArrays()):
            out[(section, data.GetArrayName(i))] = vtk_to_numpy(data.GetArray(i))
    return out


def check_compression_lossless(hqview, out, label, args):
    """The compressed annotated.vtu equals the uncompressed one array by array."""
    raw_dir, zlib_dir = os.path.join(out, label + "_vtu"), os.path.join(out, label + "_vtu_zlib")
    run_hqview(hqview, [*args, "-o", raw_dir], data="vtu")
    run_hqview(hqview, [*args, "-o", zlib_dir], data="vtu.zlib")
    raw_path, zlib_path = (os.path.join(d, "data", "annotated.vtu") for d in (raw_dir, zlib_dir))
    with open(zlib_path, "rb") as f:
        check(b'compressor="vtkZLibDataCompressor"' in f.read(4096), f"{label}: default VTU is not zlib-compressed")
    raw, packed = arrays_of(read_grid(raw_path)), arrays_of(read_grid(zlib_path))
    check(raw.keys() == packed.keys(), f"{label}: arrays differ: {sorted(raw.keys() ^ packed.keys())}")
    for key in raw.keys() & packed.keys():
        a, b = raw[key], packed[key]
        same = a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()
        check(same, f"{label}: {key} differs between the compressed and the uncompressed annotated.vtu")
    print(f"{label}: {len(raw)} arrays equal in the compressed ({os.path.getsize(zlib_path)} bytes) and the "
          f"uncompressed ({os.path.getsize(raw_path)} bytes) annotated.vtu")


def check_gzip_csv(hqview, out, label, args):
    """--data csv.gz decompresses to the bytes of --data csv, for -j1 and -j2."""
    plain = os.path.join(out, label + "_csv")
    run_hqview(hqview, [*args, "-o", plain], data="csv")
    for j in ("1", "2"):
        packed = os.path.join(out, f"{label}_csv_gz_j{j}")
        run_hqview(hqview, [*args, "-o", packed, "-j", j], data="csv.gz")
        for table in ("cells", "vertices"):
            with open(os.path.join(plain, "data", table + ".csv"), "rb") as f:
                expected = f.read()
            with gzip.open(os.path.join(packed, "data", table + ".csv.gz"), "rb") as f:
                actual = f.read()
            check(actual == expected, f"{label}: {table}.csv.gz (-j{j}) does not decompress to {table}.csv")
    print(f"{label}: cells.csv.gz and vertices.csv.gz decompress to the plain CSVs for -j1 and -j2")


def shared_data_dir(source_dir):
    candidate = os.environ.get("HQVIEW_DATA") or os.path.join(source_dir, "..", "shared", "data")
    return candidate if os.path.isdir(candidate) else None


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    hqview, out, source = sys.argv[1:]
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    examples = os.path.join(source, "examples")

    bar = os.path.join(examples, "twisted_bar.mesh")
    run_hqview(hqview, [bar, "-o", os.path.join(out, "twisted_bar_j1"), "-j", "1"])
    run_hqview(hqview, [bar, "-o", os.path.join(out, "twisted_bar_j2"), "-j", "2"])
    check_bundle(os.path.join(out, "twisted_bar_j1"))
    with open(os.path.join(out, "twisted_bar_j1", "data", "annotated.vtu"), "rb") as a, \
            open(os.path.join(out, "twisted_bar_j2", "data", "annotated.vtu"), "rb") as b:
        check(a.read() == b.read(), "twisted_bar: annotated.vtu differs between -j1 and -j2")
    run_hqview(hqview, [bar, "-o", os.path.join(out, "twisted_bar_subset"), "--metrics", "skew,taper", "--no-overlap"])
    check_bundle(os.path.join(out, "twisted_bar_subset"))
    run_hqview(hqview, [os.path.join(examples, "ball.mesh"), "--reference", os.path.join(examples, "ball.off"), "-o",
                        os.path.join(out, "ball_reference")])
    check_bundle(os.path.join(out, "ball_reference"))
    ball_reference = [os.path.join(examples, "ball.mesh"), "--reference", os.path.join(examples, "ball.off")]
    check_compression_lossless(hqview, out, "ball_reference", ball_reference)
    check_gzip_csv(hqview, out, "twisted_bar", [bar])

    data = shared_data_dir(source)
    if data is None:
        print("shared data not found: real-mesh case skipped")
    else:
        meshes = os.path.join(data, "meshes", "gao2016_sweeping")
        run_hqview(hqview, [os.path.join(meshes, "hand7_1.mesh"), "--reference", os.path.join(meshes, "hand.off"),
                            "-o", os.path.join(out, "hand7_1_reference")])
        check_bundle(os.path.join(out, "hand7_1_reference"))
        run_hqview(hqview, [os.path.join(data, "meshes", "dualsheet2019", "rockarm.vtk"), "-o",
                            os.path.join(out, "rockarm")])
        check_bundle(os.path.join(out, "rockarm"))
        # 37,734 hexes, one barely inverted (-0.0028): VTK must agree on its sign too.
        run_hqview(hqview, [os.path.join(data, "meshes", "livesu2015_edgecone", "bunny_in.mesh"), "-o",
                            os.path.join(out, "bunny_in")])
        check_bundle(os.path.join(out, "bunny_in"))
        # 37,734 hexes: ten gzip members per table, 2 MB of arrays in 17 zlib blocks.
        bunny = [os.path.join(data, "meshes", "livesu2015_edgecone", "bunny_in.mesh")]
        check_compression_lossless(hqview, out, "bunny_in", bunny)
        check_gzip_csv(hqview, out, "bunny_in", bunny)

    print(f"{'FAILED' if failures else 'passed'}: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
