#include "hqview/core/untouched_vector.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>

namespace hq {
namespace HQ_TEST_UNIT {

// Only resize(n) without a value skips the initialisation; the rest is
// std::vector's behaviour.
TEST(UntouchedVector, ValuesGivenAreKeptAndGrowthKeepsTheOldElements) {
  UntouchedVector<std::int32_t> v(5, 7);
  EXPECT_EQ(v.size(), 5u);
  for (std::int32_t x : v) EXPECT_EQ(x, 7);
  v.assign(3, -1);
  v.push_back(4);
  v.resize(1000);  // the new 996 are uninitialised: written before read
  for (std::size_t i = 4; i < v.size(); ++i) v[i] = static_cast<std::int32_t>(i);
  EXPECT_EQ(v[0], -1);
  EXPECT_EQ(v[2], -1);
  EXPECT_EQ(v[3], 4);
  EXPECT_EQ(v[999], 999);
  v.resize(1002, 5);
  EXPECT_EQ(v[1001], 5);
  const UntouchedVector<std::int32_t> copy = v;
  EXPECT_EQ(copy, v);
}

TEST(UntouchedVector, ElementsWithConstructorsAreStillConstructed) {
  UntouchedVector<std::string> names(3);
  for (const std::string& s : names) EXPECT_TRUE(s.empty());
  names.emplace_back(2, 'x');
  EXPECT_EQ(names.back(), "xx");
  UntouchedVector<std::array<int, 4>> quads(2, {1, 2, 3, 4});
  EXPECT_EQ(quads[1][3], 4);
}

}  // namespace
}  // namespace hq
