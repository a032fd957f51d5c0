#include "hqview/overlap/cell_faces.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>

namespace hq::detail {

CellFaceMap build_cell_face_map(const VolumeCells& cells) {
  struct Entry {
    std::array<Index, 4> key;  // sorted ids; a triangle's start with kNoIndex
    FaceUse use;
  };
  // Faces per cell, by kind: a prefix sum gives each cell its first entry.
  std::vector<std::size_t> first(static_cast<std::size_t>(cells.size()) + 1, 0);
  for (Index c = 0; c < cells.size(); ++c)
    first[static_cast<std::size_t>(c) + 1] =
        first[static_cast<std::size_t>(c)] + static_cast<std::size_t>(kind_faces(cells.kind_of(c)).n);
  std::vector<Entry> entries(first.back());
  tbb::parallel_for(tbb::blocked_range<Index>(0, cells.size(), 4096), [&](const tbb::blocked_range<Index>& r) {
    for (Index c = r.begin(); c != r.end(); ++c) {
      const CellCornerIds corners = cells.corners(c);
      const int n = kind_faces(corners.kind).n;
      for (int k = 0; k < n; ++k) {
        std::array<Index, 4> key = local_face_corners(corners, k);
        std::sort(key.begin(), key.end());  // kNoIndex (-1) first
        entries[first[static_cast<std::size_t>(c)] + static_cast<std::size_t>(k)] = {key, {c, k}};
      }
    }
  });
  // Keys compared inline, component by component (std::array's operators
  // call memcmp, which cost most of this sort).
  const auto same_key = [](const Entry& a, const Entry& b) {
    return a.key[0] == b.key[0] && a.key[1] == b.key[1] && a.key[2] == b.key[2] && a.key[3] == b.key[3];
  };
  tbb::parallel_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    for (std::size_t i = 0; i < 4; ++i)
      if (a.key[i] != b.key[i]) return a.key[i] < b.key[i];
    return a.use.cell != b.use.cell ? a.use.cell < b.use.cell : a.use.local < b.use.local;
  });
  CellFaceMap map;
  map.uses.reserve(entries.size());
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (i == 0 || !same_key(entries[i], entries[i - 1])) map.offsets.push_back(static_cast<Index>(i));
    map.uses.push_back(entries[i].use);
  }
  map.offsets.push_back(static_cast<Index>(entries.size()));
  return map;
}

}  // namespace hq::detail
