// "Vessel from Profile Drawing" through the real meshlabserver: a synthetic half-section with a known
// profile (size in millimetres from DPI and scale), the shared bowl (base missing), the example
// script, and bad input.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mesh_files.h"
#include "server.h"
#include "vessels.h"

using namespace rktest;
using reliefkit::Vec2;
using reliefkit::Vec3;

namespace {

std::string vessel_filter(const std::string& path, double dpi = 300, double scale = 1, double axis = -1, int side = 0,
                          int segments = 0) {
  return mlx_filter("Vessel from Profile Drawing",
                    {param_file("drawing", path), param_float("dpi", dpi), param_float("scale", scale),
                     param_float("axis", axis), param_enum("side", side, 3), param_int("segments", segments)});
}

ServerRun run_vessel(const std::string& dir, const std::string& filter, const std::vector<std::string>& outputs) {
  write_text(dir + "/s.mlx", mlx_script({filter}));
  std::vector<std::string> args;
  for (const std::string& o : outputs) args.push_back(o.rfind('-', 0) == 0 || o.size() < 3 ? o : dir + "/" + o);
  args.push_back("-s");
  args.push_back(dir + "/s.mlx");
  return run_meshlabserver(args);
}

}  // namespace

// A hatched half-section at 254 dpi drawn 1:2: 0.2 mm per pixel. The vessel's height and widest
// radius in millimetres, its profile layer, and the log's reading.
TEST(VesselFilter, SyntheticHalfSectionInMillimetres) {
  const std::string dir = temp_dir("vessel_synthetic");
  VesselDrawingOptions o;
  o.style = SectionStyle::Hatched;
  const VesselDrawing d = vessel_drawing(o);
  ASSERT_TRUE(cv::imwrite(dir + "/jar.png", d.image));
  ServerRun run = run_vessel(dir, vessel_filter(dir + "/jar.png", 254, 2),
                             {"-o", "vessel.ply", "-l", "1", "-m", "vq", "-o", "profile.obj", "-l", "0"});
  ASSERT_FALSE(run.crashed) << run.output;
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("hatched section on the left of the axis"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("the base closes on the axis"), std::string::npos) << run.output;
  const MeshFile v = read_mesh(dir + "/vessel.ply");
  double lo = 1e300, hi = -1e300, widest = 0, true_widest = 0;
  for (const Vec3& p : v.mesh.vertices) lo = std::min(lo, p.y()), hi = std::max(hi, p.y());
  for (double r : v.vertex_props.at("quality")) widest = std::max(widest, r);
  for (const Vec2& q : d.section) true_widest = std::max(true_widest, q.x());
  const double mm = 0.2;
  std::printf("[vessel filter] height %.2f mm (drawn %.2f), widest radius %.2f mm (drawn %.2f)\n", hi - lo, d.height * mm,
              widest, true_widest * mm);
  EXPECT_NEAR(hi - lo, d.height * mm, 0.01 * d.height * mm);
  EXPECT_NEAR(widest, true_widest * mm, 0.01 * d.height * mm);
  const MeshFile profile = read_mesh(dir + "/profile.obj");
  EXPECT_GT(profile.edges.size(), 50u);
}

// The shared bowl: section outlined on the left, its base broken off — the vessel stays open there.
TEST(VesselFilter, ThePotteryBowl) {
  const std::string dir = temp_dir("vessel_bowl");
  ServerRun run = run_vessel(
      dir, vessel_filter(source_dir() + "/tests/data/drawings/pottery_bowl_half_section.jpg"), {"-o", "bowl.ply", "-l", "1"});
  ASSERT_FALSE(run.crashed) << run.output;
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("outlined section on the left of the axis"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("the base is not drawn"), std::string::npos) << run.output;
  EXPECT_GT(read_mesh(dir + "/bowl.ply").mesh.faces.size(), 10000u);
}

TEST(VesselFilter, ExampleScriptRuns) {
  const std::string dir = temp_dir("vessel_example");
  std::ifstream f(source_dir() + "/examples/vessel_from_profile.mlx");
  std::stringstream ss;
  ss << f.rdbuf();
  std::string s = ss.str();
  for (size_t at = 0; (at = s.find("value=\"examples/", at)) != std::string::npos;)
    s.replace(at, 7, "value=\"" + source_dir() + "/"), at += 8;
  write_text(dir + "/s.mlx", s);
  ServerRun run = run_meshlabserver({"-o", dir + "/v.ply", "-l", "1", "-s", dir + "/s.mlx"});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Vessel from Profile Drawing: "), std::string::npos) << run.output;
}

TEST(VesselFilter, BadInputStopsWithAClearMessage) {
  const std::string dir = temp_dir("vessel_bad");
  cv::imwrite(dir + "/white.png", cv::Mat(300, 300, CV_8UC1, cv::Scalar(255)));
  cv::imwrite(dir + "/black.png", cv::Mat(300, 300, CV_8UC1, cv::Scalar(0)));
  cv::Mat line(300, 300, CV_8UC1, cv::Scalar(255));
  cv::line(line, {20, 150}, {280, 150}, cv::Scalar(0), 2);
  cv::imwrite(dir + "/line.png", line);
  write_text(dir + "/garbage.png", "not a PNG");
  cv::imwrite(dir + "/jar.png", vessel_drawing().image);
  struct Case {
    std::string what, filter, expect;
  };
  const std::vector<Case> cases = {
      {"no drawing given", vessel_filter(""), "No drawing image was given"},
      {"missing drawing", vessel_filter(dir + "/nowhere.png"), "does not exist"},
      {"unreadable drawing", vessel_filter(dir + "/garbage.png"), "not an image"},
      {"blank drawing", vessel_filter(dir + "/white.png"), "blank"},
      {"all dark", vessel_filter(dir + "/black.png"), "dark"},
      {"a lone line", vessel_filter(dir + "/line.png"), "No vessel profile"},
      {"axis outside", vessel_filter(dir + "/jar.png", 300, 1, 5000), "outside the drawing"},
      {"zero DPI", vessel_filter(dir + "/jar.png", 0), "DPI"},
      {"too few segments", vessel_filter(dir + "/jar.png", 300, 1, -1, 0, 3), "Segments"},
      {"a stone tool, not a vessel", vessel_filter(source_dir() + "/tests/data/drawings/lithic_qesem_cave.png"), "does not look like a vessel"},
      {"NaN DPI", vessel_filter(dir + "/jar.png", std::nan("")), "DPI"},
  };
  for (const Case& c : cases) {
    const std::string out = "out_" + std::to_string(&c - cases.data()) + ".ply";
    ServerRun run = run_vessel(dir, c.filter, {"-o", out});
    EXPECT_FALSE(run.crashed) << c.what << "\n" << run.output;
    EXPECT_NE(run.output.find(c.expect), std::string::npos) << c.what << "\n" << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/" + out)) << c.what << ": nothing may be written";
  }
}
