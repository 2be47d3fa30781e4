// "Unroll Around Axis" through the real meshlabserver: an embossed cylinder (a seal) of known
// geometry in a random pose unrolled and as its impression (the layer's size, its heights, the
// log), a curve layer unrolled with it, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "bad_input.h"
#include "mesh_files.h"
#include "server.h"
#include "shapes.h"
#include "turned.h"

using namespace rktest;
using reliefkit::Vec3;

namespace {

std::string unroll_filter(bool impression = false, int base = 1, double repeat = 0) {
  return mlx_filter("Unroll Around Axis",
                    {param_enum("axis_mode", 0, 3), param_point("axis_point", 0, 0, 0), param_point("axis_direction", 0, 0, 1),
                     param_enum("base", base, 2), param_enum("development", 0, 2), param_float("base_window", 0), param_bool("seam_auto", true),
                     param_float("seam_angle", 0), param_bool("impression", impression), param_float("repeat", repeat),
                     param_float("smoothing", 3)});
}

Turned seal() {
  TurnedOptions o;
  o.irregular = true, o.edge = 0.6, o.seed = 2;
  return make_turned(o);
}

}  // namespace

TEST(UnrollFilter, SealUnrolledAndItsImpression) {
  const Turned t = seal();
  for (bool impression : {false, true}) {
    SCOPED_TRACE(impression);
    std::string dir;
    const ServerRun run = run_filters(impression ? "unroll_impression" : "unroll", t.mesh, {unroll_filter(impression)},
                                      {"-o", "out.ply", "-l", "1", "-m", "vq"}, &dir);
    ASSERT_EQ(run.status, 0) << run.output;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(run.output, m, std::regex("circumference ([0-9.]+)"))) << run.output;
    EXPECT_NEAR(std::stod(m[1]), 2 * M_PI * 15, 0.01 * 2 * M_PI * 15);
    EXPECT_EQ(run.output.find("Seal impression:") != std::string::npos, impression) << run.output;
    const MeshFile out = read_mesh(dir + "/out.ply");
    ASSERT_GE(out.mesh.n_vertices(), t.mesh.n_vertices());  // the input's, then the seam's copies
    double low = INFINITY, high = -INFINITY, top = -INFINITY, bottom = INFINITY;
    for (const Vec3& p : out.mesh.vertices)
      low = std::min(low, p.x()), high = std::max(high, p.x()), top = std::max(top, p.z()), bottom = std::min(bottom, p.z());
    EXPECT_NEAR(high - low, 2 * M_PI * 15, 0.02 * 2 * M_PI * 15);  // one sheet, the circumference wide
    // the relief's heights: 0.2 mm bumps up on the rollout, down on the impression
    EXPECT_NEAR(impression ? -bottom : top, 0.2, 0.03);
    EXPECT_NEAR(impression ? top : -bottom, 0, 0.03);
  }
}

TEST(UnrollFilter, CurveLayersAreUnrolledWithTheMesh) {
  const Turned t = seal();
  // A curve layer of the mesh: the plane cut square to the axis through its middle.
  const reliefkit::Polylines ring = reliefkit::plane_cut(t.mesh, t.axis_direction, t.axis_point.dot(t.axis_direction));
  ASSERT_GT(ring.segments.size(), 50u);
  const std::string dir = temp_dir("unroll_curves");
  write_ply(dir + "/in.ply", t.mesh);
  std::string obj;
  for (const Vec3& p : ring.points) obj += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  for (const auto& s : ring.segments) obj += "l " + std::to_string(s[0] + 1) + " " + std::to_string(s[1] + 1) + "\n";
  const std::string curve_file = dir + "/in \u2013 ring.obj";  // named as a curve layer of the mesh "in"
  write_text(curve_file, obj);
  write_text(dir + "/s.mlx", mlx_script({unroll_filter()}));
  const ServerRun run = run_meshlabserver({"-i", curve_file, "-i", dir + "/in.ply", "-s", dir + "/s.mlx", "-o", dir + "/curves.obj", "-l", "3"});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("1 curve layer(s) unrolled"), std::string::npos) << run.output;
  const MeshFile curves = read_mesh(dir + "/curves.obj");
  double low = INFINITY, high = -INFINITY;
  for (const Vec3& p : curves.mesh.vertices) {
    low = std::min(low, p.x()), high = std::max(high, p.x());
    EXPECT_NEAR(p.y(), 0, 0.5);  // the middle parallel: a straight line across the sheet
  }
  EXPECT_NEAR(high - low, 2 * M_PI * 15, 0.02 * 2 * M_PI * 15);
}

// One script, as a seal scholar would run it: the impression with a quarter turn repeated, its
// demarcating curves, its plate — to scale along the circumference, the seam dash-dot, the title.
TEST(UnrollFilter, PlateOfTheImpressionShowsTheSeamTheRepeatAndItsName) {
  const Turned t = seal();
  const std::string curves = mlx_filter("Demarcating Curves", {param_float("threshold", 1), param_string("presmoothing", "auto"),
                                                               param_float("min_length", 4), param_bool("per_vertex", true),
                                                               param_bool("quality", false), param_float("lift", 0)});
  const std::string plate = mlx_filter(
      "Export Illustration Plate",
      {param_save_file("file", "impression.svg", "*.svg"), param_bool("pdf", true), param_string("layers", "all"),
       param_enum("view", 0, 4), param_point("direction", 0, 0, -1), param_enum("layout", 0, 5), param_bool("turn_over", false),
       param_bool("upside_down", false), param_string("reverse_layer", ""), param_float("unit_mm", 1), param_float("ratio", 0),
       param_enum("shading", 0, 8), param_float("light_azimuth", 315), param_float("light_elevation", 20),
       param_float("openness_radius", 10), param_int("light_stack", 0), param_int("dpi", 100), param_float("width", 0.35), param_enum("weights", 0, 3),
       param_enum("section", 0, 3), param_bool("section_fill", true), param_float("section_at", 0.5), param_enum("page", 0, 3)});
  std::string dir;
  const ServerRun run = run_filters("unroll_plate", t.mesh, {unroll_filter(true, 1, 0.25), curves, plate}, {}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Repeat: 25 % of a turn"), std::string::npos) << run.output;
  std::ifstream f(dir + "/impression.svg");
  std::stringstream svg;
  svg << f.rdbuf();
  const std::string text = svg.str();
  ASSERT_FALSE(text.empty()) << run.output;
  EXPECT_NE(text.find(">Seal impression (rollout mirrored, relief inverted)</text>"), std::string::npos);
  EXPECT_NE(text.find("25 % of a turn repeated past the seam"), std::string::npos);
  // The object's width on the plate's log: a circumference and a quarter (94.25 mm x 1.25).
  std::smatch m;
  ASSERT_TRUE(std::regex_search(run.output, m, std::regex("the object ([0-9.]+) x ([0-9.]+) mm"))) << run.output;
  const double circumference = 2 * M_PI * 15;
  EXPECT_NEAR(std::stod(m[1]), 1.25 * circumference, 0.02 * circumference);
  // The two seam lines, dash-dot, a circumference apart on the page at the plate's scale.
  ASSERT_TRUE(std::regex_search(run.output, m, std::regex("mm at ([0-9]+):([0-9]+)"))) << run.output;
  const double ratio = std::stod(m[1]) / std::stod(m[2]);
  const std::regex dashed(R"(<path stroke-width="[0-9.]+" stroke-dasharray="3 1 0.5 1"[^>]* d="M([0-9.]+),)");
  std::vector<double> xs;
  for (std::sregex_iterator it(text.begin(), text.end(), dashed), end; it != end; ++it) xs.push_back(std::stod((*it)[1]));
  ASSERT_EQ(xs.size(), 2u) << run.output;
  EXPECT_NEAR(std::abs(xs[1] - xs[0]), ratio * circumference, 0.01 * ratio * circumference);
}

TEST(UnrollFilter, BadInputAndShapesThatTurnAboutNoAxis) {
  expect_bad_input_handled(
      [](const std::string& name, const reliefkit::TriMesh& mesh) {
        return run_filters("unroll_bad_" + name, mesh, {unroll_filter()}, {"-o", "out.ply"});
      },
      "normals are nearly parallel", "no wall to unroll");
  const ServerRun sphere_run = run_filters("unroll_sphere", rktest::sphere(30, 4, 0.1), {unroll_filter()}, {"-o", "out.ply"});
  EXPECT_FALSE(sphere_run.crashed);
  EXPECT_NE(sphere_run.status, 0);
  EXPECT_NE(sphere_run.output.find("fit"), std::string::npos) << sphere_run.output;
}
