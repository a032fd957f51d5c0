#include "support/verdict_oracle.h"

#include <fstream>

#include "support/fixtures.h"

namespace hq::test {

nlohmann::json load_verdict_oracle() {
  const auto dir = shared_data_dir();
  if (!dir) return nullptr;
  std::ifstream in(*dir / "verdict" / "hex_oracle_cases.json");
  return nlohmann::json::parse(in);
}

nlohmann::json load_cell_oracle() {
  const auto dir = shared_data_dir();
  if (!dir) return nullptr;
  std::ifstream in(*dir / "verdict" / "cell_oracle_cases.json");
  return nlohmann::json::parse(in);
}

std::array<Vec3, 8> oracle_corners(const nlohmann::json& oracle_case) {
  std::array<Vec3, 8> p;
  for (int i = 0; i < 8; ++i) {
    const auto& c = oracle_case["coords"][i];
    p[i] = {c[0].get<double>(), c[1].get<double>(), c[2].get<double>()};
  }
  return p;
}

}  // namespace hq::test
