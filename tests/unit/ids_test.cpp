// Typed ids without a World: a default id is invalid, a default BodyRange is empty.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <iterator>
#include <ranges>

namespace sandphys {
namespace {

// A BodyRange works with the standard algorithms and views, not only in a range-for.
static_assert(std::forward_iterator<BodyRange::Iterator>);
static_assert(std::ranges::forward_range<BodyRange>);

TEST(Ids, DefaultIdsAreInvalid) {
  EXPECT_FALSE(BodyId{}.isValid());
  EXPECT_FALSE(ColliderId{}.isValid());
  EXPECT_FALSE(EmitterId{}.isValid());
  EXPECT_FALSE(SinkId{}.isValid());
}

TEST(Ids, ADefaultBodyRangeIsEmptyAndHoldsNothing) {
  const BodyRange none;
  EXPECT_TRUE(none.empty());
  EXPECT_EQ(none.size(), 0u);
  EXPECT_EQ(none.begin(), none.end());
  EXPECT_FALSE(none.contains(BodyId{}));
  EXPECT_FALSE(none.contains(BodyId{0, 0}));
  EXPECT_THROW((void)none[0], InvalidArgument);
}

}  // namespace
}  // namespace sandphys
