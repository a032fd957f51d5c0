#include "hqview/overlap/cell_faces.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>

namespace hq::detail {
namespace {

// One use of a face with N corners, keyed by its sorted vertex ids.
template <std::size_t N>
struct Entry {
  std::array<Index, N> key;
  FaceUse use;
};

// Every face with N corners of every cell, sorted by key, then cell, then
// local face: a block's cell c with `per_cell` such faces has its entries at
// first + per_cell * (c - the block's first cell). Keys compared inline,
// component by component (std::array's operators call memcmp).
template <std::size_t N>
std::vector<Entry<N>> sorted_entries(const VolumeCells& cells) {
  std::array<std::size_t, kNumVolumeKinds + 1> first{};
  std::array<int, kNumVolumeKinds> per_cell{};
  for (int k = 0; k < kNumVolumeKinds; ++k) {
    const KindFaces faces = kind_faces(static_cast<CellKind>(k));
    for (int f = 0; f < faces.n; ++f) per_cell[static_cast<std::size_t>(k)] += faces.faces[f].size == static_cast<int>(N);
    const auto count = static_cast<std::size_t>(cells.first[static_cast<std::size_t>(k) + 1] - cells.first[static_cast<std::size_t>(k)]);
    first[static_cast<std::size_t>(k) + 1] = first[static_cast<std::size_t>(k)] + count * static_cast<std::size_t>(per_cell[static_cast<std::size_t>(k)]);
  }
  std::vector<Entry<N>> entries(first[kNumVolumeKinds]);
  tbb::parallel_for(tbb::blocked_range<Index>(0, cells.size(), 4096), [&](const tbb::blocked_range<Index>& r) {
    for (Index c = r.begin(); c != r.end(); ++c) {
      const CellCornerIds corners = cells.corners(c);
      const auto k = static_cast<std::size_t>(corners.kind);
      std::size_t at = first[k] + static_cast<std::size_t>(corners.local) * static_cast<std::size_t>(per_cell[k]);
      const KindFaces faces = kind_faces(corners.kind);
      for (int f = 0; f < faces.n; ++f) {
        if (faces.faces[f].size != static_cast<int>(N)) continue;
        const std::array<Index, 4> all = local_face_corners(corners, f);
        Entry<N>& e = entries[at++];
        std::copy(all.begin(), all.begin() + N, e.key.begin());
        std::sort(e.key.begin(), e.key.end());
        e.use = {c, f};
      }
    }
  });
  tbb::parallel_sort(entries.begin(), entries.end(), [](const Entry<N>& a, const Entry<N>& b) {
    for (std::size_t i = 0; i < N; ++i)
      if (a.key[i] != b.key[i]) return a.key[i] < b.key[i];
    return a.use.cell != b.use.cell ? a.use.cell < b.use.cell : a.use.local < b.use.local;
  });
  return entries;
}

template <std::size_t N>
void append(const std::vector<Entry<N>>& entries, CellFaceMap& map) {
  const auto same_key = [](const Entry<N>& a, const Entry<N>& b) {
    for (std::size_t i = 0; i < N; ++i)
      if (a.key[i] != b.key[i]) return false;
    return true;
  };
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (i == 0 || !same_key(entries[i], entries[i - 1])) map.offsets.push_back(static_cast<Index>(map.uses.size()));
    map.uses.push_back(entries[i].use);
  }
}

}  // namespace

// Triangles and quads apart, each sorted on its own keys (12 and 16 bytes
// instead of 16 for every face): the faces come out in the order of the
// keys of the whole map, triangles first (as if keyed with kNoIndex first).
CellFaceMap build_cell_face_map(const VolumeCells& cells) {
  CellFaceMap map;
  {
    const std::vector<Entry<3>> triangles = sorted_entries<3>(cells);
    map.uses.reserve(triangles.size());
    append(triangles, map);
  }
  const std::vector<Entry<4>> quads = sorted_entries<4>(cells);
  map.uses.reserve(map.uses.size() + quads.size());
  append(quads, map);
  map.offsets.push_back(static_cast<Index>(map.uses.size()));
  return map;
}

}  // namespace hq::detail
