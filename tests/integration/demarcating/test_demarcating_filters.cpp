// "Demarcating Curves" and "Curvature Shading" through the real meshlabserver.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "bad_input.h"
#include "reliefkit/demarcating/demarcating.h"
#include "mesh_files.h"
#include "reliefkit/base/scale.h"
#include "reliefs.h"
#include "server.h"
#include "shapes.h"

using namespace rktest;

namespace {

std::string demarcating_filter(double threshold = 1, const std::string& presmoothing = "auto", double min_length = 4,
                               bool per_vertex = true, bool quality = false, double lift = 0) {
  return mlx_filter("Demarcating Curves",
                    {param_float("threshold", threshold), param_string("presmoothing", presmoothing),
                     param_float("min_length", min_length), param_bool("per_vertex", per_vertex),
                     param_bool("quality", quality), param_float("lift", lift)});
}

std::string shading_filter(const std::string& presmoothing = "auto", bool darken = true) {
  return mlx_filter("Curvature Shading", {param_float("contrast", 1), param_bool("darken", darken),
                                          param_float("darkness", 0.6), param_float("threshold", 1),
                                          param_string("presmoothing", presmoothing)});
}

}  // namespace

TEST(DemarcatingFilter, CurveLayerLiesOnTheStep) {
  ReliefShape s;
  s.noise = 0.1;
  Relief r = disc_on_plane(s, 120);
  std::string dir;
  ServerRun run =
      run_filters("demarcating_plane", r.mesh, {demarcating_filter()}, {"-o", "curves.obj", "-l", "1"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("in \u2013 demarcating curves"), std::string::npos) << run.output;
  MeshFile curves = read_mesh(dir + "/curves.obj");
  ASSERT_GT(curves.edges.size(), 100u);
  Detection d = score(r, polylines_of(curves), r.mean_edge);
  EXPECT_GE(d.recall, 0.85);
  EXPECT_GE(d.precision, 0.80);
}

TEST(DemarcatingFilter, ShadingIsLightOnTheShoulderDarkAtTheFoot) {
  Relief r = disc_on_plane({}, 120);
  std::string dir;
  ServerRun run =
      run_filters("shading_plane", r.mesh, {shading_filter("auto", false)}, {"-o", "out.ply", "-m", "vc"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  MeshFile out = read_mesh(dir + "/out.ply");
  const auto& red = out.vertex_props["red"];
  ASSERT_EQ(red.size(), out.mesh.vertices.size());
  double shoulder = 0, foot = 0, flat = 0;
  int ns = 0, nf = 0, nflat = 0;
  for (size_t i = 0; i < red.size(); ++i) {
    double rad = std::hypot(out.mesh.vertices[i].x(), out.mesh.vertices[i].y());
    if (std::abs(rad - 0.47) < 0.01) shoulder += red[i], ++ns;  // convex (R0 - ~w)
    if (std::abs(rad - 0.53) < 0.01) foot += red[i], ++nf;      // concave (R0 + ~w)
    if (rad < 0.2) flat += red[i], ++nflat;
  }
  ASSERT_GT(ns, 10);
  ASSERT_GT(nf, 10);
  EXPECT_GT(shoulder / ns, 160);
  EXPECT_LT(foot / nf, 95);
  EXPECT_NEAR(flat / nflat, 127.5, 10);
}

TEST(DemarcatingFilter, MainJobScriptOnTheCoin) {
  std::string dir = temp_dir("coin_demarcating");
  ServerRun run = run_meshlabserver({"-i", rktest::source_dir() + "/examples/data/penny.ply", "-o",
                                     dir + "/shaded.ply", "-l", "0", "-m", "vc", "-o", dir + "/curves.obj", "-l",
                                     "1", "-s", rktest::source_dir() + "/examples/demarcating_shading.mlx"});
  ASSERT_EQ(run.status, 0) << run.output;
  MeshFile curves = read_mesh(dir + "/curves.obj");
  MeshFile shaded = read_mesh(dir + "/shaded.ply");
  EXPECT_GT(curves.edges.size(), 1000u);
  ASSERT_EQ(shaded.vertex_props["red"].size(), 49977u);
  // Every curve point lies on the coin: lifted off its surface by the script's 0.2 edge lengths
  // along the normal, so its distance to the nearest triangle is that lift (less only where the
  // surface bends within the lift). Measured: 0.163 to 0.200 edge lengths.
  const double h = reliefkit::mesh_scale(shaded.mesh).edge;
  const std::vector<double> d = distance_to_surface(shaded.mesh, curves.mesh.vertices, 2 * h);
  const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
  std::printf("curve points' distance to the coin: %.3f to %.3f edge lengths\n", *lo / h, *hi / h);
  EXPECT_GE(*lo, 0.1 * h);
  EXPECT_LE(*hi, 0.201 * h);
  // ... and they are where the core draws them on the same scan (a curve shifted along the surface
  // keeps its distance to it): every point within the lift of a core point, and back.
  const reliefkit::TriMesh penny = read_mesh(rktest::source_dir() + "/examples/data/penny.ply").mesh;
  const reliefkit::DemarcatingResult core = reliefkit::compute_demarcating(penny, {});
  auto matched = [&](const std::vector<reliefkit::Vec3>& from, const std::vector<reliefkit::Vec3>& to) {
    size_t near = 0;
    for (const auto& p : from) {
      double best = 1e300;
      for (const auto& q : to) best = std::min(best, (p - q).squaredNorm());
      near += best <= std::pow(0.21 * h, 2);
    }
    return double(near) / from.size();
  };
  const double precision = matched(curves.mesh.vertices, core.curves.points);
  const double recall = matched(core.curves.points, curves.mesh.vertices);
  std::printf("against the core: recall %.4f, precision %.4f\n", recall, precision);
  EXPECT_GE(recall, 0.999);
  EXPECT_GE(precision, 0.999);
}

// ---- bad input, both filters ----

class DemarcatingBadInput : public ::testing::TestWithParam<int> {
 protected:
  ServerRun run(const std::string& name, const reliefkit::TriMesh& m) {
    std::string f = GetParam() == 0 ? demarcating_filter() : shading_filter();
    return run_filters(name + std::to_string(GetParam()), m, {f}, {"-o", "out.ply", "-m", "vc"});
  }
};

TEST_P(DemarcatingBadInput, ClearMessageOrSuccessNeverACrash) {
  expect_bad_input_handled([this](const std::string& name, const reliefkit::TriMesh& m) { return run(name, m); });
}

INSTANTIATE_TEST_SUITE_P(BothFilters, DemarcatingBadInput, ::testing::Values(0, 1));
