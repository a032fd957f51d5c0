#pragma once
// The structure of a quad surface mesh (docs/analysis.md, "Quad-mesh
// structure"), as quad-remeshing papers count it:
//   - a vertex's valence is its number of incident quads (some papers count
//     its edges instead: the same number inside the mesh, one more on the
//     boundary);
//   - an interior vertex is irregular when its valence is not 4; a boundary
//     vertex when its valence differs from its ideal valence
//     max(1, round(theta / 90 deg)), theta the sum of its quads' corner
//     angles (180 deg on a smooth boundary: ideal 2; 90 deg at a convex
//     feature corner: 1; 270 deg at a concave one: 3), the rule the hex
//     structure uses for boundary edges;
//   - a vertex that touches a triangle, a non-manifold edge, a hole edge
//     (an edge of a polygon the reader skipped) or more than two boundary
//     edges is unclassified: neither regular nor irregular;
//   - separatrices are traced from each irregular vertex along each of its
//     edges (only interior edges from a boundary vertex), straight on through
//     regular interior vertices of valence 4 (to the edge opposite the one
//     arrived by), stopping after an edge that ends at an irregular,
//     boundary or unclassified vertex, or before an edge already traced (a
//     separatrix that another one has traced from its other end is not
//     traced twice); each edge is traced at most once, so the work is at
//     most the number of edges, and `max_traced_edges` caps it further;
//   - the patches are the components of quads joined across interior
//     manifold edges that no separatrix traced.
// Linear in the mesh but for one sort of its edges.

#include <cstdint>
#include <map>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/mesh/mesh.h"

namespace hq {

struct QuadStructureOptions {
  // Edges traced over all separatrices at most; 0: no cap (at most every edge).
  std::int64_t max_traced_edges = 0;
  // Edges that are holes, not boundary (LoadedMesh::hole_edges: a < b).
  std::vector<std::array<Index, 2>> hole_edges;
};

enum class QuadVertexKind : std::uint8_t { interior, boundary, unclassified };

// Why a separatrix stopped.
enum class SeparatrixEnd : std::uint8_t {
  irregular_vertex,     // at an irregular vertex
  boundary,             // at a boundary vertex
  unclassified_vertex,  // at a vertex touching a triangle, a hole or a non-manifold edge
  traced_edge,          // before an edge another separatrix had traced
  cap                   // max_traced_edges reached
};

struct QuadStructure {
  // Per vertex.
  std::vector<Index> valence;               // incident quads
  std::vector<QuadVertexKind> vertex_kind;  // a vertex on no quad is unclassified
  std::vector<std::int8_t> ideal_valence;   // interior 4; boundary max(1, round(theta / 90 deg)); unclassified 0
  std::vector<char> irregular;              // 0/1
  Index num_irregular = 0, num_irregular_interior = 0, num_irregular_boundary = 0;
  Index num_unclassified = 0;                  // vertices on quads that are unclassified
  std::map<Index, Index> interior_by_valence;  // irregular interior vertices: valence -> count
  std::map<Index, Index> boundary_by_valence;  // irregular boundary vertices: valence -> count
  std::vector<Index> irregular_vertices;       // ascending

  // Edges of the quads.
  Index num_edges = 0, num_boundary_edges = 0, num_nonmanifold_edges = 0;

  // Separatrices, in tracing order (irregular vertices ascending, each one's
  // edges in the order of its quads): separatrix s is the vertex path
  // separatrix_vertices[separatrix_offsets[s] .. separatrix_offsets[s + 1]),
  // from its irregular vertex; it has (path length - 1) edges.
  std::vector<std::int64_t> separatrix_offsets{0};
  std::vector<Index> separatrix_vertices;
  std::vector<SeparatrixEnd> separatrix_end;
  Index num_separatrices = 0;
  std::int64_t num_traced_edges = 0;
  bool is_capped = false;  // max_traced_edges stopped the tracing

  // Per quad: its patch (0-based, numbered by their first quad).
  std::vector<Index> quad_patch;
  Index num_patches = 0;
};

// The structure of mesh.quads over mesh.points; the other blocks only make
// the vertices they touch unclassified (a quad-dominant mesh's triangles).
QuadStructure compute_quad_structure(const Mesh& mesh, const QuadStructureOptions& options = {});

}  // namespace hq
