// "Vessel Axis and Profile" through the real meshlabserver: a synthetic rim sherd of known axis in
// a random pose (the mesh moved onto the axis with its vertices in order, the profile layer, the
// log's record), an axis given and turned over, and bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>

#include "bad_input.h"
#include "mesh_files.h"
#include "server.h"
#include "shapes.h"
#include "sherds.h"

using namespace rktest;
using reliefkit::Vec3;

namespace {

std::string vessel_axis_filter(int mode = 0, const Vec3& point = Vec3::Zero(), const Vec3& direction = Vec3::UnitZ(),
                               bool flip = false) {
  return mlx_filter("Vessel Axis and Profile",
                    {param_enum("axis_mode", mode, 2), param_point("axis_point", point.x(), point.y(), point.z()),
                     param_point("axis_direction", direction.x(), direction.y(), direction.z()), param_bool("flip", flip),
                     param_float("smoothing", 3)});
}

Sherd rim_sherd() {
  SherdOptions o;
  o.span_deg = 108, o.from = 0.7, o.noise = 0.1, o.irregular = true, o.edge = 1;
  return make_sherd(o);
}

// The rigid motion taking the input's vertices to the output's (they keep their order).
Eigen::Isometry3d motion(const reliefkit::TriMesh& in, const reliefkit::TriMesh& out) {
  Eigen::Matrix3Xd a(3, in.n_vertices()), b(3, out.n_vertices());
  for (int i = 0; i < in.n_vertices(); ++i) a.col(i) = in.vertices[size_t(i)], b.col(i) = out.vertices[size_t(i)];
  return Eigen::Isometry3d(Eigen::umeyama(a, b, false));
}

}  // namespace

TEST(VesselAxisFilter, RimSherdTurnedOntoItsAxisWithItsProfileAndRecord) {
  const Sherd sh = rim_sherd();
  std::string dir;
  const ServerRun run = run_filters("vessel_axis", sh.mesh, {vessel_axis_filter()},
                                    {"-o", "out.ply", "-m", "vq", "-o", "profile.obj", "-l", "1"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.output, m, std::regex("Rim diameter ([0-9.]+)"))) << run.output;
  EXPECT_NEAR(std::stod(m[1]), sh.rim_diameter, 0.01 * sh.rim_diameter);  // measured 0.1 %
  ASSERT_TRUE(std::regex_search(run.output, m, std::regex("EVE ([0-9.]+)"))) << run.output;
  EXPECT_NEAR(std::stod(m[1]), 0.30, 0.02);
  EXPECT_NE(run.output.find("Up: the rim"), std::string::npos) << run.output;
  const MeshFile in = read_mesh(dir + "/in.ply"), out = read_mesh(dir + "/out.ply");
  ASSERT_EQ(out.mesh.n_vertices(), in.mesh.n_vertices());
  const Eigen::Isometry3d t = motion(in.mesh, out.mesh);
  EXPECT_GT((t.linear() * sh.axis_direction).z(), std::cos(0.5 * M_PI / 180));  // the axis is +Z, rim up
  const Vec3 foot = t * sh.axis_point;
  EXPECT_LT(foot.head<2>().norm(), 0.01 * sh.largest_radius);  // through the origin
  // vertex quality: the distance from the surface of revolution, small on the wall
  const auto& q = out.vertex_props.at("quality");
  std::vector<double> magnitude;
  for (double d : q) magnitude.push_back(std::abs(d));
  EXPECT_LT(percentile(magnitude, 0.5), 0.2);
  // the profile layer: in the plane y = 0, x = radius >= 0, within the piece's heights
  const MeshFile profile = read_mesh(dir + "/profile.obj");
  ASSERT_GT(profile.mesh.n_vertices(), 50);
  for (const Vec3& p : profile.mesh.vertices) {
    EXPECT_NEAR(p.y(), 0, 1e-3);
    EXPECT_GE(p.x(), -1e-3);
  }
}

TEST(VesselAxisFilter, AGivenAxisIsUsedAsGivenAndFlipTurnsThePieceOver) {
  const Sherd sh = rim_sherd();
  std::string dir;
  const ServerRun run = run_filters("vessel_axis_given", sh.mesh, {vessel_axis_filter(1, sh.axis_point, sh.axis_direction, true)},
                                    {"-o", "out.ply"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("as given"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("turned over, as asked"), std::string::npos) << run.output;
  const Eigen::Isometry3d t = motion(read_mesh(dir + "/in.ply").mesh, read_mesh(dir + "/out.ply").mesh);
  EXPECT_LT((t.linear() * sh.axis_direction).z(), -std::cos(0.01));  // rim down, as asked
}

TEST(VesselAxisFilter, BadInputAndShapesThatTurnAboutNoAxis) {
  expect_bad_input_handled(
      [](const std::string& name, const reliefkit::TriMesh& mesh) {
        return run_filters("vessel_axis_bad_" + name, mesh, {vessel_axis_filter()}, {"-o", "out.ply"});
      },
      "normals are nearly parallel");  // the relief on a plane (a disc) turns about its axis: it is taken
  const ServerRun sphere_run = run_filters("vessel_axis_sphere", rktest::sphere(30, 4, 0.1), {vessel_axis_filter()}, {"-o", "out.ply"});
  EXPECT_FALSE(sphere_run.crashed);
  EXPECT_NE(sphere_run.status, 0);
  EXPECT_NE(sphere_run.output.find("fit"), std::string::npos) << sphere_run.output;
}

TEST(VesselAxisFilter, ThePotteryExampleWritesTheSherdsPlate) {
  std::string dir;
  const ServerRun run = run_filters("pottery_plate", rim_sherd().mesh, {}, {"-o", "out.ply"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;  // the sherd written as in.ply; now the example script on it
  const ServerRun plate = run_meshlabserver({"-i", dir + "/in.ply", "-s", source_dir() + "/examples/pottery.mlx"});
  ASSERT_EQ(plate.status, 0) << plate.output;
  EXPECT_NE(plate.output.find("Pottery plate: Rim diameter"), std::string::npos) << plate.output;
  EXPECT_NE(plate.output.find("at 1:1 (automatic)"), std::string::npos) << plate.output;
  std::ifstream svg(dir + "/in-plate.svg");
  const std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("<g id=\"section\""), std::string::npos);
  EXPECT_NE(text.find("fill=\"black"), std::string::npos);     // the section filled
  EXPECT_NE(text.find("stroke-dasharray"), std::string::npos);  // the axis dash-dot
  EXPECT_NE(text.find("57 mm, 31 %"), std::string::npos) << text.substr(0, 400);
  EXPECT_TRUE(std::filesystem::exists(dir + "/in-plate.pdf"));
}
