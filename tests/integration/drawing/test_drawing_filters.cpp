// "Line Drawing to Curves" and "Relief from Line Drawing" through the real meshlabserver: the
// nested synthetic drawing (known shapes and levels), an edited interpretation file, the three
// bases, the real drawings (tests/data/drawings: copies of ../shared/data/drawings), and bad input.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "bad_input.h"
#include "drawings.h"
#include "mesh_files.h"
#include "server.h"

using namespace rktest;
using reliefkit::Vec2;
using reliefkit::Vec3;

namespace {

const std::string kShared = rktest::source_dir() + "/tests/data/drawings";  // copies of ../shared/data/drawings

std::vector<std::string> drawing_params(const std::string& path, double dpi = 300, double scale = 1, double sigma = 0,
                                        bool shading = true) {
  return {param_file("drawing", path),  param_float("sigma", sigma), param_float("min_length", 12),
          param_bool("shading", shading),  param_float("outline_gap", 6), param_float("dpi", dpi),
          param_float("scale", scale)};
}
std::string curves_filter(const std::string& path, double dpi = 300, double scale = 1, double sigma = 0, double margins = 0) {
  auto p = drawing_params(path, dpi, scale, sigma);
  p.push_back(param_float("margins", margins));
  return mlx_filter("Line Drawing to Curves", p);
}
struct ReliefArgs {
  std::string interpretation;
  int ground = 0;
  int base = 0;
  Vec3 view = Vec3::Zero();
  double margin = 4, step = 0.5, cell = 0, dpi = 254, sigma = 0;  // the filter's defaults (0: automatic line scale)
  double shading_depth = 0;
  bool shading = true;
  int placement = 0;  // current layer: fitted (0) or as drawn (1)
};
std::vector<std::string> relief_params(const std::string& path, const ReliefArgs& a = {}) {
  auto p = drawing_params(path, a.dpi, 1, a.sigma, a.shading);
  p.push_back(param_file("interpretation", a.interpretation));
  p.push_back(param_enum("ground", a.ground, 2));
  p.push_back(param_enum("base", a.base, 3));
  p.push_back(param_point("view", a.view.x(), a.view.y(), a.view.z()));
  p.push_back(param_enum("placement", a.placement, 2));
  p.push_back(param_float("margin", a.margin));
  p.push_back(param_float("step_height", a.step));
  p.push_back(param_float("shading_depth", a.shading_depth));
  p.push_back(param_float("cell", a.cell));
  return p;
}
std::string relief_filter(const std::string& path, const ReliefArgs& a = {}) {
  return mlx_filter("Relief from Line Drawing", relief_params(path, a));
}

// The curves filter's parameters at their defaults; a parameter list with one float set to `value`.
std::vector<std::string> curves_params(const std::string& path) {
  auto p = drawing_params(path);
  p.push_back(param_float("margins", 0));
  return p;
}
std::vector<std::string> with_param(std::vector<std::string> params, const std::string& name, double value) {
  for (auto& p : params)
    if (p.find("name=\"" + name + "\"") != std::string::npos) p = param_float(name, value);
  return params;
}

// Runs a script without an input mesh (the filters make their layers from the drawing).
ServerRun run_script(const std::string& dir, const std::vector<std::string>& filters, std::vector<std::string> outputs,
                     const std::string& input = "") {
  write_text(dir + "/s.mlx", mlx_script(filters));
  for (size_t i = 0; i + 1 < outputs.size(); ++i)
    if (outputs[i] == "-o") outputs[i + 1] = dir + "/" + outputs[i + 1];
  std::vector<std::string> args;
  if (!input.empty()) args = {"-i", input};
  args.insert(args.end(), outputs.begin(), outputs.end());
  args.push_back("-s");
  args.push_back(dir + "/s.mlx");
  return run_meshlabserver(args);
}

std::string write_nested(const std::string& dir) {
  const std::string path = dir + "/nested.png";
  EXPECT_TRUE(cv::imwrite(path, nested_drawing()));
  return path;
}

// The number in "<N> curves" of the filter's log line.
int logged_curves(const std::string& out, const std::string& filter) {
  std::smatch m;
  if (std::regex_search(out, m, std::regex(filter + ": [^\\n]*?(\\d+) curves"))) return std::stoi(m[1]);
  return -1;
}

// The "step <x> mesh units" of the relief filter's log line.
double logged_step(const std::string& out) {
  std::smatch m;
  if (std::regex_search(out, m, std::regex("step ([0-9.eE+-]+) mesh units"))) return std::stod(m[1]);
  return -1;
}

// Height of a relief layer (vertex quality) at the vertex nearest to (x, y) in mesh units.
double height_near(const MeshFile& f, double x, double y) {
  double best = 1e300, h = 0;
  const auto& q = f.vertex_props.at("quality");
  for (size_t v = 0; v < f.mesh.vertices.size(); ++v) {
    const double d = std::hypot(f.mesh.vertices[v].x() - x, f.mesh.vertices[v].y() - y);
    if (d < best) best = d, h = q[v];
  }
  return h;
}

}  // namespace

TEST(DrawingFilters, CurvesOfTheNestedDrawingInMillimetres) {
  const std::string dir = temp_dir("drawing_curves");
  const std::string png = write_nested(dir);
  // 254 DPI = 0.1 mm per pixel; a drawing at 1:2: 0.2 mm per pixel on the object.
  ServerRun run = run_script(dir, {curves_filter(png, 254, 2, 2, 4)}, {"-o", "curves.obj", "-l", "0", "-o", "margins.obj", "-l", "1"});
  ASSERT_FALSE(run.crashed) << run.output;
  ASSERT_EQ(run.status, 0) << run.output;
  const int n = logged_curves(run.output, "Line Drawing to Curves");
  EXPECT_GE(n, 6) << run.output;
  EXPECT_LE(n, 8) << run.output;
  const MeshFile f = read_mesh(dir + "/curves.obj");
  ASSERT_GT(f.edges.size(), 1000u);
  double worst = 0;
  for (const Vec3& p : f.mesh.vertices) {
    EXPECT_EQ(p.z(), 0.0);
    worst = std::max(worst, nested_truth_distance(Vec2(p.x() / 0.2, -p.y() / 0.2)));
  }
  std::printf("[drawing filters, curves] %d curves, %zu points, worst distance to the drawn shapes %.2f px\n", n,
              f.mesh.vertices.size(), worst);
  EXPECT_LT(worst, 2.0);
  // The margins: 4 px either side of the shapes (away from corners and junctions, where offsets fold).
  const MeshFile mg = read_mesh(dir + "/margins.obj");
  ASSERT_GT(mg.edges.size(), 1000u);
  long near = 0;
  for (const Vec3& p : mg.mesh.vertices) near += std::abs(nested_truth_distance(Vec2(p.x() / 0.2, -p.y() / 0.2)) - 4) < 1.0;
  const double share = double(near) / mg.mesh.vertices.size();
  std::printf("[drawing filters, margins] %zu points, %.3f of them 4 +- 1 px from the shapes\n", mg.mesh.vertices.size(), share);
  EXPECT_GT(share, 0.9);
}

TEST(DrawingFilters, ReliefOfTheNestedDrawingHasItsLevels) {
  const std::string dir = temp_dir("drawing_relief");
  const std::string png = write_nested(dir);
  ReliefArgs a;  // 254 DPI: 0.1 mm per pixel
  ServerRun run = run_script(dir, {relief_filter(png, a)}, {"-o", "relief.ply", "-l", "0", "-m", "vq", "-o", "curves.obj", "-l", "1"});
  ASSERT_FALSE(run.crashed) << run.output;
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Interpretation written to"), std::string::npos) << run.output;
  ASSERT_TRUE(std::filesystem::exists(dir + "/nested.interpretation.json"));
  const MeshFile f = read_mesh(dir + "/relief.ply");
  const MeshFile c = read_mesh(dir + "/curves.obj");
  EXPECT_GT(c.edges.size(), 1000u);
  // One level: 0.5 % of the drawn part's width, as logged.
  const double step = logged_step(run.output);
  ASSERT_GT(step, 0) << run.output;
  EXPECT_NEAR(step, 0.005 * 0.1 * 563, 0.005 * 0.1 * 10);  // the curves' box (~523 px) + 2 x 20 px
  const NestedParts parts = nested_parts();
  auto level_at = [&](cv::Point px) { return height_near(f, px.x * 0.1, -px.y * 0.1) / step; };
  std::printf("[drawing filters, relief] %zu vertices; levels: object %.3f, disc %.3f, ring %.3f, inner %.3f, halves %.3f / %.3f\n",
              f.mesh.vertices.size(), level_at(parts.object), level_at(parts.disc), level_at(parts.ring), level_at(parts.inner),
              level_at(parts.left), level_at(parts.right));
  EXPECT_NEAR(level_at(parts.object), 1, 0.05);
  EXPECT_NEAR(level_at(parts.disc), 2, 0.05);
  EXPECT_NEAR(level_at(parts.ring), 2, 0.05);
  EXPECT_NEAR(level_at(parts.inner), 3, 0.05);
  EXPECT_NEAR(std::abs(level_at(parts.left) - level_at(parts.right)), 1, 0.05);
  // The relief's z is its height over the plane.
  for (size_t v = 0; v < f.mesh.vertices.size(); v += 97) EXPECT_NEAR(f.mesh.vertices[v].z(), f.vertex_props.at("quality")[v], 1e-4);

  // The thesis' ground: the region bordered by most curves (the object: 5 of them) is level 0, the
  // paper around it one step up (the object is then read as a sunken panel).
  {
    ReliefArgs t = a;
    t.ground = 1;
    ServerRun r2 = run_script(dir, {relief_filter(png, t)}, {"-o", "thesis.ply", "-l", "0", "-m", "vq"});
    ASSERT_EQ(r2.status, 0) << r2.output;
    const MeshFile g = read_mesh(dir + "/thesis.ply");
    const double s2 = logged_step(r2.output);
    const double object = height_near(g, parts.object.x * 0.1, -parts.object.y * 0.1) / s2,
                 paper = height_near(g, 1.0, -1.0) / s2, disc = height_near(g, parts.disc.x * 0.1, -parts.disc.y * 0.1) / s2;
    std::printf("[drawing filters, thesis ground] object %.3f, paper %.3f, disc %.3f\n", object, paper, disc);
    EXPECT_NEAR(object, 0, 0.05);
    EXPECT_NEAR(paper, 1, 0.05);
    EXPECT_NEAR(disc, 1, 0.05);
  }
  // The user edits the interpretation: the inner disc sunk into the ring (its curve's higher side
  // made the lower one). Then the filter reads it back and keeps the file as it is.
  nlohmann::json j;
  std::ifstream(dir + "/nested.interpretation.json") >> j;
  int edited = -1;
  for (auto& e : j["curves"]) {
    const Vec2 s(e["start"][0].get<double>(), e["start"][1].get<double>());
    if (std::abs((s - Vec2(420, 170)).norm() - 40) < 3 && e["step"].get<int>() != 0) {
      e["direction"] = e["step"].get<int>() > 0 ? "right-lower" : "left-lower";
      edited = e["id"].get<int>();
    }
  }
  ASSERT_GE(edited, 0);
  write_text(dir + "/sunk.json", j.dump(1));
  a.interpretation = dir + "/sunk.json";
  run = run_script(dir, {relief_filter(png, a)}, {"-o", "sunk.ply", "-l", "0", "-m", "vq"});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("1 curves fixed by the interpretation file"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("Interpretation written to"), std::string::npos) << run.output;
  const MeshFile g = read_mesh(dir + "/sunk.ply");
  ASSERT_NEAR(logged_step(run.output), step, 1e-9);
  const double ring = height_near(g, parts.ring.x * 0.1, -parts.ring.y * 0.1) / step,
               inner = height_near(g, parts.inner.x * 0.1, -parts.inner.y * 0.1) / step;
  std::printf("[drawing filters, sunk] ring %.3f, inner disc %.3f\n", ring, inner);
  EXPECT_NEAR(ring - inner, 1, 0.05);
}

TEST(DrawingFilters, CylinderAndCurrentLayerBases) {
  const std::string dir = temp_dir("drawing_bases");
  const std::string png = write_nested(dir);
  // Cylinder: circumference = the image's width (600 px x 0.1 mm); the relief rides on the radius.
  ReliefArgs a;
  a.base = 1;
  ServerRun run = run_script(dir, {relief_filter(png, a)}, {"-o", "cyl.ply", "-l", "0", "-m", "vq"});
  ASSERT_EQ(run.status, 0) << run.output;
  const MeshFile cyl = read_mesh(dir + "/cyl.ply");
  const double R = 60.0 / (2 * 3.14159265358979);
  double worst = 0;
  for (size_t v = 0; v < cyl.mesh.vertices.size(); ++v) {
    const Vec3& p = cyl.mesh.vertices[v];
    worst = std::max(worst, std::abs(std::hypot(p.x(), p.z()) - (R + cyl.vertex_props.at("quality")[v])));
  }
  std::printf("[drawing filters, cylinder] radius %.3f mm, worst |r - (R + h)| %.2e mm\n", R, worst);
  EXPECT_LT(worst, 1e-3);
  // Current layer: a plane in pixel units (x = px, y = -py) turned 90 degrees about z; the drawing
  // lands upright on it again (the layer's longer side takes the drawing's longer side).
  reliefkit::TriMesh plane = reliefkit::drawing_grid(561, 401, 2.0, 1.0, 20, 20);
  for (auto& v : plane.vertices) v = Vec3(-v.y(), v.x(), v.z());  // turned: +90 degrees about z
  write_ply(dir + "/base.ply", plane);
  a.base = 2;
  run = run_script(dir, {relief_filter(png, a)}, {"-o", "onbase.ply", "-l", "1", "-m", "vq"}, dir + "/base.ply");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Drawing projected along"), std::string::npos) << run.output;
  const MeshFile on = read_mesh(dir + "/onbase.ply");
  ASSERT_EQ(on.mesh.vertices.size(), plane.vertices.size());
  EXPECT_GT(on.mesh.faces.size(), 0u);
}

// Each real drawing gives a relief in which regions rise, at the default (automatic) line scale and,
// for the small cuneiform tablet, also at 1 px (at the former fixed default of 2 px nothing rose on
// it). Measured: replica 6, Qesem 16, cuneiform 4 (automatic) and 12 (1 px), bowl 8 regions rise.
TEST(DrawingFilters, RealDrawingsReconstruct) {
  struct Case {
    const char* file;
    double sigma;
    int lo, hi;  // plausible curve counts
    int rising;  // at least this many regions rise
  };
  for (const Case& cs : {Case{"lithic_replica_1.png", 0, 30, 200, 4}, Case{"lithic_qesem_cave.png", 0, 10, 100, 10},
                         Case{"cuneiform_P102630_obverse.png", 0, 40, 300, 2},
                         Case{"cuneiform_P102630_obverse.png", 1, 40, 300, 8},
                         Case{"pottery_bowl_half_section.jpg", 0, 10, 100, 5}}) {
    const std::string src = kShared + "/" + cs.file;
    ASSERT_TRUE(std::filesystem::exists(src)) << src;
    const std::string dir = temp_dir(std::string("drawing_real_") + std::to_string(int(cs.sigma)) + "_" + cs.file);
    const std::string png = dir + "/" + cs.file;
    std::filesystem::copy_file(src, png);  // the interpretation file is written beside the drawing
    ReliefArgs a;
    a.dpi = 300, a.sigma = cs.sigma, a.margin = cs.sigma == 1 ? 2 : 4;
    ServerRun run = run_script(dir, {relief_filter(png, a), curves_filter(png, 300, 1, cs.sigma)},  // relief: layer 0
                               {"-o", "relief.ply", "-l", "0", "-m", "vq", "-o", "curves.obj", "-l", "1"});
    ASSERT_FALSE(run.crashed) << run.output;
    ASSERT_EQ(run.status, 0) << run.output;
    const int n = logged_curves(run.output, "Line Drawing to Curves");
    std::smatch m;
    std::regex_search(run.output, m, std::regex("Relief from Line Drawing: [^\\n]*?levels 0 to (\\d+), (\\d+) regions rise"));
    ASSERT_EQ(m.size(), 3u) << run.output;
    std::printf("[drawing filters, %s, line scale %g] %d curves, levels 0 to %s, %s regions rise\n", cs.file, cs.sigma, n,
                m[1].str().c_str(), m[2].str().c_str());
    EXPECT_GE(n, cs.lo) << cs.file;
    EXPECT_LE(n, cs.hi) << cs.file;
    EXPECT_GE(std::stoi(m[2]), cs.rising) << cs.file;
    const MeshFile f = read_mesh(dir + "/relief.ply");
    EXPECT_GT(f.mesh.faces.size(), 10000u) << cs.file;
    for (const Vec3& p : f.mesh.vertices) ASSERT_TRUE(std::isfinite(p.z())) << cs.file;
  }
}

// Issue 23: a crop of the shared plate of stone tools through meshlabserver at the defaults: the
// hatching goes to its own layer "– shading", objects' outlines are closed, the relief stays
// between the ground and half a step above its top level; with shading engraved the relief dips
// along the strokes; with Recognise shading unticked nothing is taken for shading. Measured: 872
// curves, 502 shading, 69 outline pieces, 20 regions rise; heights -0.001 to 2.08 steps.
TEST(DrawingFilters, APlateRisesWithItsShadingInItsOwnLayer) {
  const std::string dir = temp_dir("drawing_plate");
  const std::string png = dir + "/plate.jpg";
  std::filesystem::copy_file(kShared + "/lithic_plate_morar_quartz_crop.jpg", png);
  ReliefArgs a;
  a.dpi = 300;
  ReliefArgs engraved = a, lines = a;
  engraved.shading_depth = 0.2;
  lines.shading = false;
  ServerRun run = run_script(dir, {relief_filter(png, a), relief_filter(png, engraved), relief_filter(png, lines)},
                             {"-o", "relief.ply", "-l", "0", "-m", "vq", "-o", "shading.obj", "-l", "2", "-o",
                              "engraved.ply", "-l", "3", "-m", "vq"});
  ASSERT_FALSE(run.crashed) << run.output;
  ASSERT_EQ(run.status, 0) << run.output;
  std::smatch m;
  const std::regex logged("(\\d+) of the curves recognised as shading[^\\n]*?, (\\d+) outline pieces added");
  std::vector<std::pair<int, int>> found;
  for (auto it = std::sregex_iterator(run.output.begin(), run.output.end(), logged); it != std::sregex_iterator(); ++it)
    found.emplace_back(std::stoi((*it)[1]), std::stoi((*it)[2]));
  ASSERT_GE(found.size(), 3u) << run.output;
  ASSERT_TRUE(std::regex_search(run.output, m, std::regex("levels 0 to (\\d+), (\\d+) regions rise[^\\n]*?step ([0-9.e+-]+) mesh")))
      << run.output;
  const int top = std::stoi(m[1]);
  const double step = std::stod(m[3]);
  const MeshFile relief = read_mesh(dir + "/relief.ply"), engraved_relief = read_mesh(dir + "/engraved.ply");
  const MeshFile shading = read_mesh(dir + "/shading.obj");
  const auto& q = relief.vertex_props.at("quality");
  const auto [lo, hi] = std::minmax_element(q.begin(), q.end());
  const auto& qe = engraved_relief.vertex_props.at("quality");
  const double deepest = *std::min_element(qe.begin(), qe.end());
  std::printf("[plate crop through meshlabserver] shading %d, outline pieces %d, %s regions rise, levels 0 to %d; heights "
              "%.3f to %.3f steps; shading layer %zu edges; engraved: lowest %.3f steps; unticked: %d shading\n",
              found[0].first, found[0].second, m[2].str().c_str(), top, *lo / step, *hi / step, shading.edges.size(),
              deepest / step, found.back().first);
  EXPECT_GE(found[0].first, 300);
  EXPECT_GE(found[0].second, 20);
  EXPECT_GE(std::stoi(m[2]), 14);
  EXPECT_GE(*lo / step, -2e-3);
  EXPECT_LE(*hi / step, top + 0.5 + 2e-3);
  EXPECT_GT(shading.edges.size(), 1000u);
  EXPECT_LT(deepest / step, -0.1);
  EXPECT_EQ(found.back().first, 0);  // the last run's (meshlabserver repeats the log as it goes)
}

TEST(DrawingFilters, BadInputStopsWithAClearMessage) {
  const std::string dir = temp_dir("drawing_bad");
  const std::string png = write_nested(dir);
  struct Case {
    std::string what, filter, expect;
  };
  write_text(dir + "/garbage.png", "not a PNG at all");
  write_text(dir + "/empty.png", "");
  cv::imwrite(dir + "/white.png", cv::Mat(300, 300, CV_8UC1, cv::Scalar(255)));
  cv::imwrite(dir + "/one.png", cv::Mat(1, 1, CV_8UC1, cv::Scalar(0)));
  // Hatching alone: parallel strokes with free ends close no region, so nothing can rise.
  cv::Mat hatching(300, 300, CV_8UC1, cv::Scalar(255));
  for (int k = 0; k < 8; ++k) cv::line(hatching, {60 + 25 * k, 60}, {40 + 25 * k, 240}, cv::Scalar(0), 2, cv::LINE_AA);
  cv::imwrite(dir + "/hatching.png", hatching);
  write_text(dir + "/unknown.json", R"({"format": "reliefkit-drawing-interpretation", "curves": [{"id": 999}]})");
  write_text(dir + "/notjson.json", "{curves: oops");
  // A cycle: three rays from a disc's centre, each fixed with the sector on its left the lower one
  // (seen going outwards), so that going round the centre each sector is below the next.
  cv::Mat sectors(400, 400, CV_8UC1, cv::Scalar(255));
  cv::circle(sectors, {200, 200}, 150, cv::Scalar(0), 2, cv::LINE_AA);
  for (double deg : {-90.0, 30.0, 150.0}) {
    const double r = deg * 3.14159265358979 / 180;
    cv::line(sectors, {200, 200}, {int(200 + 150 * std::cos(r)), int(200 + 150 * std::sin(r))}, cv::Scalar(0), 2, cv::LINE_AA);
  }
  cv::imwrite(dir + "/sectors.png", sectors);
  ServerRun first = run_script(dir, {relief_filter(dir + "/sectors.png")}, {"-o", "sectors.ply", "-l", "0"});
  ASSERT_EQ(first.status, 0) << first.output;
  nlohmann::json j;
  std::ifstream(dir + "/sectors.interpretation.json") >> j;
  int rays = 0;
  for (auto& e : j["curves"]) {
    const Vec2 s(e["start"][0].get<double>(), e["start"][1].get<double>()), t(e["end"][0].get<double>(), e["end"][1].get<double>());
    const double ds = (s - Vec2(200, 200)).norm(), dt = (t - Vec2(200, 200)).norm();
    if (std::min(ds, dt) < 20 && std::max(ds, dt) > 100) {
      e["direction"] = ds < dt ? "left-lower" : "right-lower";
      ++rays;
    }
  }
  ASSERT_EQ(rays, 3);
  write_text(dir + "/cycle.json", j.dump(1));
  std::filesystem::remove(dir + "/sectors.interpretation.json");

  auto relief_with = [&](const std::string& drawing, const std::string& interp) {
    ReliefArgs a;
    a.interpretation = interp;
    return relief_filter(drawing, a);
  };
  ReliefArgs current;
  current.base = 2;
  const std::vector<Case> cases = {
      {"missing drawing", curves_filter(dir + "/nowhere.png"), "does not exist"},
      {"no drawing given", curves_filter(""), "No drawing image was given"},
      {"unreadable drawing", curves_filter(dir + "/garbage.png"), "not an image"},
      {"empty file", curves_filter(dir + "/empty.png"), "not an image"},
      {"all-white drawing", curves_filter(dir + "/white.png"), "No lines were found"},
      {"1 x 1 drawing", relief_filter(dir + "/one.png"), "No lines were found"},
      {"hatching only: a flat relief", relief_filter(dir + "/hatching.png"), "8 recognised as shading"},
      {"negative outline gap", mlx_filter("Line Drawing to Curves", with_param(curves_params(png), "outline_gap", -1)),
       "Outline gaps closed"},
      {"NaN shading depth", mlx_filter("Relief from Line Drawing", with_param(relief_params(png), "shading_depth", std::nan(""))),
       "Shading engraved"},
      {"NaN line scale", curves_filter(png, 300, 1, std::nan("")), "Line scale"},
      {"negative DPI", curves_filter(png, -3), "DPI"},
      {"cycle", relief_with(dir + "/sectors.png", dir + "/cycle.json"), "contradict each other"},
      {"unknown curve", relief_with(png, dir + "/unknown.json"), "names curve 999"},
      {"not JSON", relief_with(png, dir + "/notjson.json"), "not valid JSON"},
      {"missing interpretation", relief_with(png, dir + "/nowhere.json"), "does not exist"},
      {"current layer without a mesh", relief_filter(png, current), "needs a mesh layer"},
  };
  for (const Case& c : cases) {
    const std::string out = "out_" + std::to_string(&c - cases.data()) + ".obj";
    ServerRun run = run_script(dir, {c.filter}, {"-o", out});
    EXPECT_FALSE(run.crashed) << c.what << "\n" << run.output;
    EXPECT_NE(run.output.find(c.expect), std::string::npos) << c.what << "\n" << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/" + out)) << c.what << ": nothing may be written";
  }
  // Nothing written beside the drawings either.
  EXPECT_FALSE(std::filesystem::exists(dir + "/sectors.interpretation.json"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/nested.interpretation.json"));
}

namespace {
// An example script with its relative paths (examples/...) made absolute.
std::string example(const std::string& name) {
  std::ifstream f(rktest::source_dir() + "/examples/" + name);
  std::stringstream ss;
  ss << f.rdbuf();
  std::string s = ss.str();
  for (size_t at = 0; (at = s.find("value=\"examples/", at)) != std::string::npos;)
    s.replace(at, 7, "value=\"" + rktest::source_dir() + "/"), at += 8;
  return s;
}
}  // namespace

// The example scripts run as written (every parameter listed), the sunk-disc interpretation file
// of examples/data still names this extraction's curves, and the relief on a base layer scales
// with the base: the same script for a base in millimetres and in metres.
TEST(DrawingFilters, ExampleScriptsRunAndFollowTheBasesUnit) {
  const std::string dir = temp_dir("drawing_examples");
  const std::string png = dir + "/nested_drawing.png";
  std::filesystem::copy_file(rktest::source_dir() + "/examples/data/nested_drawing.png", png);
  auto local = [&](std::string s) {  // the drawing in the test's folder (its interpretation file is written there)
    const std::string from = rktest::source_dir() + "/examples/data/nested_drawing.png";
    for (size_t at = 0; (at = s.find(from, at)) != std::string::npos;) s.replace(at, from.size(), png), at += png.size();
    return s;
  };
  write_text(dir + "/curves.mlx", local(example("drawing_curves.mlx")));
  ServerRun run = run_meshlabserver({"-o", dir + "/curves.obj", "-s", dir + "/curves.mlx"});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(logged_curves(run.output, "Line Drawing to Curves"), 6) << run.output;

  std::string relief = local(example("drawing_relief.mlx"));
  const std::string sunk = rktest::source_dir() + "/examples/data/nested_drawing.sunk.json";
  relief.replace(relief.find("name=\"interpretation\" value=\"\""), 30, "name=\"interpretation\" value=\"" + sunk + "\"");
  write_text(dir + "/relief.mlx", relief);
  run = run_meshlabserver({"-o", dir + "/sunk.ply", "-l", "0", "-m", "vq", "-s", dir + "/relief.mlx"});
  ASSERT_EQ(run.status, 0) << run.output;
  const MeshFile f = read_mesh(dir + "/sunk.ply");
  const double px = 25.4 / 300, step = logged_step(run.output);
  const NestedParts parts = nested_parts();
  const double ring = height_near(f, parts.ring.x * px, -parts.ring.y * px) / step,
               inner = height_near(f, parts.inner.x * px, -parts.inner.y * px) / step;
  std::printf("[drawing examples] sunk.json: ring %.3f, inner disc %.3f levels\n", ring, inner);
  EXPECT_NEAR(ring - inner, 1, 0.05);

  write_text(dir + "/onlayer.mlx", local(example("drawing_on_layer.mlx")));
  std::map<double, double> top;
  for (double unit : {1.0, 1000.0}) {
    reliefkit::TriMesh dome = reliefkit::drawing_grid(800, 600, 2.0, 1.0);
    for (auto& v : dome.vertices) {
      const double x = v.x() - 400, y = v.y() + 300, R = 1200;
      v = unit * Vec3(v.x(), v.y(), std::sqrt(R * R - x * x - y * y) - R);
    }
    const std::string base = dir + "/dome" + std::to_string(int(unit)) + ".ply";
    write_ply(base, dome);
    run = run_meshlabserver({"-i", base, "-o", dir + "/on" + std::to_string(int(unit)) + ".ply", "-l", "1", "-m", "vq", "-s",
                             dir + "/onlayer.mlx"});
    ASSERT_EQ(run.status, 0) << run.output;
    const MeshFile on = read_mesh(dir + "/on" + std::to_string(int(unit)) + ".ply");
    double hi = 0;
    for (double h : on.vertex_props.at("quality")) hi = std::max(hi, h);
    top[unit] = hi;
  }
  std::printf("[drawing examples] on a dome: highest relief %.4g (mm) / %.4g (m x 1000)\n", top[1.0], top[1000.0]);
  EXPECT_GT(top[1.0], 0);
  EXPECT_NEAR(top[1000.0] / top[1.0], 1000, 1);
}

// The current layer as the base: the damaged meshes every ReliefKit filter is tested on.
TEST(DrawingFilters, BadBaseLayersAreHandled) {
  const std::string dir = temp_dir("drawing_bad_base_png");
  const std::string png = write_nested(dir);
  ReliefArgs a;
  a.base = 2;
  expect_bad_input_handled([&](const std::string& name, const reliefkit::TriMesh& mesh) {
    return run_filters("drawing_bad_base_" + name, mesh, {relief_filter(png, a)}, {"-o", "out.ply", "-l", "1"});
  });
}
