#pragma once
// data/annotated.vtu: the hex mesh with every per-cell and per-vertex field of
// the report, for ParaView (CONTRACT.md "Bundle layout").
//
// Format (Kitware's "VTK File Formats", XML section): <VTKFile
// type="UnstructuredGrid" version="1.0" byte_order="LittleEndian"
// header_type="UInt64">, one Piece, every DataArray format="appended" into one
// <AppendedData encoding="raw">: after its '_', each array is a UInt64 byte
// count followed by the values, little-endian, in the order the arrays are
// declared; a DataArray's `offset` is the position of its byte count after
// the '_'. No timestamps: the same model gives the same bytes. Compressed
// (VtuData::zlib, the default of a bundle): VTK's vtkZLibDataCompressor,
// each array in fixed-size zlib blocks (report_vtu.cpp), read by VTK,
// ParaView, pyvista and meshio as the uncompressed file.
//
// Points: Float64 x 3. Cells: connectivity Int64 (HQView's corner order is
// VTK_HEXAHEDRON's, so no permutation), offsets Int64, types UInt8 (12).
// CellData mirrors data/cells.csv (same names): scaled_jacobian, corner_sj_0
// ... corner_sj_7, min_corner_sj (an addition: min of the 8), one Float64 array
// per computed Verdict metric (Verdict's order; metrics not computed are left
// out), then UInt8 inverted, degenerate and intersecting (left out with
// --no-overlap), then Float64 size_gradation (NaN where the CSV is empty), then
// with the finite-element check Float64 fem_kappa, fem_lambda_max, fem_det_j_min,
// fem_det_j_max and, when the Poisson check was solved, fem_l2_error_share,
// fem_h1_error_share, fem_error_density. PointData mirrors data/vertices.csv: quality (NaN for a
// vertex no hex uses), glyph_radius (0 without a glyph, NaN where quality is
// NaN) and Int32 cluster (-1 none) when the glyph stage ran, Int32
// coincident_group (-1 none) when the overlap stage ran, UInt8 boundary, and
// boundary_error (signed distance, NaN for interior vertices) with a
// reference, then UInt8 singular. Verdict's +-1e30 sentinels are written as they are.

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "hqview/report/data_files.h"
#include "hqview/report/report_model.h"

namespace hq {

// One DataArray of the file, as declared in its XML header.
struct VtuArrayInfo {
  std::string section;           // "PointData", "CellData", "Points" or "Cells"
  std::string name;              // e.g. "scaled_jacobian"
  std::string type;              // "Float64", "Int64", "Int32" or "UInt8"
  int components = 1;            // values per tuple
  std::uint64_t num_values = 0;  // tuples x components
  std::uint64_t offset = 0;      // of its UInt64 byte count, after the AppendedData '_'
};

// The arrays write_annotated_vtu writes for `model`, in file order, with
// their offsets in the uncompressed file (the layout; lets tests and
// callers list the arrays).
std::vector<VtuArrayInfo> annotated_vtu_layout(const ReportModel& model);

// Writes the file to `out` (opened in binary mode), array by array through a
// fixed-size buffer: memory beyond the model's own arrays stays bounded.
// The caller checks the stream for I/O errors. Both functions throw
// hq::Error ("internal: ...") when a per-vertex or per-cell field of the
// model does not have one entry per vertex or cell.
// `out` must be seekable when compressed (the header is written last).
void write_annotated_vtu(const ReportModel& model, std::ostream& out, VtuData encoding = VtuData::raw);

}  // namespace hq
