#pragma once
// ../shared/data/verdict/hex_oracle_cases.json: 13 hexes with every metric
// as Verdict 1.4.5 and VTK 9.1 compute it.

#include <array>
#include <nlohmann/json.hpp>

#include "hqview/core/vec3.h"

namespace hq::test {

// The parsed oracle, or null when ../shared/data is absent.
nlohmann::json load_verdict_oracle();

// ../shared/data/verdict/cell_oracle_cases.json (quads, triangles, tets,
// wedges, pyramids), or null when ../shared/data is absent.
nlohmann::json load_cell_oracle();

// The 8 corners of one oracle case.
std::array<Vec3, 8> oracle_corners(const nlohmann::json& oracle_case);

}  // namespace hq::test
