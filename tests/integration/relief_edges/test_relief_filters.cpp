// "Relief Edges", "Estimate Base Normals" and "Ridges and Valleys" through the real meshlabserver.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bad_input.h"
#include "mesh_files.h"
#include "reliefs.h"
#include "server.h"
#include "shapes.h"

using namespace rktest;

namespace {

std::string relief_filter() {
  return mlx_filter("Relief Edges",
                    {param_string("presmoothing", "auto"), param_string("base_scale", "auto"),
                     param_string("edge_smoothing", "auto"), param_bool("restrict", true),
                     param_float("strong_error", 0.5), param_float("weak_error", 0.8), param_float("strong_angle", 0),
                     param_float("weak_angle", 0), param_float("min_length", 2), param_float("gap", 3), param_bool("per_vertex", true),
                     param_bool("quality", false), param_float("lift", 0)});
}
std::string base_filter() {
  return mlx_filter("Estimate Base Normals", {param_string("base_scale", "auto"), param_bool("quality", true)});
}
std::string ridges_filter() {
  return mlx_filter("Ridges and Valleys", {param_float("threshold", 1), param_string("presmoothing", "auto"),
                                           param_float("min_length", 4), param_float("lift", 0)});
}


}  // namespace

TEST(ReliefFilters, ReliefEdgesOnANoisyCylinder) {
  ReliefShape s;
  s.noise = 0.15;
  Relief r = discs_on_cylinder(s);
  std::string dir;
  ServerRun run =
      run_filters("relief_cylinder", r.mesh, {relief_filter()}, {"-o", "edges.obj", "-l", "1"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("in \u2013 relief edges"), std::string::npos) << run.output;
  MeshFile edges = read_mesh(dir + "/edges.obj");
  ASSERT_GT(edges.edges.size(), 100u);
  Detection d = score(r, polylines_of(edges), r.mean_edge);
  EXPECT_GE(d.recall, 0.90);
  EXPECT_GE(d.precision, 0.85);
}

TEST(ReliefFilters, BaseNormalsTiltIsLargeOnTheFlanksOnly) {
  Relief r = disc_on_plane({}, 100);
  std::string dir;
  ServerRun run = run_filters("base_plane", r.mesh, {base_filter()}, {"-o", "out.ply", "-m", "vq"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  MeshFile out = read_mesh(dir + "/out.ply");
  const auto& q = out.vertex_props["quality"];
  ASSERT_EQ(q.size(), out.mesh.vertices.size());
  double flank = 0, flat = 0;
  int nf = 0, nt = 0;
  for (size_t i = 0; i < q.size(); ++i) {
    double rad = std::hypot(out.mesh.vertices[i].x(), out.mesh.vertices[i].y());
    if (std::abs(rad - 0.5) < 0.01) flank += q[i], ++nf;  // steepest part of the step (37 degrees)
    if (rad < 0.2 || (rad > 0.8 && rad < 0.95)) flat += q[i], ++nt;
  }
  EXPECT_GT(flank / nf, 25);
  EXPECT_LT(flat / nt, 3);
}

TEST(ReliefFilters, RidgesAndValleysLayers) {
  // A groove along y at x = 0: one valley line there.
  reliefkit::TriMesh m = height_field([](double x, double) { return -0.05 * std::exp(-x * x / (2 * 0.05 * 0.05)); },
                                      1.0, 120, 0.3, 2);
  double h = reliefkit::edge_length_stats(m).mean;
  std::string dir;
  ServerRun run = run_filters("ridges_groove", m, {ridges_filter()},
                              {"-o", "ridges.obj", "-l", "1", "-o", "valleys.obj", "-l", "2"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  MeshFile valleys = read_mesh(dir + "/valleys.obj");
  MeshFile ridges = read_mesh(dir + "/ridges.obj");
  ASSERT_GT(valleys.edges.size(), 50u);
  ASSERT_GT(ridges.edges.size(), 50u);  // the groove's two shoulders
  // The groove bottom x = 0 is covered along its length; the shoulders at x = +-sqrt(3) s.
  auto covered = [&](const MeshFile& f, double x0) {
    double len = 0;
    for (const auto& e : f.edges) {
      const auto &a = f.mesh.vertices[e[0]], &b = f.mesh.vertices[e[1]];
      if (std::abs(0.5 * (a.x() + b.x()) - x0) < h) len += (a - b).norm();
    }
    return len;
  };
  EXPECT_GT(covered(valleys, 0.0), 0.9 * 2.0);
  for (const auto& p : valleys.mesh.vertices) EXPECT_LT(std::abs(p.x()), h) << "a valley off the groove bottom";
  EXPECT_GT(covered(ridges, std::sqrt(3.0) * 0.05), 0.8 * 2.0);
  EXPECT_GT(covered(ridges, -std::sqrt(3.0) * 0.05), 0.8 * 2.0);
}

class ReliefBadInput : public ::testing::TestWithParam<int> {
 protected:
  ServerRun run(const std::string& name, const reliefkit::TriMesh& m) {
    std::string f = GetParam() == 0 ? relief_filter() : GetParam() == 1 ? base_filter() : ridges_filter();
    return run_filters(name + std::to_string(GetParam()), m, {f}, {"-o", "out.ply"});
  }
};

TEST_P(ReliefBadInput, ClearMessageOrSuccessNeverACrash) {
  expect_bad_input_handled([this](const std::string& name, const reliefkit::TriMesh& m) { return run(name, m); });
}

INSTANTIATE_TEST_SUITE_P(AllThreeFilters, ReliefBadInput, ::testing::Values(0, 1, 2));
