#include "hqview/render/upright.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hq {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The unit horizontal axes of an up axis: front (azimuth 0) and side
// (azimuth 90), with side = up x front.
struct Horizontal {
  Vec3 front, side;
};

Horizontal horizontal_of(const Vec3& up) {
  const Vec3 u = normalized(up);
  // The front axis made orthogonal to up (exact for coordinate axes).
  Vec3 f = front_of(u);
  f = normalized(f - dot(f, u) * u);
  return {f, cross(u, f)};
}

}  // namespace

std::optional<Vec3> parse_up_axis(std::string_view name) {
  double sign = 1.0;
  if (!name.empty() && (name.front() == '+' || name.front() == '-')) {
    sign = name.front() == '-' ? -1.0 : 1.0;
    name.remove_prefix(1);
  }
  if (name == "x") return Vec3{sign, 0.0, 0.0};
  if (name == "y") return Vec3{0.0, sign, 0.0};
  if (name == "z") return Vec3{0.0, 0.0, sign};
  return std::nullopt;
}

std::string up_axis_name(const Vec3& up) {
  const char axes[3] = {'x', 'y', 'z'};
  for (int i = 0; i < 3; ++i) {
    const bool others_zero = up[(i + 1) % 3] == 0.0 && up[(i + 2) % 3] == 0.0;
    if (others_zero && up[i] != 0.0) return std::string(up[i] > 0.0 ? "+" : "-") + axes[i];
  }
  return "(" + std::to_string(up.x) + ", " + std::to_string(up.y) + ", " + std::to_string(up.z) + ")";
}

Vec3 front_of(const Vec3& up) {
  const double ax = std::abs(up.x), ay = std::abs(up.y), az = std::abs(up.z);
  if (az >= ax && az >= ay) return {0.0, -1.0, 0.0};
  return {0.0, 0.0, 1.0};
}

Vec3 upright_view_direction(const Vec3& up, double azimuth_degrees, double elevation_degrees) {
  const Horizontal h = horizontal_of(up);
  const double a = azimuth_degrees * kDegree, e = elevation_degrees * kDegree;
  const Vec3 eye = std::cos(e) * (std::cos(a) * h.front + std::sin(a) * h.side) + std::sin(e) * normalized(up);
  return -eye;
}

Vec3 three_quarter_view(const Vec3& up) {
  return upright_view_direction(up, kThreeQuarterAzimuth, kThreeQuarterElevation);
}

Vec3 three_quarter_back_view(const Vec3& up) {
  return upright_view_direction(up, kThreeQuarterAzimuth + 180.0, kThreeQuarterElevation);
}

double view_elevation_degrees(const Vec3& view_direction, const Vec3& up) {
  const Vec3 eye = -normalized(view_direction);
  return std::asin(std::clamp(dot(eye, normalized(up)), -1.0, 1.0)) / kDegree;
}

double view_azimuth_degrees(const Vec3& view_direction, const Vec3& up) {
  const Horizontal h = horizontal_of(up);
  const Vec3 eye = -view_direction;
  const double x = dot(eye, h.front), y = dot(eye, h.side);
  if (std::hypot(x, y) < 1e-12 * std::max(1.0, norm(eye))) return 0.0;
  return std::atan2(y, x) / kDegree;
}

std::vector<Vec3> upright_view_candidates(const Vec3& up) {
  std::vector<Vec3> directions;
  for (double elevation : kUprightElevations)
    for (double azimuth = 0.0; azimuth < 360.0 - 1e-9; azimuth += kAzimuthStepDegrees)
      directions.push_back(upright_view_direction(up, azimuth, elevation));
  return directions;
}

std::vector<Vec3> below_view_candidates(const Vec3& up) {
  std::vector<Vec3> directions;
  for (double elevation : {0.0, -25.0, -60.0})
    for (double azimuth = 0.0; azimuth < 360.0 - 1e-9; azimuth += kAzimuthStepDegrees)
      directions.push_back(upright_view_direction(up, azimuth, elevation));
  directions.push_back(upright_view_direction(up, 0.0, -90.0));
  return directions;
}

}  // namespace hq
