#pragma once
// The structure of a hex mesh, as HexaLab and cinolib define it:
//   - an edge's valence is its number of incident hexes; an interior edge
//     is singular when its valence is not 4, a boundary edge (an edge of a
//     boundary face) when it is not 2; a boundary edge on more than two
//     boundary faces is non-manifold and counted apart;
//   - a boundary edge is also irregular when its valence differs from
//     round(theta / 90 deg) (at least 1), theta the dihedral angle inside the
//     mesh between its two boundary faces (90 along a box edge);
//   - singular vertices touch a singular edge; the singularity graph's nodes
//     are singular vertices with other than 2 singular edges (on a hybrid
//     mesh not a curve's end on the interface with the non-hex cells), its curves
//     maximal chains of singular edges between nodes (a closed chain
//     without a node is one curve);
//   - the size gradation of a cell is the largest ratio of its size to a
//     face neighbour's (or the inverse, so >= 1); a cell's size is a
//     length, its equivalent edge length: the cube root of its Verdict
//     volume over the volume of its kind's regular cell of unit edges
//     (cell_volume.h), i.e. the edge of the regular cell of its kind with
//     its volume (a hex: the cube root of its volume), so a regular tet next
//     to a cube of the same edge length grades 1, and a cube next to one of
//     twice its edge grades 2 (issue 46: a volume ratio turned the shape
//     noise of same-size tets into ratios of 2-3). On a hybrid mesh every volume cell has one, its neighbours
//     those sharing a whole face with it (any kinds) and, across a
//     non-conforming interface, the quad's cell and the two triangles'.
// On a hybrid mesh all of this but the size gradation is the hex part's: valences count hexes, and
// an edge of the hex part that is also an edge of a tet, wedge or pyramid
// (Topology::edge_touches_non_hex) is neither singular nor regular nor
// irregular: it is listed with touches_non_hex and counted apart (its kind
// says whether it lies on the whole mesh's boundary).
// Linear in the mesh: the valences come from Topology's sorted edges.

#include <cstdint>
#include <map>
#include <vector>

#include "hqview/mesh/hex_mesh.h"
#include "hqview/mesh/topology.h"
#include "hqview/quality/statistics.h"

namespace hq {

enum class EdgeKind : std::uint8_t { interior, boundary, nonmanifold };

// An edge worth a row of data/edges.csv: singular, irregular, non-manifold
// or touching a non-hex cell.
struct StructureEdge {
  Edge vertices;  // a < b
  Index valence = 0;
  EdgeKind kind = EdgeKind::interior;
  bool singular = false;
  Index ideal_valence = 0;  // boundary edges: round(theta / 90 deg), at least 1; else 0
  bool irregular = false;   // boundary edges: valence != ideal_valence
  Index curve = kNoIndex;   // singular edges: their singular curve
  bool touches_non_hex = false;  // also an edge of a tet, wedge or pyramid: never singular or irregular
};

struct HexStructure {
  Index num_edges = 0;
  Index num_singular_edges_interior = 0;
  Index num_singular_edges_boundary = 0;
  Index num_irregular_edges_boundary = 0;
  Index num_nonmanifold_edges = 0;
  Index num_edges_touching_non_hex = 0;  // hex edges that are also edges of non-hex cells
  std::map<Index, Index> interior_by_valence;  // singular interior edges: valence -> count
  std::map<Index, Index> boundary_by_valence;  // singular boundary edges: valence -> count
  // Singular, irregular, non-manifold and non-hex-touching edges, ascending
  // vertex pairs; the singular ones (interior and boundary) make the
  // singularity graph.
  std::vector<StructureEdge> edges;
  std::vector<char> vertex_singular;           // per vertex, 0/1
  Index num_singular_vertices = 0;
  std::vector<Index> nodes;                    // ascending vertex ids
  // A hybrid mesh: singular vertices with one singular edge on an edge that
  // touches a non-hex cell, where a curve is cut by the hex part's
  // interface; not nodes (the curve goes on in the non-hex part, unseen).
  Index num_interface_ends = 0;
  Index num_curves = 0;
  std::vector<Index> curve_lengths;            // edges per curve, by curve id
  // Per volume cell id (hexes first, then tets, wedges, pyramids): the size
  // gradation (NaN for a cell without a positive volume or without a face
  // neighbour of positive volume).
  std::vector<double> cell_gradation;
  Statistics gradation;                        // of the finite cell_gradation values
  Index num_gradation_above_2 = 0, num_gradation_above_4 = 0;  // length ratios, strictly above
};

HexStructure compute_structure(const HexMesh& mesh, const Topology& topology);

// Edge valences the simple way (a std::map of sorted vertex pairs): the
// baseline of bench_structure and a test oracle.
std::map<Edge, Index> edge_valences_by_map(const HexMesh& mesh);

}  // namespace hq
