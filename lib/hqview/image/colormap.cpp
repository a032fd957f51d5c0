#include "hqview/image/colormap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace hq {
namespace {

struct Rgb {
  float r, g, b;
};

// See colormap.h for how this table was made. Index 0 is t = 0 (worst).
constexpr std::array<Rgb, 33> kQualityTable = {{
    {0.7736f, 0.0802f, 0.1015f}, {0.7926f, 0.1526f, 0.1058f}, {0.8115f, 0.2055f, 0.1102f}, {0.8302f, 0.2508f, 0.1146f},
    {0.8487f, 0.2919f, 0.1191f}, {0.8670f, 0.3306f, 0.1235f}, {0.8790f, 0.3668f, 0.1314f}, {0.8854f, 0.4009f, 0.1425f},
    {0.8914f, 0.4337f, 0.1538f}, {0.8971f, 0.4655f, 0.1653f}, {0.9024f, 0.4966f, 0.1770f}, {0.9073f, 0.5271f, 0.1888f},
    {0.9118f, 0.5570f, 0.2008f}, {0.9147f, 0.5821f, 0.2285f}, {0.9161f, 0.6032f, 0.2674f}, {0.9168f, 0.6242f, 0.3049f},
    {0.9168f, 0.6451f, 0.3415f}, {0.9162f, 0.6660f, 0.3775f}, {0.9149f, 0.6869f, 0.4132f}, {0.9128f, 0.7077f, 0.4487f},
    {0.9099f, 0.7285f, 0.4842f}, {0.9062f, 0.7492f, 0.5196f}, {0.9050f, 0.7650f, 0.5570f}, {0.9044f, 0.7787f, 0.5953f},
    {0.9031f, 0.7925f, 0.6336f}, {0.9010f, 0.8063f, 0.6719f}, {0.8980f, 0.8202f, 0.7102f}, {0.8942f, 0.8342f, 0.7487f},
    {0.8895f, 0.8483f, 0.7873f}, {0.8837f, 0.8624f, 0.8260f}, {0.8770f, 0.8766f, 0.8649f}, {0.8691f, 0.8909f, 0.9039f},
    {0.8600f, 0.9052f, 0.9431f},
}};

constexpr Rgb hex(unsigned v) {
  return {static_cast<float>((v >> 16) & 0xff) / 255.0f, static_cast<float>((v >> 8) & 0xff) / 255.0f,
          static_cast<float>(v & 0xff) / 255.0f};
}

// ColorBrewer RdBu (11), from -1 (blue) to +1 (red).
constexpr std::array<Rgb, 11> kDivergingTable = {{
    hex(0x053061),
    hex(0x2166ac),
    hex(0x4393c3),
    hex(0x92c5de),
    hex(0xd1e5f0),
    hex(0xf7f7f7),
    hex(0xfddbc7),
    hex(0xf4a582),
    hex(0xd6604d),
    hex(0xb2182b),
    hex(0x67001f),
}};

// Labelled clusters: designed, not cycled (docs/analysis.md, "Colours"; the
// search rounds before these three: CHANGELOG and git history, issue 44).
// The rule (tests/views/palette_test.cpp): view A's colours that mean
// something (the cluster colours, the pale "others" as drawn, the rings,
// the inverted, coincident and intersection colours, the intersecting
// cells' tint) CIEDE2000 >= 20 apart for normal vision, and under simulated
// protanopia, deuteranopia and tritanopia (Machado 2009) >= 14.5 between
// cluster colours, >= 8 from the others; #0 the most salient mark, a vivid
// red (within 25 degrees of the quality map's worst hue, chroma >= 70),
// #1 and #2 >= 8 from the map's bad end and >= 12 from the greys under
// every simulation. A search over the sRGB grid in steps of 17 found no
// fourth colour beside a vivid #0 (a darker or more saturated one falls
// within 14.5 of #0 or the overlap colours for a dichromat), so 3 clusters
// are coloured (the issue: "colour fewer clusters than 10 if the palette
// cannot hold them"): #0 vivid crimson #ee0055 (CIELCh chroma 82), #1 sea
// blue #0088aa, #2 pale mint #ccffbb. Every later class is the neutral grey.
constexpr std::array<Rgb, kLabelledClusterPaletteSize> kLabelledClusterTable = {{
    hex(0xee0055),
    hex(0x0088aa),
    hex(0xccffbb),
}};
// A light grey (#a0a0a0), calm among the coloured clusters: CIEDE2000 19
// from the undefined grey (kUndefinedColor), 16 from the quality map's
// nearest sample (its pale end is a light blue-grey), >= 17 from the cluster
// and overlap colours.
constexpr Rgb kNeutralCluster = hex(0xa0a0a0);

// Piecewise-linear lookup, u in [0, 1] over the whole table.
template <std::size_t N>
Color sample(const std::array<Rgb, N>& table, double u) {
  const double x = std::clamp(u, 0.0, 1.0) * static_cast<double>(N - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), N - 2);
  const float f = static_cast<float>(x - static_cast<double>(i));
  const Rgb& p = table[i];
  const Rgb& q = table[i + 1];
  return {p.r + (q.r - p.r) * f, p.g + (q.g - p.g) * f, p.b + (q.b - p.b) * f, 1.0f};
}

}  // namespace

Color sample_quality_map(double t) {
  if (std::isnan(t)) return kUndefinedColor;
  return sample(kQualityTable, t);
}

std::vector<Color> quality_map_samples() {
  std::vector<Color> samples;
  for (const Rgb& c : kQualityTable) samples.push_back({c.r, c.g, c.b, 1.0f});
  return samples;
}

Color quality_color(double vertex_quality) {
  if (std::isnan(vertex_quality)) return kUndefinedColor;
  if (vertex_quality < 0.0) return kInvertedColor;
  return sample(kQualityTable, vertex_quality);
}

Color diverging_color(double t) {
  if (std::isnan(t)) return kUndefinedColor;
  return sample(kDivergingTable, 0.5 * (t + 1.0));
}

Color labelled_cluster_color(int i) {
  const Rgb& c = kLabelledClusterTable[static_cast<std::size_t>(std::clamp(i, 0, kLabelledClusterPaletteSize - 1))];
  return {c.r, c.g, c.b, 1.0f};
}

Color neutral_cluster_color() { return {kNeutralCluster.r, kNeutralCluster.g, kNeutralCluster.b, 1.0f}; }

Color cluster_color(std::int64_t rank, std::int64_t top_clusters) {
  if (rank >= 0 && rank < labelled_cluster_count(top_clusters)) return labelled_cluster_color(static_cast<int>(rank));
  return neutral_cluster_color();
}

double cie_lightness(const Color& c) {
  auto linear = [](double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); };
  const double y = 0.2126729 * linear(c.r) + 0.7151522 * linear(c.g) + 0.0721750 * linear(c.b);
  return y > 216.0 / 24389.0 ? 116.0 * std::cbrt(y) - 16.0 : y * 24389.0 / 27.0;
}

}  // namespace hq
