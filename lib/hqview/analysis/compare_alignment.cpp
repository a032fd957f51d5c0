#include "hqview/analysis/compare_alignment.h"

#include <cmath>
#include <vector>


namespace hq {
namespace {

Box3 used_box(const HexMesh& mesh) {
  std::vector<std::uint8_t> used(mesh.points.size(), 0);
  for (const Hex& h : mesh.hexes)
    for (Index v : h) used[static_cast<std::size_t>(v)] = 1;
  Box3 box;
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if (used[i]) box.add(mesh.points[i]);
  return box;
}

}  // namespace

CompareAlignment align_compare_mesh(const HexMesh& mesh, const HexMesh& other, CompareAlign requested) {
  return align_boxes(used_box(mesh), used_box(other), requested);
}

CompareAlignment align_boxes(const Box3& mine, const Box3& theirs, CompareAlign requested) {
  CompareAlignment a;
  a.requested = requested;
  if (mine.is_empty() || theirs.is_empty()) return a;
  const double dm = mine.diagonal(), dt = theirs.diagonal();
  if (!(dm > 0.0) || !(dt > 0.0) || !std::isfinite(dm) || !std::isfinite(dt)) return a;
  a.diagonal_ratio = dt / dm;
  a.boxes_overlap = mine.overlaps(theirs);
  const bool differ = a.diagonal_ratio > kAutoAlignDiagonalRatio || a.diagonal_ratio < 1.0 / kAutoAlignDiagonalRatio;
  a.aligned = requested == CompareAlign::bbox || (requested == CompareAlign::auto_ && (differ || !a.boxes_overlap));
  if (!a.aligned) return a;
  a.scale = dm / dt;
  const Vec3 cm = 0.5 * (mine.lo + mine.hi), ct = 0.5 * (theirs.lo + theirs.hi);
  a.translation = cm - a.scale * ct;
  return a;
}

Vec3 aligned_point(const Vec3& p, const CompareAlignment& alignment) {
  return alignment.aligned ? alignment.scale * p + alignment.translation : p;
}

HexMesh aligned_copy(const HexMesh& other, const CompareAlignment& alignment) {
  HexMesh copy = other;
  for (Vec3& p : copy.points) p = aligned_point(p, alignment);
  return copy;
}

const char* compare_align_name(CompareAlign mode) {
  switch (mode) {
    case CompareAlign::none:
      return "none";
    case CompareAlign::bbox:
      return "bbox";
    case CompareAlign::auto_:
      return "auto";
  }
  return "auto";
}

}  // namespace hq
