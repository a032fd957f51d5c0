#pragma once
// The hex boundary the viewer draws, and its reduction under the viewer's
// size budget (--viewer-max-mb): vertex clustering on a uniform grid, the way
// a picture is simplified, never the numbers. Each grid cell keeps one real
// boundary vertex, its worst-quality one (so the worst vertex of the mesh is
// always drawn where it is, with its own values); a face survives when its
// corners land in at least three cells, and of faces that land on the same
// cells the one whose hex has the lowest scaled Jacobian is kept. Every face
// drawn is a real boundary face's hex, so a click still shows exact values.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "hqview/core/types.h"
#include "hqview/core/vec3.h"

namespace hq {

struct Analysis;

struct ViewerBoundary {
  std::vector<Index> vertices;       // mesh vertex ids (ascending when not reduced)
  std::vector<std::uint32_t> quads;  // 4 per face into `vertices`; a triangle repeats its last corner
  std::vector<Index> face_hex;       // the cell of each face (id over all blocks, hexes first)
  std::size_t num_source_faces = 0;  // boundary faces of the mesh
  double cell_size = 0;              // the clustering grid's cell (0: not reduced)
};

// Every boundary face of the analysed mesh over all kinds (boundary_polygons),
// as seen from outside; of a surface mesh (issue 47), its faces: the quads
// then the triangles, each face's cell its own id, as the file orients them.
ViewerBoundary viewer_boundary(const Analysis& analysis);

// The boundary reduced to at most `max_faces` faces: the grid's cells start
// at about one boundary vertex each for that count and grow until it fits
// (the result has roughly 0.5-1 times `max_faces` faces). `vertex_quality` and `cell_scaled_jacobian` are indexed by
// mesh vertex and hex. Deterministic: the result depends only on the input.
ViewerBoundary reduce_boundary(const ViewerBoundary& full, const std::vector<Vec3>& points,
                               const std::vector<double>& vertex_quality,
                               const std::vector<double>& cell_scaled_jacobian, std::size_t max_faces);

}  // namespace hq
