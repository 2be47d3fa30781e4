// "Compute Optimal Scale", "Optimally Smoothed Surface", "Multi-scale Ridges and Valleys" and
// "Multi-scale Relief Edges" through the real meshlabserver, against known answers and against
// the cores on the same mesh.
#include <gtest/gtest.h>

#include <cmath>

#include "bad_input.h"
#include "mesh_files.h"
#include "reliefkit/multiscale/multiscale.h"
#include "reliefs.h"
#include "server.h"
#include "shapes.h"

using namespace rktest;

namespace {

std::vector<std::string> scale_range() {
  return {param_string("min_scale", "auto"), param_string("max_scale", "auto"), param_int("levels", 2)};
}
std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}
std::string optimal_filter(int curve = 0) {
  return mlx_filter("Compute Optimal Scale",
                    with(with({param_enum("curve", curve, 2)}, scale_range()), {param_bool("quality", true)}));
}
std::string smoothed_filter() {
  return mlx_filter("Optimally Smoothed Surface",
                    with(with({param_enum("curve", 0, 2)}, scale_range()), {param_string("final_smoothing", "auto")}));
}
std::string ridges_filter() {
  return mlx_filter("Multi-scale Ridges and Valleys",
                    with(with({param_float("threshold", 1), param_float("min_length", reliefkit::kMultiscaleMinLengthEdges)}, scale_range()),
                         {param_float("lift", 0)}));
}
std::string relief_filter() {
  return mlx_filter("Multi-scale Relief Edges",
                    with(with({param_float("min_length", 2), param_float("gap", 3)}, scale_range()),
                         {param_float("lift", 0)}));
}

// The unit test's noisy cylinder (tests/unit/multiscale/test_multiscale.cpp), shorter, with one fine valley
// (Gaussian of 0.35 edge lengths, at arc 0) and one coarse valley (5 edge lengths, at arc 1.2).
constexpr int kAround = 1800;
const double kH = 2 * M_PI / kAround;
AxialCylinder grooved_cylinder() {
  return axial_cylinder({{AxialFeature::Valley, 0.37 * kH, 0.35 * kH, 2 * kH, 0, 0},
                         {AxialFeature::Valley, 1.2, 5 * kH, 2 * kH, 0, 1}},
                        kAround, 0.15, 0.2);
}

// Values at the vertices within half an edge of a line's arc (z away from the rims).
std::vector<double> along(const MeshFile& f, const std::vector<double>& q, double arc) {
  std::vector<double> v;
  for (size_t i = 0; i < q.size(); ++i) {
    const auto& p = f.mesh.vertices[i];
    if (std::abs(std::remainder(std::atan2(p.y(), p.x()) - arc, 2 * M_PI)) < 0.5 * kH && std::abs(p.z()) < 0.05)
      v.push_back(q[i]);
  }
  return v;
}

}  // namespace

TEST(MultiscaleFilters, OptimalScaleFollowsEachGroovesWidth) {
  const AxialCylinder c = grooved_cylinder();
  std::string dir;
  ServerRun run = run_filters("ms_optimal", c.mesh, {optimal_filter()}, {"-o", "out.ply", "-m", "vq"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Optimal scale (edge lengths, share of vertices)"), std::string::npos) << run.output;
  MeshFile out = read_mesh(dir + "/out.ply");
  const auto& q = out.vertex_props["quality"];
  ASSERT_EQ(q.size(), out.mesh.vertices.size());
  const double fine = median(along(out, q, c.features[0].arc)), coarse = median(along(out, q, c.features[1].arc));
  std::printf("scale at the fine valley %.2f, at the coarse one %.2f edge lengths\n", fine, coarse);
  // Measured 1.3 and 6.5 (the core: 1.3-1.7 and 6.4-6.6 on the longer cylinder): the coarse
  // valley's scale is about sqrt(2) x its width (4.4 mean edge lengths).
  EXPECT_LT(fine, 2.5);
  EXPECT_NEAR(coarse, std::sqrt(2.0) * 5 * kH / c.edge, 1.5);
}

TEST(MultiscaleFilters, SmoothedSurfaceIsANewLayerThatKeepsTheFineValley) {
  const AxialCylinder c = grooved_cylinder();
  std::string dir;
  ServerRun run = run_filters("ms_smoothed", c.mesh, {smoothed_filter()},
                              {"-o", "in.out.ply", "-l", "0", "-o", "smoothed.ply", "-l", "1"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  MeshFile orig = read_mesh(dir + "/in.out.ply"), sm = read_mesh(dir + "/smoothed.ply");
  ASSERT_EQ(sm.mesh.vertices.size(), c.mesh.vertices.size());
  for (size_t i = 0; i < c.mesh.vertices.size(); i += 37)  // the input layer is untouched
    EXPECT_NEAR(orig.mesh.vertices[i].z(), c.mesh.vertices[i].z(), 1e-6);
  // Far from both valleys the noise is gone (radius deviation from its median); the fine valley
  // keeps most of its depth (2 edge lengths; a single scale of 2 edge lengths leaves 0.4).
  std::vector<double> r_in, r_sm, bottom;
  for (size_t i = 0; i < c.mesh.vertices.size(); ++i) {
    const auto &p = c.mesh.vertices[i], &s = sm.mesh.vertices[i];
    const double a = std::atan2(p.y(), p.x());
    if (std::abs(std::remainder(a - 3.0, 2 * M_PI)) < 0.3 && std::abs(p.z()) < 0.05)
      r_in.push_back(p.head<2>().norm()), r_sm.push_back(s.head<2>().norm());
  }
  auto spread = [](std::vector<double> v) { return percentile(v, 0.9) - percentile(v, 0.1); };
  for (size_t i = 0; i < c.mesh.vertices.size(); ++i) {
    const auto& p = c.mesh.vertices[i];
    if (std::abs(std::remainder(std::atan2(p.y(), p.x()) - c.features[0].arc, 2 * M_PI)) < 0.5 * kH &&
        std::abs(p.z()) < 0.05)
      bottom.push_back(1 - sm.mesh.vertices[i].head<2>().norm());
  }
  std::printf("background spread %.2e -> %.2e; fine valley depth %.2f edge lengths\n", spread(r_in), spread(r_sm),
              median(bottom) / c.edge);
  EXPECT_LT(spread(r_sm), 0.2 * spread(r_in));
  EXPECT_GT(median(bottom) / kH, 0.8);
}

TEST(MultiscaleFilters, RidgesAndValleysMatchTheCoreAndFindBothValleys) {
  const AxialCylinder c = grooved_cylinder();
  std::string dir;
  ServerRun run = run_filters("ms_ridges", c.mesh, {ridges_filter()},
                              {"-o", "ridges.obj", "-l", "1", "-o", "valleys.obj", "-l", "2"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  MeshFile valleys = read_mesh(dir + "/valleys.obj");
  ASSERT_GT(valleys.edges.size(), 50u);
  const reliefkit::Polylines server = polylines_of(valleys);
  const AxialScore sc = score_axial(c, server, {AxialFeature::Valley}, 0.005, 3 * c.edge);
  std::printf("valleys: recall fine %.4f coarse %.4f, precision %.4f\n", sc.recall[0], sc.recall[1], sc.precision);
  // Measured: recall 1.000 / 1.000, precision 0.984 (was asserted 0.9 / 0.9 / 0.8).
  EXPECT_GE(sc.recall[0], 0.99);
  EXPECT_GE(sc.recall[1], 0.99);
  EXPECT_GE(sc.precision, 0.95);
  // The same curves as the core computes on the same (saved) mesh with the filter's options (its
  // largest scale "auto": lowered on small objects; with a fixed 16 edge lengths the valleys differ).
  reliefkit::OptimalScaleOptions options;
  options.max_scale_auto = true;
  const reliefkit::MultiscaleRidgeValleys core =
      reliefkit::multiscale_ridges_valleys(read_mesh(dir + "/in.ply").mesh, options);
  // Each one's points lie on the other's segments (the file stores single precision).
  Relief core_points, server_points;
  core_points.boundary = core.curves.valleys.points;
  server_points.boundary = server.points;
  const double found = score(core_points, server, 0.01 * c.edge).recall;
  const double kept = score(server_points, core.curves.valleys, 0.01 * c.edge).recall;
  std::printf("meshlabserver valleys against the core's: recall %.4f precision %.4f\n", found, kept);
  EXPECT_GE(found, 0.999);
  EXPECT_GE(kept, 0.999);
}

TEST(MultiscaleFilters, ReliefEdgesOnANoisyCylinder) {
  ReliefShape s;
  s.noise = 0.1;
  Relief r = discs_on_cylinder(s);
  std::string dir;
  ServerRun run = run_filters("ms_relief", r.mesh, {relief_filter()}, {"-o", "edges.obj", "-l", "1"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  MeshFile edges = read_mesh(dir + "/edges.obj");
  ASSERT_GT(edges.edges.size(), 100u);
  Detection d = score(r, polylines_of(edges), r.mean_edge);
  std::printf("relief edges: recall %.4f precision %.4f\n", d.recall, d.precision);
  // Measured: 1.000 / 1.000 (was asserted 0.9 / 0.9).
  EXPECT_GE(d.recall, 0.99);
  EXPECT_GE(d.precision, 0.99);
}

TEST(MultiscaleFilters, TooSmallAMeshStopsWithAMessageAndChangesNothing) {
  // 5 x 5 cells: about 7 edge lengths across, less than 8 smallest scales of 1 edge length.
  const reliefkit::TriMesh tiny = height_field([](double, double) { return 0.0; }, 1.0, 5);
  for (const std::string& f : {optimal_filter(), smoothed_filter(), ridges_filter(), relief_filter()}) {
    ServerRun run = run_filters("ms_tiny", tiny, {f}, {"-o", "out.ply"});
    EXPECT_FALSE(run.crashed) << run.output;
    EXPECT_NE(run.output.find("too small for a scale range"), std::string::npos) << run.output;
  }
}

TEST(MultiscaleFilters, BadParametersStopWithAClearMessage) {
  const reliefkit::TriMesh m = height_field([](double x, double) { return 0.1 * x * x; }, 1.0, 30);
  const struct {
    std::string filter, expect;
  } cases[] = {
      {mlx_filter("Compute Optimal Scale", {param_enum("curve", 0, 2), param_string("min_scale", "auto"),
                                            param_string("max_scale", "auto"), param_int("levels", 99),
                                            param_bool("quality", true)}),
       "Scales per doubling"},
      {mlx_filter("Compute Optimal Scale", {param_enum("curve", 7, 2), param_string("min_scale", "auto"),
                                            param_string("max_scale", "auto"), param_int("levels", 2),
                                            param_bool("quality", true)}),
       "Curves the scale is for"},
      {mlx_filter("Multi-scale Ridges and Valleys",
                  with(with({param_float("threshold", std::nan("")), param_float("min_length", reliefkit::kMultiscaleMinLengthEdges)}, scale_range()),
                       {param_float("lift", 0)})),
       "Strength threshold"},
      {mlx_filter("Multi-scale Relief Edges", {param_float("min_length", 2), param_float("gap", 3),
                                               param_string("min_scale", "4"), param_string("max_scale", "lots"),
                                               param_int("levels", 2), param_float("lift", 0)}),
       "Largest scale"},
  };
  for (const auto& c : cases) {
    ServerRun run = run_filters("ms_badparam", m, {c.filter}, {"-o", "out.ply"});
    EXPECT_FALSE(run.crashed) << run.output;
    EXPECT_NE(run.output.find(c.expect), std::string::npos) << c.expect << ": " << run.output;
  }
}

class MultiscaleBadInput : public ::testing::TestWithParam<int> {};

TEST_P(MultiscaleBadInput, ClearMessageOrSuccessNeverACrash) {
  const int which = GetParam();
  const std::string f = which == 0 ? optimal_filter() : which == 1 ? smoothed_filter() : which == 2 ? ridges_filter() : relief_filter();
  expect_bad_input_handled([&](const std::string& name, const reliefkit::TriMesh& m) {
    return run_filters("ms_bad_" + name + std::to_string(which), m, {f}, {"-o", "out.ply"});
  });
}

INSTANTIATE_TEST_SUITE_P(AllFourFilters, MultiscaleBadInput, ::testing::Values(0, 1, 2, 3));
