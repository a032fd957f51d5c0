// cell_metrics_dump KIND AVERAGE: reads one cell per line on stdin (its
// corners' x y z in VTK order, 3 x corners numbers) and prints every HQView
// metric of that kind per cell as CSV (a header of Verdict's names, values
// with 17 significant digits, NaN as "nan"). KIND: tet, wedge, pyramid,
// quad, triangle; AVERAGE: the mean cell size for the size metrics.
// A test helper for check_vtk_cells.py (the VTK 9.1 agreement test).

#include <array>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "hqview/quality/pyramid_metrics.h"
#include "hqview/quality/quad_metrics.h"
#include "hqview/quality/tet_metrics.h"
#include "hqview/quality/triangle_metrics.h"
#include "hqview/quality/wedge_metrics.h"

namespace {

template <std::size_t N, class Info, class Values>
int dump(int num_metrics, const Info& info, const Values& values) {
  for (int m = 0; m < num_metrics; ++m) std::printf("%s%s", m ? "," : "", std::string(info(m)).c_str());
  std::printf("\n");
  std::array<hq::Vec3, N> p;
  while (true) {
    for (std::size_t i = 0; i < N; ++i)
      if (!(std::cin >> p[i].x >> p[i].y >> p[i].z)) return std::cin.eof() && i == 0 ? 0 : 2;
    const auto v = values(p);
    for (int m = 0; m < num_metrics; ++m) std::printf("%s%.17g", m ? "," : "", v[static_cast<std::size_t>(m)]);
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace hq;
  if (argc != 3) {
    std::fprintf(stderr, "usage: cell_metrics_dump KIND AVERAGE < corners\n");
    return 2;
  }
  const std::string kind = argv[1];
  const double average = std::strtod(argv[2], nullptr);
  if (kind == "tet")
    return dump<4>(
        kNumTetMetrics, [](int m) { return tet_metric_info(TetMetric(m)).name; },
        [&](const TetCorners& p) { return tet_metrics(p, average); });
  if (kind == "wedge")
    return dump<6>(
        kNumWedgeMetrics, [](int m) { return wedge_metric_info(WedgeMetric(m)).name; },
        [&](const WedgeCorners& p) { return wedge_metrics(p, average); });
  if (kind == "pyramid")
    return dump<5>(
        kNumPyramidMetrics, [](int m) { return pyramid_metric_info(PyramidMetric(m)).name; },
        [&](const PyramidCorners& p) { return pyramid_metrics(p, average); });
  if (kind == "quad")
    return dump<4>(
        kNumQuadMetrics, [](int m) { return quad_metric_info(QuadMetric(m)).name; },
        [&](const QuadCorners& p) { return quad_metrics(p, average); });
  if (kind == "triangle")
    return dump<3>(
        kNumTriangleMetrics, [](int m) { return triangle_metric_info(TriangleMetric(m)).name; },
        [&](const TriangleCorners& p) { return triangle_metrics(p, average); });
  std::fprintf(stderr, "cell_metrics_dump: unknown kind %s\n", kind.c_str());
  return 2;
}
