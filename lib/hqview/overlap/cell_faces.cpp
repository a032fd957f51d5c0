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
  Index half_face;  // half_face_id: ascends with (cell, local face)
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
        e.half_face = half_face_id(cells.first, corners.kind, corners.local, f);
      }
    }
  });
  tbb::parallel_sort(entries.begin(), entries.end(), [](const Entry<N>& a, const Entry<N>& b) {
    for (std::size_t i = 0; i < N; ++i)
      if (a.key[i] != b.key[i]) return a.key[i] < b.key[i];
    return a.half_face < b.half_face;
  });
  return entries;
}

template <std::size_t N>
void append(const std::vector<Entry<N>>& entries, std::vector<Index>& offsets, std::vector<Index>& uses) {
  const auto same_key = [](const Entry<N>& a, const Entry<N>& b) {
    for (std::size_t i = 0; i < N; ++i)
      if (a.key[i] != b.key[i]) return false;
    return true;
  };
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (i == 0 || !same_key(entries[i], entries[i - 1])) offsets.push_back(static_cast<Index>(uses.size()));
    uses.push_back(entries[i].half_face);
  }
}

}  // namespace

// Triangles and quads apart, each sorted on its own keys (12 and 16 bytes
// instead of 16 for every face): the faces come out in the order of the
// keys of the whole map, triangles first (as if keyed with kNoIndex first).
void match_cell_faces(const VolumeCells& cells, std::vector<Index>& offsets, std::vector<Index>& uses) {
  offsets.clear();
  uses.clear();
  {
    const std::vector<Entry<3>> triangles = sorted_entries<3>(cells);
    uses.reserve(triangles.size());
    append(triangles, offsets, uses);
  }
  const std::vector<Entry<4>> quads = sorted_entries<4>(cells);
  uses.reserve(uses.size() + quads.size());
  append(quads, offsets, uses);
  offsets.push_back(static_cast<Index>(uses.size()));
}

CellFaceMap::CellFaceMap(const VolumeCells& cells, const Topology& topo) : first_(cells.first) {
  if (topo.across_kinds && !topo.cell_face_offsets.empty()) {
    offsets_ = &topo.cell_face_offsets;
    uses_ = &topo.cell_face_uses;
    return;
  }
  match_cell_faces(cells, own_offsets_, own_uses_);
  offsets_ = &own_offsets_;
  uses_ = &own_uses_;
}

}  // namespace hq::detail
