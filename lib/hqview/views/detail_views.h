#pragma once
// Detail views: C, the sub-region of one glyph cluster, and D, the one-ring
// of hexes around one vertex with the scaled Jacobian of each corner there.

#include <span>
#include <string>
#include <vector>

#include "hqview/glyph/glyphs.h"
#include "hqview/image/image.h"
#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/render/camera.h"
#include "hqview/render/renderer.h"
#include "hqview/render/scene.h"

namespace hq {

struct DetailViewOptions {
  int width = 1600, height = 1200;
  std::string title;
  Rgba8 background{255, 255, 255, 255};
  Vec3 up{0.0, 0.0, 1.0};  // the model axis drawn upwards (--up)
};

// The hexes of a cluster (those with a member vertex), ascending.
struct ClusterRegion {
  std::vector<Index> cells;
};
ClusterRegion cluster_region(const Topology& topology, const GlyphResult& glyphs, Index cluster);

// View C's scene:
//   lines[0]       edges of the neighbour cells, grey;
//   lines[1]       edges of the cluster's cells, in the cluster's colour;
//   spheres[0]     the cluster's glyphs, not aggregated: one per member at
//                  half its radius (full-size glyphs overlap and hide the
//                  cells), at most 0.35 times the mean edge length of the
//                  cluster's cells, coloured by quality_color(vertex quality);
//   translucent[0] the region's outer faces (faces of region cells not
//                  shared by two region cells), pale, so its shape reads.
Scene build_cluster_scene(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                          const GlyphResult& glyphs, Index cluster);

// The figure of view C: framed on the cluster's cells, from the direction
// (among 26) that shows the most glyph area; quality colour bar.
Image render_cluster_view(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                          const GlyphResult& glyphs, Index cluster, const DetailViewOptions& options,
                          Renderer& renderer);

// The same in two steps: the scene and its camera (no drawing; safe to run
// for several clusters at once), then the figure drawn from them.
struct ClusterShot {
  Scene scene;
  Camera camera;
};
ClusterShot cluster_shot(const HexMesh& mesh, const Topology& topology, const std::vector<double>& vertex_quality,
                         const GlyphResult& glyphs, Index cluster, const DetailViewOptions& options);
Image render_cluster_shot(const ClusterShot& shot, const DetailViewOptions& options, Renderer& renderer);

// The corners at vertex v: one per incident hex (ascending hex id), with its
// corner scaled Jacobian read from corner_values (QualityField's
// corner_scaled_jacobian: 8 per hex).
struct VertexCorner {
  Index hex = 0;
  int local = 0;     // corner index 0..7 of v in the hex
  double value = 0;  // corner scaled Jacobian
};
std::vector<VertexCorner> vertex_corners(const HexMesh& mesh, const Topology& topology,
                                         std::span<const double> corner_values, Index v);

// View D's scene:
//   lines[0]       edges of the one-ring hexes, dark grey;
//   spheres[0]     one marker per corner, 45% of the way from v
//                  towards its hex's centre, coloured by quality_color(value);
//   spheres[1]     v itself, small, dark;
//   translucent[0] the one-ring hexes' faces, pale.
Scene build_local_scene(const HexMesh& mesh, const Topology& topology, std::span<const double> corner_values, Index v);

// The figure of view D: the one ring framed, each corner marker labelled
// with its value and its hex id (as in chart E), quality colour bar.
Image render_local_view(const HexMesh& mesh, const Topology& topology, std::span<const double> corner_values, Index v,
                        const DetailViewOptions& options, Renderer& renderer);

}  // namespace hq
