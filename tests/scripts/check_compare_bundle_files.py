#!/usr/bin/env python3
"""scripts/compare_bundle_files.py on hand-made output trees: it passes when
only the listed additions differ, and fails, naming the path, on a changed
number, a removed key, a listed addition that is absent, a changed CSV cell, a
changed VTU value, a file on one side only and a changelog quote that is not
in the changelog.

  check_compare_bundle_files.py SOURCE_DIR WORK_DIR
"""
import contextlib
import io
import json
import os
import shutil
import struct
import sys
import zlib

SOURCE, WORK = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SOURCE, "scripts"))
import compare_bundle_files  # noqa: E402  (run in this process: one start-up for every case)
CHANGELOG = "- Unreleased (issue 46): new keys `headline.num_cells` and the column `cell_type`.\n" \
            "- Unreleased (issue 44): cluster colours change; the array `source_index`\n  is new.\n"
failures = []


def vtu(arrays, compressed):
    """A VTU of (section, name, type code, values) arrays, appended raw data,
    UInt64 headers, zlib blocks of 8 bytes when compressed (several blocks)."""
    types = {"d": "Float64", "q": "Int64", "B": "UInt8"}
    payload = b""
    lines = []
    for section, name, code, values in arrays:
        raw = struct.pack("<%d%s" % (len(values), code), *values)
        offset = len(payload)
        if compressed:
            blocks = [raw[i:i + 8] for i in range(0, len(raw), 8)] or [b""]
            packed = [zlib.compress(b) for b in blocks]
            last = len(blocks[-1]) if len(blocks[-1]) != 8 else 0
            payload += struct.pack("<%dQ" % (3 + len(packed)), len(packed), 8, last, *map(len, packed))
            payload += b"".join(packed)
        else:
            payload += struct.pack("<Q", len(raw)) + raw
        lines.append((section, '<DataArray type="%s" Name="%s" format="appended" offset="%d"/>'
                      % (types[code], name, offset)))
    head = '<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" ' \
           'header_type="UInt64"%s>\n<UnstructuredGrid>\n<Piece NumberOfPoints="2" NumberOfCells="1">\n' \
           % (' compressor="vtkZLibDataCompressor"' if compressed else "")
    for section in ("PointData", "CellData", "Points", "Cells"):
        head += "<%s>\n" % section + "".join(l + "\n" for s, l in lines if s == section) + "</%s>\n" % section
    head += '</Piece>\n</UnstructuredGrid>\n<AppendedData encoding="raw">\n_'
    return head.encode() + payload + b"\n</AppendedData>\n</VTKFile>\n"


BASE_REPORT = {"headline": {"num_vertices": 8, "num_hexes": 1, "min_scaled_jacobian": 0.5},
               "quality": {"worst_cells": [{"cell": 0, "scaled_jacobian": 0.5}], "p05": 1e-17},
               "glyphs": {"clusters": [{"id": 0, "color": "#ff3c5a"}, {"id": 1, "color": "#0078e1"}]},
               "compare": {"differences": {"quality.min": 0.25}}, "boundary_error": None}
NEW_REPORT = {"headline": {"num_vertices": 8, "num_hexes": 1, "min_scaled_jacobian": 0.5, "num_cells": 1},
              "quality": {"worst_cells": [{"cell": 0, "scaled_jacobian": 0.5, "kind": "hex"}], "p05": 1.0e-17},
              "glyphs": {"clusters": [{"id": 0, "color": "#ee0055"}, {"id": 1, "color": "#0088aa"}]},
              "compare": {"differences": {"quality.min": 0.25, "headline.num_cells": 0}}, "boundary_error": None}
BASE_CELLS = "cell,scaled_jacobian,size_gradation\n0,0.5,1\n1,1,1.5\n"
NEW_CELLS = "cell,scaled_jacobian,size_gradation,cell_type\n0,0.50,1,hex\n1,1.0,1.5,hex\n"
BASE_VTU = [("CellData", "scaled_jacobian", "d", [0.5, 1.0, 0.25]), ("Cells", "types", "B", [12])]
NEW_VTU = BASE_VTU + [("CellData", "source_index", "q", [1])]

def entry(files, kind, target, change, issue, quote):
    return {"files": files, kind: target, "change": change, "issue": issue, "changelog": quote}


ADDED_46 = "new keys `headline.num_cells`"
ADDITIONS = {"base": "test", "entries": [
    entry("report.json", "json", "headline.num_cells", "added", "46", ADDED_46),
    entry("report.json", "json", "quality.worst_cells[*].kind", "added", "46", ADDED_46),
    entry("report.json", "json", 'compare.differences["headline.*"]', "added", "46", ADDED_46),
    # boundary_error is null (the stage did not run): its addition is not missing.
    entry("report.json", "json", "boundary_error.planar", "added", "46", ADDED_46),
    entry("report.json", "json", "glyphs.clusters[*].color", "changed", "44", "cluster colours change"),
    entry("data/cells.csv", "column", "cell_type", "added", "46", "the column `cell_type`"),
    entry("data/annotated.vtu", "array", "source_index", "added", "44", "the array `source_index` is new")]}


def make_tree(root, report, cells, arrays, compressed):
    bundle = os.path.join(root, "plain-j1", "m.mesh")
    os.makedirs(os.path.join(bundle, "data"))
    os.makedirs(os.path.join(bundle, "views"))
    with open(os.path.join(bundle, "report.json"), "w") as f:
        f.write(report if isinstance(report, str) else json.dumps(report, indent=2))
    with open(os.path.join(bundle, "data", "cells.csv"), "w") as f:
        f.write(cells)
    with open(os.path.join(bundle, "data", "annotated.vtu"), "wb") as f:
        f.write(vtu(arrays, compressed))
    # Pictures and timings differ on every side: skipped, never compared.
    with open(os.path.join(bundle, "views", "main_1.png"), "wb") as f:
        f.write(os.urandom(16))
    with open(os.path.join(bundle, "timings.json"), "w") as f:
        f.write(json.dumps({"total_seconds": len(root)}))


def run(name, new_report=None, new_cells=NEW_CELLS, new_vtu=NEW_VTU, additions=None, changelog=CHANGELOG,
        expect=0, expect_text=(), extra_file=None):
    case = os.path.join(WORK, name)
    shutil.rmtree(case, ignore_errors=True)
    make_tree(os.path.join(case, "base"), BASE_REPORT, BASE_CELLS, BASE_VTU, compressed=False)
    if new_report is None:  # the same values written otherwise
        new_report = json.dumps(NEW_REPORT, indent=1).replace("1e-17", "1.0e-17")
    make_tree(os.path.join(case, "new"), new_report, new_cells, new_vtu, compressed=True)
    if extra_file:
        with open(os.path.join(case, "new", "plain-j1", "m.mesh", extra_file), "w") as f:
            f.write("{}")
    with open(os.path.join(case, "additions.json"), "w") as f:
        json.dump(additions if additions is not None else ADDITIONS, f)
    with open(os.path.join(case, "CHANGELOG.md"), "w") as f:
        f.write(changelog)
    output = io.StringIO()
    with contextlib.redirect_stdout(output), contextlib.redirect_stderr(output):
        code = compare_bundle_files.main(["--additions", os.path.join(case, "additions.json"),
                                          "--changelog", os.path.join(case, "CHANGELOG.md"),
                                          os.path.join(case, "base"), os.path.join(case, "new")])
    text = output.getvalue()
    if code != expect or not all(t in text for t in expect_text):
        failures.append("%s: exit %d (expected %d), expected %r in:\n%s" % (name, code, expect, expect_text, text))
    return text


def changed(path, value):
    report = json.loads(json.dumps(NEW_REPORT))
    node = report
    for key in path[:-1]:
        node = node[key]
    if value is None:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return report


# Only the listed additions differ (numbers written differently, 0.50 and
# 1.0e-17, are the same values; the VTU compressed on one side only):
# passes, and counts the picture and timings.json as skipped.
out = run("only_listed", expect=0, expect_text=["no difference outside the listed additions (3 files compared)",
                                                "skipped: 1 files: pictures", "skipped: 1 files: wall times"])
# A changed number: named by its path and both values.
run("changed_number", new_report=changed(["headline", "min_scaled_jacobian"], 0.5000000000000001), expect=1,
    expect_text=["headline.min_scaled_jacobian: 0.5 -> 0.5000000000000001"])
# A number within rounding of the base is still a difference (equal, not close).
run("close_number", new_report=changed(["quality", "p05"], 1.0000000000000001e-17 * 1.0000001), expect=1,
    expect_text=["quality.p05: 1e-17 -> "])
# A removed key.
run("removed_key", new_report=changed(["headline", "num_hexes"], None), expect=1,
    expect_text=["headline.num_hexes: removed (was 1)"])
# A listed addition absent from the new output, at its own path.
run("absent_addition", new_report=changed(["headline", "num_cells"], None), expect=1,
    expect_text=["headline.num_cells: listed addition absent from the new output"])
# An addition inside an array element, absent from one element.
report = json.loads(json.dumps(NEW_REPORT))
del report["quality"]["worst_cells"][0]["kind"]
run("absent_in_array", new_report=report, expect=1,
    expect_text=["quality.worst_cells[0].kind: listed addition absent from the new output"])
# An unlisted added key.
run("unlisted_key", new_report=changed(["headline", "hex_fraction"], 1), expect=1,
    expect_text=["headline.hex_fraction: added (1)"])
# A listed change that did not change anywhere is over-broad.
run("over_broad_change", new_report=changed(["glyphs", "clusters"], BASE_REPORT["glyphs"]["clusters"]), expect=1,
    expect_text=["json glyphs.clusters[*].color (changed, issue 44): found in 1 files, equal on both sides"])
# A changed CSV cell (an unlisted column) and a removed column.
run("changed_cell", new_cells=NEW_CELLS.replace("1,1.0,1.5", "1,1.0,1.25"), expect=1,
    expect_text=["row 2 (cell 1), column size_gradation: 1.5 -> 1.25"])
run("removed_column", new_cells="cell,scaled_jacobian,cell_type\n0,0.5,hex\n1,1,hex\n", expect=1,
    expect_text=["header: cell,scaled_jacobian,size_gradation -> cell,scaled_jacobian"])
run("absent_column", new_cells=BASE_CELLS, expect=1,
    expect_text=["column cell_type: listed addition absent from the new output"])
# A changed VTU value, a listed VTU array absent.
run("changed_vtu", new_vtu=[("CellData", "scaled_jacobian", "d", [0.5, 1.0, 0.125])] + NEW_VTU[1:], expect=1,
    expect_text=["CellData/scaled_jacobian[2] (tuple 2): 0.25 -> 0.125"])
run("absent_vtu_array", new_vtu=BASE_VTU, expect=1,
    expect_text=["array source_index: listed addition absent from the new output"])
# A file on one side only (not a picture).
run("extra_file", extra_file="extra.json", expect=1, expect_text=["plain-j1/m.mesh/extra.json: in the new output only"])
# A justification that CHANGELOG.md does not hold.
run("unjustified", changelog="- nothing\n", expect=1, expect_text=["its changelog quote is not in"])

if failures:
    print("\n\n".join(failures))
    sys.exit(1)
print("compare_bundle_files.py: 15 cases as expected")
