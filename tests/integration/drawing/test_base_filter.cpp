// "Base from Drawing Silhouette" through the real meshlabserver: a lamp drawn in front and top
// view finds a lamp of the shipped library and fits its outlines; a cylinder made a goblet; the
// example chaining the base and "Relief from Line Drawing"; a folder of the user's models; bad input.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "bases.h"
#include "mesh_files.h"
#include "reliefkit/drawing/line_drawing.h"
#include "server.h"

using namespace rktest;
using namespace reliefkit;

namespace {

struct BaseArgs {
  std::string views = "front";
  double dpi = 300, scale = 1, alpha = 1, gap = 0;
  std::string library, user_models, model;
  int passes = 10, matches = 5;
  bool round = false;
};
std::string base_filter(const std::string& drawing, const BaseArgs& a = {}) {
  return mlx_filter("Base from Drawing Silhouette",
                    {param_file("drawing", drawing), param_string("views", a.views), param_float("dpi", a.dpi),
                     param_float("scale", a.scale), param_string("library", a.library),
                     param_string("user_models", a.user_models), param_string("model", a.model),
                     param_bool("round", a.round), param_float("alpha", a.alpha), param_int("passes", a.passes), param_float("gap", a.gap),
                     param_int("matches", a.matches)});
}

ServerRun run_script(const std::string& dir, const std::vector<std::string>& filters, std::vector<std::string> outputs) {
  write_text(dir + "/s.mlx", mlx_script(filters));
  for (size_t i = 0; i + 1 < outputs.size(); ++i)
    if (outputs[i] == "-o") outputs[i + 1] = dir + "/" + outputs[i + 1];
  outputs.push_back("-s");
  outputs.push_back(dir + "/s.mlx");
  return run_meshlabserver(outputs);
}

// The drawing's outline in a view, in millimetres (view coordinates), as the filter reads it.
Outline outline_mm(const std::string& png, int index_in_reading_order, int count, double dpi = 300) {
  auto all = drawing_outlines(drawing_grey(cv::imread(png, cv::IMREAD_UNCHANGED)), cv::Rect(), count);
  std::sort(all.begin(), all.end(), [](const DrawingOutline& a, const DrawingOutline& b) { return a.box.y < b.box.y; });
  Outline o;
  for (const auto& p : all[size_t(index_in_reading_order)].outline) o.push_back(Vec2(p.x() * 25.4 / dpi, -p.y() * 25.4 / dpi));
  return o;
}

// The class of the best match the log lists.
std::string first_match(const std::string& log) {
  std::smatch m;
  if (std::regex_search(log, m, std::regex("Best matches of \\d+ models[^:]*: 1\\. ([A-Za-z0-9_]+) \\(([a-z]+)\\)"))) return m[2];
  return "";
}

}  // namespace

TEST(BaseFilter, LampDrawingFindsALampAndFitsItsOutlines) {
  const std::string dir = temp_dir("base_lamp");
  const std::string png = dir + "/lamp.png";
  std::filesystem::copy_file(rktest::source_dir() + "/examples/data/lamp_figure.png", png);
  BaseArgs a;
  a.views = "front; top";
  ServerRun run = run_script(dir, {base_filter(png, a)}, {"-o", "retrieved.ply", "-l", "0", "-o", "base.ply", "-l", "1", "-m", "vq"});
  ASSERT_FALSE(run.crashed) << run.output;
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(first_match(run.output), "lamp") << run.output;
  const MeshFile base = read_mesh(dir + "/base.ply");
  const MeshFile retrieved = read_mesh(dir + "/retrieved.ply");
  ASSERT_EQ(base.mesh.n_vertices(), retrieved.mesh.n_vertices());
  // The base's silhouettes against the drawing's outlines, in millimetres.
  const std::vector<ViewOutline> views = {{ViewKind::Front, outline_mm(png, 0, 2)}, {ViewKind::Top, outline_mm(png, 1, 2)}};
  const double before = silhouette_error(retrieved.mesh, views), after = silhouette_error(base.mesh, views);
  std::printf("[base filter] lamp drawing: silhouettes off by %.2f %% (retrieved, placed) -> %.2f %% (deformed)\n",
              100 * before, 100 * after);
  EXPECT_LT(after, 0.01);
  EXPECT_LT(after, before);
  // Vertex quality: how far each vertex moved.
  double worst = 0;
  for (int i = 0; i < base.mesh.n_vertices(); ++i)
    worst = std::max(worst, std::abs(base.vertex_props.at("quality")[size_t(i)] -
                                     (base.mesh.vertices[size_t(i)] - retrieved.mesh.vertices[size_t(i)]).norm()));
  EXPECT_LT(worst, 1e-3);
}

TEST(BaseFilter, CylinderBecomesTheGoblet) {
  // Thesis fig. 7.10 (a), from the goblet's front view alone: with the thesis' kept depth (the
  // default) the stem stays as deep as the cylinder; taken as round, the outline is the side view too.
  const std::string dir = temp_dir("base_goblet");
  std::mt19937 rng(1);
  cv::imwrite(dir + "/goblet.png", draw_figure(goblet_outline(), {}, rng));
  const Outline drawn = outline_mm(dir + "/goblet.png", 0, 1);
  double front[2], side[2];
  for (int round = 1; round >= 0; --round) {
    BaseArgs a;
    a.model = "cylinder_05";
    a.round = round;
    ServerRun run = run_script(dir, {base_filter(dir + "/goblet.png", a)}, {"-o", "base.ply", "-l", "1"});
    ASSERT_EQ(run.status, 0) << run.output;
    EXPECT_NE(run.output.find("cylinder_05 (cylinder"), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("taken as round") != std::string::npos, bool(round)) << run.output;
    const MeshFile base = read_mesh(dir + "/base.ply");
    front[round] = silhouette_error(base.mesh, {{ViewKind::Front, drawn}});
    side[round] = silhouette_error(base.mesh, {{ViewKind::Side, drawn}});
  }
  std::printf("[base filter] cylinder -> goblet: front / side view off by %.2f / %.2f %% (round), %.2f / %.2f %% (depth kept)\n",
              100 * front[1], 100 * side[1], 100 * front[0], 100 * side[0]);
  EXPECT_LT(std::max(front[1], side[1]), 0.08);  // measured 6.7 / 4.7 %: the drawn corners rounded
  EXPECT_LT(front[0], 0.04);                     // measured 1.6 %
  EXPECT_GT(side[0], 0.3);                       // the cylinder's depth: 74 %
}

TEST(BaseFilter, ExampleChainsBaseAndRelief) {
  // examples/base_and_relief.mlx as written, its drawings copied to the test's folder (the relief
  // filter writes its interpretation file beside the drawing).
  const std::string dir = temp_dir("base_example");
  for (const char* f : {"lamp_figure.png", "nested_drawing.png"})
    std::filesystem::copy_file(rktest::source_dir() + "/examples/data/" + f, dir + "/" + f);
  std::ifstream in(rktest::source_dir() + "/examples/base_and_relief.mlx");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string script = ss.str();
  const std::string from = "value=\"examples/data/";
  for (size_t at = 0; (at = script.find(from, at)) != std::string::npos;) {
    script.replace(at, from.size(), "value=\"" + dir + "/");
    at += 8;
  }
  write_text(dir + "/s.mlx", script);
  ServerRun run = run_meshlabserver({"-o", dir + "/base.ply", "-l", "1", "-o", dir + "/relief.ply", "-l", "2", "-m", "vq", "-s",
                                     dir + "/s.mlx"});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(first_match(run.output), "lamp") << run.output;
  const MeshFile base = read_mesh(dir + "/base.ply"), relief = read_mesh(dir + "/relief.ply");
  double hi = 0;
  for (double h : relief.vertex_props.at("quality")) hi = std::max(hi, h);
  std::printf("[base filter] example: base %d vertices (Loop-subdivided), relief %d vertices, highest step %.3g mm\n",
              base.mesh.n_vertices(), relief.mesh.n_vertices(), hi);
  EXPECT_GT(hi, 0);
  EXPECT_GT(base.mesh.n_vertices(), 40000);
  // The relief lies on the base: every relief vertex within its height (and a little) of the base's box.
  Vec3 lo = base.mesh.vertices[0], up = lo;
  for (const auto& p : base.mesh.vertices) { lo = lo.cwiseMin(p); up = up.cwiseMax(p); }
  for (const auto& p : relief.mesh.vertices)
    ASSERT_TRUE(((p - lo).array() > -(hi + 1e-3)).all() && ((up - p).array() > -(hi + 1e-3)).all());
}

TEST(BaseFilter, ACutDrawingIsFlagged) {
  // The real cuneiform drawing (tests/data/drawings): the tablet's outline runs into the image's
  // border and no base model fits it; the base is still written, with both warnings in the log.
  const std::string dir = temp_dir("base_cut");
  ServerRun run = run_script(
      dir, {base_filter(rktest::source_dir() + "/tests/data/drawings/cuneiform_P102630_obverse.png")},
      {"-o", "base.ply", "-l", "1"});
  ASSERT_FALSE(run.crashed) << run.output;
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("outline touches the border of its image"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Warning: the base stays"), std::string::npos) << run.output;
  // The lamp figure raises neither.
  const std::string png = dir + "/lamp.png";
  std::filesystem::copy_file(rktest::source_dir() + "/examples/data/lamp_figure.png", png);
  BaseArgs a;
  a.views = "front; top";
  run = run_script(dir, {base_filter(png, a)}, {"-o", "lamp.ply", "-l", "1"});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(run.output.find("Warning:"), std::string::npos) << run.output;
}

TEST(BaseFilter, UserModelsAndBadInput) {
  const std::string dir = temp_dir("base_bad");
  std::mt19937 rng(2);
  cv::imwrite(dir + "/goblet.png", draw_figure(goblet_outline(), {}, rng));
  // A folder of the user's models (a cup in a class folder, a bowl), searched without the library.
  std::filesystem::create_directories(dir + "/mine/cups");
  write_model_ply(dir + "/mine/cups/my_cup.ply", make_base_model(standard_base_specs(1)[2]));
  write_model_ply(dir + "/mine/my_bowl.ply", make_base_model(standard_base_specs(1)[1]));
  BaseArgs mine;
  mine.library = "none";
  mine.user_models = dir + "/mine";
  ServerRun run = run_script(dir, {base_filter(dir + "/goblet.png", mine)}, {"-o", "mine.ply", "-l", "1"});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Best matches of 2 models"), std::string::npos) << run.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/mine/" + kFeatureCache));

  // Bad input: a clear message, nothing written.
  cv::Mat stroke(300, 300, CV_8UC1, cv::Scalar(255));
  cv::line(stroke, {20, 150}, {280, 160}, cv::Scalar(0), 3);
  cv::imwrite(dir + "/stroke.png", stroke);
  write_text(dir + "/garbage.png", "not a PNG");
  std::filesystem::create_directories(dir + "/empty");
  std::filesystem::create_directories(dir + "/broken");
  write_text(dir + "/broken/a.ply", "ply\nformat ascii 1.0\nelement vertex 3\nend_header\n1 2\n");
  write_text(dir + "/broken/b.obj", "v 0 0 0\n");
  auto with = [&](auto change) {
    BaseArgs a;
    change(a);
    return a;
  };
  struct Case {
    std::string what, filter, expect;
  };
  const std::string g = dir + "/goblet.png";
  const std::vector<Case> cases = {
      {"no closed outline", base_filter(dir + "/stroke.png"), "No closed outline"},
      {"missing image", base_filter(dir + "/nowhere.png"), "does not exist"},
      {"unreadable image", base_filter(dir + "/garbage.png"), "not an image"},
      {"no image given", base_filter(""), "No drawing image was given"},
      {"empty library folder", base_filter(g, with([&](BaseArgs& a) { a.library = dir + "/empty"; })), "library is empty"},
      {"missing library folder", base_filter(g, with([&](BaseArgs& a) { a.library = dir + "/nowhere"; })), "does not exist"},
      {"unreadable models only",
       base_filter(g, with([&](BaseArgs& a) { a.library = "none"; a.user_models = dir + "/broken"; })), "library is empty"},
      {"unknown view", base_filter(g, with([&](BaseArgs& a) { a.views = "back"; })), "is not a view"},
      {"two views, one outline", base_filter(g, with([&](BaseArgs& a) { a.views = "front; top"; })), "separate outlines"},
      {"region outside", base_filter(g, with([&](BaseArgs& a) { a.views = "front = 5000 5000 100 100"; })), "outside"},
      {"unknown model", base_filter(g, with([&](BaseArgs& a) { a.model = "teapot_01"; })), "no model named"},
      {"NaN alpha", base_filter(g, with([&](BaseArgs& a) { a.alpha = std::nan(""); })), "alpha"},
      {"zero passes", base_filter(g, with([&](BaseArgs& a) { a.passes = 0; })), "Passes"},
  };
  for (const Case& c : cases) {
    const std::string out = "out_" + std::to_string(&c - cases.data()) + ".ply";
    run = run_script(dir, {c.filter}, {"-o", out});
    EXPECT_FALSE(run.crashed) << c.what << "\n" << run.output;
    EXPECT_NE(run.output.find(c.expect), std::string::npos) << c.what << "\n" << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/" + out)) << c.what << ": nothing may be written";
  }
}
