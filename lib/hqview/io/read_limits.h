#pragma once
// The memory budget of reading and analysing one mesh (--max-memory). Each
// reader calls check_mesh_memory() as soon as it knows the counts a file
// declares (vertices, then hexahedra) and before it allocates from them, so
// a file asking for more than the budget is refused with a clear message
// instead of being killed by the kernel's OOM killer half-way through.
//
// Order of the checks in a reader: a count is first checked against the
// bytes left in the file ("... cannot fit in the N bytes left in the file":
// a malformed file), then against the budget (a well-formed file too large
// for this machine).

#include <cstdint>
#include <string>
#include <string_view>

#include "hqview/mesh/hex_mesh.h"

namespace hq {

// The default budget: 75 % of the physical memory (sysconf), or of the
// cgroup's memory limit when that is lower and readable (cgroup v2
// memory.max, v1 memory.limit_in_bytes). 0 when neither is known.
std::uint64_t default_max_memory();

// Which cells a mesh is read with (--dimension): `automatic` reads a file
// with volume cells as a volume mesh (its quadrilaterals and triangles left
// out, as boundary faces) and a file with only surface cells (quadrilaterals,
// triangles) as a surface mesh; `volume` and `surface` force either.
enum class MeshDimension : std::uint8_t { automatic, volume, surface };

struct ReadLimits {
  std::uint64_t max_memory = default_max_memory();  // bytes; 0: no limit
  MeshDimension dimension = MeshDimension::automatic;  // not a limit: what every reader keeps
};

// Estimated peak bytes of `hqview analyze` on a mesh: the file's bytes
// (held during the analysis) plus per vertex and per hex costs of the whole
// pipeline (mesh, topology, quality fields, Verdict metrics, glyphs,
// overlap, rendering). Calibrated with /usr/bin/time -v (README, "Resource
// limits"). Saturates instead of overflowing.
std::uint64_t estimate_analysis_memory(std::uint64_t file_bytes, std::uint64_t num_vertices, std::uint64_t num_hexes);

// Estimated peak memory (bytes) of analysing a mesh file of `file_bytes`
// bytes, with or without the rendered views, and with or without the
// finite-element check (--simulate: its CSR matrix, CG vectors and per-hex
// error fields), before its counts are known: what `batch` schedules
// meshes by (--memory-budget).
std::uint64_t estimate_mesh_memory(std::uint64_t file_bytes, bool is_rendering, bool is_simulating = false);

// "512 MB", "1.5 GB", "3 TB" (binary units: 1 GB = 2^30 bytes), 3 significant digits.
std::string format_memory_size(std::uint64_t bytes);

// Throws ParseError "name:line: the file declares N hexes, which needs about
// X; --max-memory is Y" (or "N vertices" while the hexes are not known yet:
// num_hexes < 0) when estimate_analysis_memory() exceeds limits.max_memory.
// cell_noun: what the file declares ("cell", "element": a count of cells of
// any type, estimated as hexes).
void check_mesh_memory(const ReadLimits& limits, const std::string& name, std::int64_t line, std::uint64_t file_bytes,
                       std::int64_t num_vertices, std::int64_t num_hexes, std::string_view cell_noun = "hex");

// The largest coordinate magnitude HQView analyses. Squared lengths of
// coordinates up to 1e100 stay far from overflow (1.8e308), so bounding-box
// diagonals, edge lengths and Jacobians are finite; no physical mesh comes
// near it (a light year is 1e16 m; 1e9-scaled real meshes reach 1e11).
inline constexpr double kMaxCoordinateMagnitude = 1e100;

// Throws ParseError "name: node coordinates span A to B in magnitude: ..."
// when a coordinate's magnitude exceeds kMaxCoordinateMagnitude (A: the
// smallest non-zero magnitude, B: the largest). The readers refuse NaN and
// Inf themselves; tiny and denormal coordinates are analysed (their
// degenerate cells are data).
void check_coordinate_magnitudes(const HexMesh& mesh, const std::string& name);

}  // namespace hq
