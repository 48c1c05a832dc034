#include <gtest/gtest.h>

#include "meshround/radius_law.h"

using namespace meshround;

namespace {
// A straight chain of 11 vertices along x, 0..100: enough for the law, which only needs arc lengths.
SharpChain straight_chain() {
  Points V(22, 3);
  for (int i = 0; i < 11; ++i) V.row(i) << 10.0 * i, 0, 0, V.row(11 + i) << 10.0 * i, 1, 1;
  Triangles F(20, 3);
  for (int i = 0; i < 10; ++i) F.row(2 * i) << i, i + 1, 11 + i, F.row(2 * i + 1) << i + 1, 12 + i, 11 + i;
  static Points keepV;
  static Triangles keepF;
  keepV = V, keepF = F;
  static MeshTopology mesh(keepV, keepF);
  SharpChain c;
  for (int i = 0; i < 11; ++i) c.points.push_back(V.row(i).transpose()), c.arc_length.push_back(10.0 * i);
  c.length = 100;
  return c;
}
}  // namespace

// OCCT's Add(2, 8, E) on a straight edge has r = 3.1786 and 6.8214 a quarter from either end (sections of
// its fillet; tests/python's box_ends case checks the whole round against it).
TEST(RadiusLaw, TwoPointsFollowOcctsStartEndLawAndAreClampedOutside) {
  const SharpChain chain = straight_chain();
  RoundOptions o;
  o.radius_law = {{Vec3(20, 0, 0), 2.0}, {Vec3(80, 0, 0), 8.0}};
  const RadiusLaw law(o, chain, 10);
  EXPECT_DOUBLE_EQ(law.at(0), 2.0);
  EXPECT_DOUBLE_EQ(law.at(20), 2.0);
  EXPECT_NEAR(law.at(35), 3.1786, 1e-4);
  EXPECT_DOUBLE_EQ(law.at(50), 5.0);
  EXPECT_NEAR(law.at(65), 6.8214, 1e-4);
  EXPECT_DOUBLE_EQ(law.at(80), 8.0);
  EXPECT_DOUBLE_EQ(law.at(100), 8.0);
  double prev = 0;
  for (double s = 0; s <= 100; s += 0.5) {  // monotone
    EXPECT_GE(law.at(s), prev - 1e-12);
    prev = law.at(s);
  }
}

TEST(RadiusLaw, ThreePointsAreMonotoneWithoutOvershoot) {
  const SharpChain chain = straight_chain();
  RoundOptions o;
  o.radius_law = {{Vec3(0, 0, 0), 2.0}, {Vec3(30, 0, 0), 6.0}, {Vec3(100, 0, 0), 6.5}};
  const RadiusLaw law(o, chain, 10);
  double prev = 0;
  for (double s = 0; s <= 100; s += 0.5) {
    const double r = law.at(s);
    EXPECT_GE(r, prev - 1e-12);
    EXPECT_LE(r, 6.5 + 1e-12);
    prev = r;
  }
  EXPECT_NEAR(law.at(30), 6.0, 1e-12);
}

TEST(RadiusLaw, RejectsBadControlPoints) {
  const SharpChain chain = straight_chain();
  RoundOptions o;
  o.radius_law = {{Vec3(50, 40, 0), 3.0}, {Vec3(80, 0, 0), 4.0}};
  EXPECT_THROW(RadiusLaw(o, chain, 10), RoundingError);
  o.radius_law = {{Vec3(50, 0, 0), -1.0}, {Vec3(80, 0, 0), 4.0}};
  EXPECT_THROW(RadiusLaw(o, chain, 10), RoundingError);
}
