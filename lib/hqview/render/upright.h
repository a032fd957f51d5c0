#pragma once
// Upright viewpoints: a person photographs a model with its up axis up, from
// a little above the horizon. Directions here are view directions (from the
// eye towards the scene, as fit_camera_to_points takes them); azimuth and
// elevation describe where the eye sits around the model's up axis.
//
//   azimuth 0      the eye on the model's front axis (front_of(up));
//                  positive azimuths turn the eye counter-clockwise seen
//                  from above (right-handed about up);
//   elevation      the angle of the eye above the horizontal plane
//                  (negative: below, -90: straight below).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hqview/core/vec3.h"

namespace hq {

// The --up names: "+x" "-x" "+y" "-y" "+z" "-z" (a bare "x" is "+x").
std::optional<Vec3> parse_up_axis(std::string_view name);
// "+y" for (0, 1, 0); an axis that is not a coordinate axis is written as
// its components.
std::string up_axis_name(const Vec3& up);

// The up axis of a view when none is chosen: the library's default and what
// `--up auto` falls back to when no pose rests (the command line's default
// is auto: docs/analysis.md "Up axis: auto").
inline constexpr std::string_view kDefaultUpAxis = "+z";

// The horizontal axis the front view's eye sits on: +z for a y-up model
// (the Stanford convention: +x to the right), -y for a z-up model (CAD:
// +x to the right), +z for an x-up model.
Vec3 front_of(const Vec3& up);

// The view direction of an eye at (azimuth, elevation), degrees.
Vec3 upright_view_direction(const Vec3& up, double azimuth_degrees, double elevation_degrees);

// The eye's elevation and azimuth (degrees, azimuth in (-180, 180]) of a view
// direction; the azimuth of a vertical direction is 0.
double view_elevation_degrees(const Vec3& view_direction, const Vec3& up);
double view_azimuth_degrees(const Vec3& view_direction, const Vec3& up);

// The elevations upright views are chosen among, degrees: the preferred
// one first (ties between candidates go to the earlier one).
inline constexpr double kUprightElevations[] = {25.0, 15.0, 35.0};
inline constexpr double kAzimuthStepDegrees = 30.0;
// The three-quarter view (overview, boundary error, reference overlay,
// compare): the eye turned 30 degrees right of the front, 25 above.
inline constexpr double kThreeQuarterAzimuth = 30.0, kThreeQuarterElevation = 25.0;
Vec3 three_quarter_view(const Vec3& up);
// The view from behind it: azimuth + 180, the same elevation (not its
// opposite, which would look from below).
Vec3 three_quarter_back_view(const Vec3& up);

// Candidates at kUprightElevations x every kAzimuthStepDegrees, from azimuth
// 0 on, elevation by elevation.
std::vector<Vec3> upright_view_candidates(const Vec3& up);
// What is tried when no upright candidate shows the target: the horizon,
// then below (-25, -60 degrees), and straight below last.
std::vector<Vec3> below_view_candidates(const Vec3& up);

}  // namespace hq
