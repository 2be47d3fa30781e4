// The pottery plate (make_pottery_plate with pottery_sheet): a synthetic jar and a rim sherd on
// their axes — the axis dash-dot, the section filled left of it at the true scale, the exterior
// right of it, the rim line and the rim diameter written, the scale chosen among 1:1, 1:2...
#include <gtest/gtest.h>

#include <algorithm>

#include "reliefkit/illustration/plate.h"
#include "sherds.h"

using namespace reliefkit;

namespace {

struct Drawn {
  rktest::Sherd sherd;
  VesselRecord record;
  Plate plate;
};
Drawn draw(double span, double from) {
  rktest::SherdOptions o;
  o.span_deg = span, o.from = from, o.noise = 0.1, o.irregular = true, o.edge = 1;
  Drawn d{rktest::make_sherd(o), {}, {}};
  d.record = record_vessel(Surface(d.sherd.mesh));
  d.plate = make_pottery_plate(oriented_mesh(d.sherd.mesh, d.record), {}, {}, pottery_sheet(d.record), PlateParams{});
  return d;
}

const PlatePath* path_of(const Plate& p, const std::string& layer) {
  for (const PlatePath& path : p.paths)
    if (path.layer == layer) return &path;
  return nullptr;
}

}  // namespace

TEST(PotteryPlate, WholeJarInHalfSection) {
  const Drawn d = draw(360, 0);
  EXPECT_EQ(d.plate.scale_label, "1:1");  // a 100 mm jar fits A4 at 1:1; never enlarged
  const PlatePath* axis = path_of(d.plate, "axis");
  ASSERT_NE(axis, nullptr);
  EXPECT_TRUE(axis->dash_dot);
  const double axis_x = axis->points[0].x();
  EXPECT_NEAR(axis->points[1].x(), axis_x, 1e-9);
  // The section: filled, wholly left of the axis, as wide as the jar's largest radius (1:1, mm).
  const PlatePath* section = path_of(d.plate, "section");
  ASSERT_NE(section, nullptr);
  EXPECT_TRUE(section->filled);
  double left = INFINITY, right = -INFINITY;
  for (const PlatePath& p : d.plate.paths)
    if (p.layer == "section")
      for (const Vec2& q : p.points) left = std::min(left, q.x()), right = std::max(right, q.x());
  EXPECT_LE(right, axis_x + 1e-6);
  EXPECT_NEAR(axis_x - left, d.sherd.largest_radius, 0.02 * d.sherd.largest_radius);
  // The exterior (its shading raster) starts at the axis: the right half of the jar.
  // Faces across the axis reach beyond it by up to their longest edge (irregular, 1 mm nominal).
  EXPECT_NEAR(d.plate.drawing_origin_mm.x(), axis_x, 1.5);
  EXPECT_NEAR(d.plate.drawing_size_mm.x(), d.sherd.largest_radius, 0.03 * d.sherd.largest_radius);
  // The rim line across both halves and the diameter written.
  const PlatePath* rim = path_of(d.plate, "rim line");
  ASSERT_NE(rim, nullptr);
  EXPECT_NEAR(rim->points[1].x() - rim->points[0].x(), d.sherd.rim_diameter, 0.01 * d.sherd.rim_diameter);
  ASSERT_EQ(d.plate.texts.size(), 1u);
  EXPECT_NE(d.plate.texts[0].text.find("57 mm, 100 %"), std::string::npos) << d.plate.texts[0].text;
  EXPECT_NE(plate_svg(d.plate).find("57 mm, 100 %"), std::string::npos);
}

TEST(PotteryPlate, RimSherdBesideItsProfile) {
  const Drawn d = draw(108, 0.7);
  const double axis_x = path_of(d.plate, "axis")->points[0].x();
  const PlatePath* rim = path_of(d.plate, "rim line");
  ASSERT_NE(rim, nullptr);
  EXPECT_NEAR(rim->points[1].x(), axis_x, 1e-9);  // a sherd's rim line runs from its profile to the axis
  EXPECT_NEAR(axis_x - rim->points[0].x(), d.sherd.rim_diameter / 2, 0.01 * d.sherd.rim_diameter);
  EXPECT_NE(d.plate.texts.at(0).text.find("31 %"), std::string::npos) << d.plate.texts[0].text;
  EXPECT_GE(d.plate.drawing_origin_mm.x(), axis_x - 1e-6);  // the exterior right of the axis
}

TEST(PotteryPlate, NoProfileIsRefused) {
  EXPECT_THROW(make_pottery_plate(rktest::make_sherd({}).mesh, {}, {}, PotterySheet{}, PlateParams{}), InputError);
}
