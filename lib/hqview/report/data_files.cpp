#include "hqview/report/data_files.h"

#include "hqview/core/error.h"

namespace hq {

DataFormats parse_data_formats(std::string_view list) {
  DataFormats f;
  f.vtu = VtuData::none;
  bool none = false, any = false;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string_view name = list.substr(start, comma - start);
    start = comma + 1;
    const auto vtu = [&](VtuData v) {
      if (f.vtu != VtuData::none && f.vtu != v)
        throw ValueError("--data: vtu and vtu.zlib are the same file (data/annotated.vtu); choose one");
      f.vtu = v;
    };
    if (name == "csv")
      f.csv = true;
    else if (name == "csv.gz")
      f.csv_gz = true;
    else if (name == "vtu")
      vtu(VtuData::raw);
    else if (name == "vtu.zlib")
      vtu(VtuData::zlib);
    else if (name == "none")
      none = true;
    else
      throw ValueError("--data: '" + std::string(name) + "' is not one of csv, csv.gz, vtu, vtu.zlib, none");
    any = any || name != "none";
  }
  if (none && any) throw ValueError("--data: none cannot be combined with other formats");
  return f;
}

std::vector<DataFile> data_files(const DataFormats& f) {
  std::vector<DataFile> files;
  if (f.vtu != VtuData::none)
    files.push_back({"data/annotated.vtu", f.vtu == VtuData::zlib ? "vtu.zlib" : "vtu",
                     std::string("the mesh with every per-cell and per-vertex value, for ParaView, pyvista, meshio") +
                         (f.vtu == VtuData::zlib ? " (zlib-compressed)" : "")});
  if (f.csv) files.push_back({"data/cells.csv", "csv", "one row per hex"});
  if (f.csv_gz) files.push_back({"data/cells.csv.gz", "csv.gz", "one row per hex, gzip'ed"});
  if (f.csv) files.push_back({"data/vertices.csv", "csv", "one row per vertex"});
  if (f.csv_gz) files.push_back({"data/vertices.csv.gz", "csv.gz", "one row per vertex, gzip'ed"});
  files.push_back({"data/edges.csv", "csv", "one row per singular, irregular or non-manifold edge"});
  if (f.non_conforming_faces)
    files.push_back({"data/non_conforming_faces.csv", "csv",
                     "one row per non-conforming face (a quad against two triangles) with its cells"});
  return files;
}

namespace {
std::string table_path(const DataFormats& f, const char* table) {
  if (f.csv) return std::string("data/") + table + ".csv";
  if (f.csv_gz) return std::string("data/") + table + ".csv.gz";
  if (f.vtu != VtuData::none) return "data/annotated.vtu";
  return "";
}
}  // namespace

std::string cell_data_path(const DataFormats& f) { return table_path(f, "cells"); }
std::string vertex_data_path(const DataFormats& f) { return table_path(f, "vertices"); }

}  // namespace hq
