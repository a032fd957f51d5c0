#pragma once
// The per-cell and per-vertex data files a bundle carries (`--data`,
// docs/contract.md "The bundle"). Every value is in each of them: the
// choice is only of form. data/edges.csv (a short table of the singular,
// irregular and non-manifold edges) is in every bundle.

#include <string>
#include <string_view>
#include <vector>

namespace hq {

enum class VtuData { none, raw, zlib };

struct DataFormats {
  bool csv = false;             // data/cells.csv, data/vertices.csv
  bool csv_gz = false;          // data/cells.csv.gz, data/vertices.csv.gz
  VtuData vtu = VtuData::zlib;  // data/annotated.vtu (zlib: vtkZLibDataCompressor)
  // data/non_conforming_faces.csv: set by the pipeline for a mesh with
  // non-hex volume cells (never by --data).
  bool non_conforming_faces = false;
};

// The default: annotated.vtu, compressed; no per-cell text (docs/contract.md).
inline constexpr std::string_view kDefaultDataList = "vtu.zlib";

// `--data LIST`: comma-separated csv, csv.gz, vtu, vtu.zlib, or none alone.
// Throws ValueError naming the bad entry (vtu with vtu.zlib: one file).
DataFormats parse_data_formats(std::string_view list);

struct DataFile {
  std::string path;    // relative to the bundle, e.g. "data/cells.csv.gz"
  std::string format;  // its --data name: csv, csv.gz, vtu, vtu.zlib
  std::string what;    // one line for the pages
};

// The bundle's data files in a fixed order (the VTU, cells, vertices, edges,
// non-conforming faces).
std::vector<DataFile> data_files(const DataFormats& formats);

// The file the pages point to for every per-cell (per-vertex) value: the
// plain CSV, else the gzip'ed one, else annotated.vtu; "" for --data none.
std::string cell_data_path(const DataFormats& formats);
std::string vertex_data_path(const DataFormats& formats);

}  // namespace hq
