#include "hqview/glyph/glyph_ties.h"

#include <cmath>

namespace hq {

std::vector<Index> glyph_tie_classes(std::span<const AggregatedGlyph> clusters, double tolerance) {
  std::vector<Index> classes(clusters.size(), 0);
  Index current = 0;
  double first = 0.0;
  for (std::size_t r = 0; r < clusters.size(); ++r) {
    const double q = clusters[r].min_quality;
    const bool ties = r > 0 && !std::isnan(q) && !std::isnan(first) && (q < 0.0) == (first < 0.0) &&
                      q - first <= tolerance && first - q <= tolerance;
    if (r > 0 && !ties) {
      ++current;
      first = q;
    }
    if (r == 0) first = q;
    classes[r] = current;
  }
  return classes;
}

std::vector<Index> tie_class_sizes(std::span<const Index> classes) {
  std::vector<Index> sizes;
  for (Index c : classes) {
    if (static_cast<std::size_t>(c) >= sizes.size()) sizes.resize(static_cast<std::size_t>(c) + 1, 0);
    ++sizes[static_cast<std::size_t>(c)];
  }
  return sizes;
}

Index coloured_tie_classes(std::span<const Index> class_sizes, Index max_classes, Index max_glyphs) {
  Index classes = 0, glyphs = 0;
  for (Index size : class_sizes) {
    if (classes >= max_classes || (classes > 0 && glyphs + size > max_glyphs)) break;
    glyphs += size;
    ++classes;
  }
  return classes;
}

std::vector<Index> glyph_colour_slots(std::span<const AggregatedGlyph> clusters, Index max_classes) {
  std::vector<Index> slots = glyph_tie_classes(clusters);
  const Index coloured = coloured_tie_classes(tie_class_sizes(slots), max_classes);
  for (Index& s : slots)
    if (s >= coloured) s = -1;
  return slots;
}

}  // namespace hq
