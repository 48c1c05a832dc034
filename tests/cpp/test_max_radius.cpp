// max_radius (max_radius.h) on a meshed box: the top back edge of a 100 x 60 x 40 box takes any ball up to
// the 40 mm side face (closed form), and round_edges agrees: 0.98x of the answer rounds, 1.02x is refused.
#include <BRepPrimAPI_MakeBox.hxx>
#include <gtest/gtest.h>

#include "meshround/max_radius.h"
#include "meshround/round.h"
#include "support.h"

namespace meshround {
namespace {

TEST(MaxRadius, BoxTopEdgeIsTheSideFaceHeight) {
  const test::TriMesh box = test::mesh_shape(BRepPrimAPI_MakeBox(100, 60, 40).Shape(), 4.0);
  const std::vector<Vec3> seed{Vec3(50, 60, 40)};
  const std::vector<ChainRoom> rooms = max_radius(box.V, box.F, seed, MaxRadiusOptions{});
  ASSERT_EQ(rooms.size(), 1u);
  EXPECT_NEAR(rooms[0].radius, 40.0, 0.005 * 40);
  EXPECT_LE(rooms[0].radius_refused, rooms[0].radius * (1 + 2e-4));
  EXPECT_EQ(rooms[0].why, RoomLimit::OppositeWall);  // the bottom face, across the 40 mm side face
  EXPECT_NEAR(rooms[0].where.z(), 0.0, 1e-6);
  RoundOptions o;
  o.radius = 0.98 * rooms[0].radius;
  EXPECT_NO_THROW(round_edges(box.V, box.F, seed, o));
  o.radius = 1.02 * rooms[0].radius;
  try {
    round_edges(box.V, box.F, seed, o);
    FAIL() << "1.02 x the largest radius was not refused";
  } catch (const RoundingError& e) {
    EXPECT_EQ(e.code, ErrorCode::RadiusTooLarge);
  }
}

TEST(MaxRadius, RefusesBadOptions) {
  const test::TriMesh box = test::mesh_shape(BRepPrimAPI_MakeBox(10, 10, 10).Shape(), 2.0);
  MaxRadiusOptions o;
  o.precision = 0;
  EXPECT_THROW(max_radius(box.V, box.F, {Vec3(5, 10, 10)}, o), RoundingError);
  EXPECT_THROW(max_radius(box.V, box.F, {}, MaxRadiusOptions{}), RoundingError);
}

}  // namespace
}  // namespace meshround
