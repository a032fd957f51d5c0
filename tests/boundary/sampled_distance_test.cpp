// The sampled boundary error (issue 43): certified maxima over the surfaces
// both ways, against analytic distances (a coarse hex ball against a fine
// sphere), brute force; the exhaustive dense sampling of the shared pairs is
// in boundary_error_test.cpp (SampledPairs).

#include "hqview/boundary/sampled_distance.h"

#include <gtest/gtest.h>

#include <cmath>

#include "hqview/boundary/boundary_error.h"
#include "hqview/boundary/triangle_closest_point.h"
#include "hqview/mesh/topology.h"
#include "support/fixtures.h"
#include "support/surface_fixtures.h"

namespace hq::test {
namespace HQ_TEST_UNIT {

double brute_force_distance(const TriSurface& s, const Vec3& p) {
  double best = INFINITY;
  for (const auto& t : s.triangles)
    best = std::min(best, norm(p - closest_point_on_triangle(p, s.points[t[0]], s.points[t[1]], s.points[t[2]])));
  return best;
}

double unit_radius(const Vec3&) { return 1.0; }

// Largest distance from the unit sphere's inscribed icosphere(level) to the
// sphere: 1 - the smallest distance of a triangle from the centre.
double chord_sag(const TriSurface& s) {
  double sag = 0;
  for (const auto& t : s.triangles)
    sag = std::max(sag, 1.0 - norm(closest_point_on_triangle({}, s.points[t[0]], s.points[t[1]], s.points[t[2]])));
  return sag;
}

TEST(SampledDistance, CoarseHexBallAgainstAFineSphereMatchesTheAnalyticDistance) {
  const HexMesh mesh = hex_ball(4, unit_radius);  // boundary vertices on the unit sphere
  const Topology topo = build_topology(mesh);
  const TriSurface sphere = icosphere(6);  // 81920 triangles
  const double sag = chord_sag(sphere);
  ASSERT_LT(sag, 3e-4);
  BoundaryOptions options;
  const BoundaryError e = compute_boundary_error(mesh, topo, sphere, options);
  const double tolerance = options.sampling_tolerance * e.reference_bbox_diagonal;
  EXPECT_NEAR(e.sampling_tolerance, tolerance, 1e-15);

  // The vertex figure stays near 0 (the vertices lie on the sphere, the icosphere within sag of it).
  EXPECT_LE(e.hausdorff_mesh_to_reference, sag + 1e-12);

  // Every sample: the distance to the sphere, 1 - |c|, within the chord sag;
  // inside the reference (flat faces cut the ball), so negative.
  ASSERT_FALSE(e.mesh_patches.empty());
  double area = 0;
  for (const auto& p : e.mesh_patches) {
    const Vec3 c = (p.corners[0] + p.corners[1] + p.corners[2]) / 3.0;
    const double analytic = norm(c) - 1.0;
    ASSERT_NEAR(p.error, analytic, sag + 1e-12);
    area += p.area;
  }
  // The patches tile the hex boundary triangles.
  double boundary_area = 0;
  const TriSurface hex = boundary_triangles(mesh, topo);
  for (const auto& t : hex.triangles)
    boundary_area += 0.5 * norm(cross(hex.points[t[1]] - hex.points[t[0]], hex.points[t[2]] - hex.points[t[0]]));
  EXPECT_NEAR(area, boundary_area, 1e-9 * boundary_area);

  // At the centre of each boundary face (the midpoint of the split diagonal
  // 0-2) the sample of the patch holding it reads 1 - |centre|.
  int centres = 0;
  for (Index f : topo.boundary_faces) {
    const Quad& q = topo.faces[f];
    const Vec3 centre = 0.5 * (mesh.points[q[0]] + mesh.points[q[2]]);
    double best = INFINITY, error = 0, radius = 0;
    for (const auto& p : e.mesh_patches) {
      const Vec3 c = (p.corners[0] + p.corners[1] + p.corners[2]) / 3.0;
      if (norm(c - centre) < best) {
        best = norm(c - centre);
        error = p.error;
        radius = std::max({norm(p.corners[0] - c), norm(p.corners[1] - c), norm(p.corners[2] - c)});
      }
    }
    EXPECT_NEAR(-error, 1.0 - norm(centre), sag + radius + 1e-12) << f;  // 1-Lipschitz
    ++centres;
  }
  EXPECT_EQ(centres, 96);

  // The analytic maximum over the hex boundary: 1 - the smallest distance of a triangle from the centre.
  double analytic_max = 0;
  for (const auto& t : hex.triangles)
    analytic_max =
        std::max(analytic_max, 1.0 - norm(closest_point_on_triangle({}, hex.points[t[0]], hex.points[t[1]], hex.points[t[2]])));
  ASSERT_GT(analytic_max, 0.05);  // flat faces of a 4^3 ball: far from the sphere between the vertices
  const auto& m = e.sampled_mesh_to_reference;
  EXPECT_LE(m.max, m.upper_bound);
  EXPECT_LE(m.upper_bound - m.max, tolerance + 1e-15);
  EXPECT_NEAR(m.max, analytic_max, sag + tolerance);
  EXPECT_GE(m.upper_bound, analytic_max - sag);
  EXPECT_LT(m.mean, -0.3 * analytic_max);  // the whole boundary lies inside
  EXPECT_DOUBLE_EQ(e.fraction_outside, 0.0);
  EXPECT_GT(e.fraction_inside, 0.8);
  EXPECT_NEAR(e.fraction_inside + e.fraction_on_surface, 1.0, 1e-12);

  // Reference -> mesh: the sphere bulges out of the flat faces, outside the
  // hex solid, so negative (but near the hex vertices, where the icosphere
  // lies up to sag inside); its maximum is certified against a brute-force
  // sampling of every 7th sphere triangle.
  const auto& r = e.sampled_reference_to_mesh;
  EXPECT_LE(r.upper_bound - r.max, tolerance + 1e-15);
  double dense = 0;
  for (std::size_t t = 0; t < sphere.triangles.size(); t += 7) {
    const auto& tri = sphere.triangles[t];
    const Vec3 &a = sphere.points[tri[0]], &b = sphere.points[tri[1]], &c = sphere.points[tri[2]];
    for (const Vec3& p : {a, (a + b) / 2.0, (a + b + c) / 3.0, (a + 2.0 * b + c) / 4.0})
      dense = std::max(dense, brute_force_distance(hex, p));
  }
  EXPECT_LE(dense, r.upper_bound + 1e-12);
  EXPECT_LE(dense, r.max + tolerance);
  EXPECT_NEAR(r.max, analytic_max, sag + tolerance);  // the same gap seen from the sphere
  for (const auto& p : e.reference_patches) ASSERT_LE(p.error, sag);
  EXPECT_NEAR(e.sampled_symmetric, std::max(m.max, r.max), 0.0);
  EXPECT_EQ(e.sampled_upper_bound, std::max(m.upper_bound, r.upper_bound));
}

TEST(SampledDistance, TighterToleranceGivesATighterBoundAndMoreSamples) {
  const HexMesh mesh = hex_ball(3, [](const Vec3& u) { return 1.0 + 0.1 * u.x * u.y; });
  const Topology topo = build_topology(mesh);
  const TriSurface sphere = icosphere(5);
  BoundaryOptions loose, tight;
  loose.sampling_tolerance = 1e-2;
  tight.sampling_tolerance = 1e-4;
  const BoundaryError a = compute_boundary_error(mesh, topo, sphere, loose);
  const BoundaryError b = compute_boundary_error(mesh, topo, sphere, tight);
  EXPECT_LT(a.sampled_mesh_to_reference.num_samples, b.sampled_mesh_to_reference.num_samples);
  EXPECT_LE(b.sampled_upper_bound - b.sampled_symmetric, 1e-4 * b.reference_bbox_diagonal + 1e-15);
  EXPECT_LE(a.sampled_upper_bound - a.sampled_symmetric, 1e-2 * a.reference_bbox_diagonal + 1e-15);
  // Both bounds hold for the tighter maximum.
  EXPECT_LE(b.sampled_mesh_to_reference.max, a.sampled_mesh_to_reference.upper_bound);
  EXPECT_LE(a.sampled_mesh_to_reference.max, b.sampled_mesh_to_reference.upper_bound);
}

// The target square [0,4]^2 x {0} (split along y = x) and a source triangle at height 0.25 over it.
TriSurface square_target() {
  TriSurface target;
  target.points = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  target.triangles = {{0, 1, 2}, {0, 2, 3}};
  return target;
}
TriSurface triangle_above() {
  TriSurface source;
  source.points = {{1, 1, 0.25}, {3, 1, 0.25}, {2, 3, 0.25}};
  source.triangles = {{0, 1, 2}};
  return source;
}

TEST(SampledDistance, PlaneTriangleAboveAPlaneIsItsHeightEverywhere) {
  const TriSurface target = square_target(), source = triangle_above();
  const ClosestPointTree tree(target);
  SampledDistanceOptions options;
  options.tolerance = 1e-3;
  options.initial_radius = 0.1;
  const SampledDistance d = sample_distance(source, tree, options);
  EXPECT_DOUBLE_EQ(d.max_distance, 0.25);
  double area = 0;
  for (const SamplePatch& p : d.patches) {
    EXPECT_NEAR(p.closest.distance, 0.25, 1e-15);
    area += p.area;
  }
  EXPECT_NEAR(area, 2.0, 1e-12);
  // Level 0 cut to radius <= 0.1: the triangle's radius is 4/3 (centroid to
  // the apex), 4 halvings, 4^4 patches; those across the target's diagonal
  // y = x (corners off the centroid's closest triangle) are split further.
  EXPECT_GT(d.patches.size(), std::size_t{256});
  EXPECT_LT(d.patches.size(), std::size_t{4096});
  EXPECT_GT(d.deepest_level, 0);
  // Uniform distance: the bound of the corners to the closest triangle is tight.
  EXPECT_LE(d.upper_bound - d.max_distance, 1e-3);
  EXPECT_GE(d.upper_bound, 0.25);
}

TEST(SampledDistance, ASampleBudgetStopsTheSplitsAndTheBoundSaysSo) {
  const TriSurface target = square_target(), source = triangle_above();
  const ClosestPointTree tree(target);
  SampledDistanceOptions options;
  options.tolerance = 1e-12;  // unreachable across the target's diagonal
  options.max_samples = 500;
  const SampledDistance d = sample_distance(source, tree, options);
  EXPECT_LE(d.num_samples, 504);
  EXPECT_DOUBLE_EQ(d.max_distance, 0.25);
  EXPECT_GT(d.upper_bound - d.max_distance, 1e-12) << "not certified to the tolerance, and it says so";
  EXPECT_GE(d.upper_bound, 0.25);
}

}  // namespace
}  // namespace hq::test
