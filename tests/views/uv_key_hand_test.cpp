// The UV key of the hand (../shared/data), whose numbers the issue-45b
// review found on the wrong charts: each on its own chart or led to it.
// Slow: the atlas as analyze builds it (LSCM) takes most of 17 s.
#include <gtest/gtest.h>

#include "hqview/io/mesh_reader.h"
#include "support/fixtures.h"
#include "uv_key_checks.h"

namespace hq {
namespace HQ_TEST_UNIT {

TEST(UvKeyFigure, TheHandsNumbersLieOnTheirChartsOrLeadToThem) {
  const auto data = test::shared_data_dir();
  if (!data) GTEST_SKIP() << "../shared/data is absent";
  const TriSurface hand = read_surface(*data / "meshes/gao2016_sweeping/hand.off");
  // As analyze builds it (12 charts, the reviewer's figure).
  const UvAtlas atlas = build_uv_atlas(hand, UvOptions{.up = {0.0, 1.0, 0.0}, .improve_with_lscm = true});
  EXPECT_EQ(atlas.num_charts, 12);
  expect_numbers_on_their_charts(hand, atlas, atlas.num_charts);
}

}  // namespace
}  // namespace hq
