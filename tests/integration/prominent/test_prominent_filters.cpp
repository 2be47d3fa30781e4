// "Prominent Field", "Prominent Enhancement" and "Prominent Coloring" through the real meshlabserver.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "bad_input.h"
#include "mesh_files.h"
#include "reliefkit/prominent/prominent.h"
#include "reliefs.h"
#include "server.h"
#include "shapes.h"

using namespace rktest;

namespace {

std::vector<std::string> field_params(double theta = 2) {
  return {param_string("presmoothing", "auto"), param_string("base_scale", "auto"), param_float("theta", theta)};
}
std::string field_filter(int quality = 0) {
  auto p = field_params();
  p.push_back(param_enum("quality", quality, 4));
  p.push_back(param_bool("curvature_dir", true));
  return mlx_filter("Prominent Field", p);
}
std::string enhance_filter(const std::string& sigma_c = "auto", int flow = -1, double strength = 1) {
  std::vector<std::string> p{param_string("sigma_c", sigma_c), param_int("bilateral_iterations", 2),
                             param_int("flow_iterations", flow), param_float("flow_step", 0.2),
                             param_float("strength", strength)};
  for (const auto& x : field_params()) p.push_back(x);
  return mlx_filter("Prominent Enhancement", p);
}
std::string coloring_filter(int curvature = 0, double contrast = 1, double theta = 2) {
  std::vector<std::string> p{param_enum("curvature", curvature, 3), param_float("contrast", contrast)};
  for (const auto& x : field_params(theta)) p.push_back(x);
  return mlx_filter("Prominent Coloring", p);
}

}  // namespace

TEST(ProminentFilters, FieldQualityIsTheCurvatureAlongTheCoresField) {
  ReliefShape s;
  s.noise = 0.1;
  const Relief r = disc_on_plane(s, 100);
  std::string dir;
  ServerRun run = run_filters("prominent_field", r.mesh, {field_filter(0)}, {"-o", "out.ply", "-m", "vq"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Prominent field of"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Show Curvature"), std::string::npos) << run.output;
  const MeshFile out = read_mesh(dir + "/out.ply");
  const auto& q = out.vertex_props.at("quality");
  ASSERT_EQ(q.size(), r.mesh.vertices.size());
  // The core on the mesh meshlabserver read (in.ply, single precision).
  const reliefkit::ProminentFieldResult f = reliefkit::compute_prominent_field(read_mesh(dir + "/in.ply").mesh);
  double worst = 0, scale = 0;
  for (size_t v = 0; v < q.size(); ++v) {
    const double kp = f.curvature->normal_curvature(int(v), f.field[v]);
    worst = std::max(worst, std::abs(q[v] - kp));
    scale = std::max(scale, std::abs(kp));
  }
  EXPECT_LT(worst, 1e-4 * scale) << "quality differs from the core's kappa_p";
}

TEST(ProminentFilters, EnhancementAddsALayerCloserToTheSharpStep) {
  ReliefShape sharp;
  sharp.width = 0.008;
  const Relief clean = disc_on_plane(sharp, 100);
  ReliefShape eroded;
  eroded.width = 0.05;
  eroded.noise = 0.2;
  const Relief noisy = disc_on_plane(eroded, 100);
  std::string dir;
  // Restoring a worn step goes beyond what the noisy scan supports: strength 12 (docs/prominent.md).
  ServerRun run = run_filters("prominent_enhance", noisy.mesh, {enhance_filter("auto", -1, 12)},
                              {"-o", "scan.ply", "-l", "0", "-o", "enhanced.ply", "-l", "1", "-m", "vq"}, &dir);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("in \u2013 enhanced"), std::string::npos) << run.output;
  const MeshFile scan = read_mesh(dir + "/scan.ply"), enh = read_mesh(dir + "/enhanced.ply");
  ASSERT_EQ(enh.mesh.vertices.size(), noisy.mesh.vertices.size());
  for (size_t v = 0; v < scan.mesh.vertices.size(); ++v)  // the scan is untouched
    ASSERT_LT((scan.mesh.vertices[v] - noisy.mesh.vertices[v]).norm(), 1e-5) << v;
  auto rms_near = [&](const std::vector<reliefkit::Vec3>& pos) {
    const std::vector<double> d = distance_to_surface(clean.mesh, pos, 0.06);
    double s = 0;
    long n = 0;
    for (size_t v = 0; v < pos.size(); ++v) {
      const auto& x = clean.mesh.vertices[v];
      if (std::abs(std::hypot(x.x(), x.y()) - 0.5) < 2 * eroded.width) s += d[v] * d[v], ++n;
    }
    return std::sqrt(s / n) / noisy.mean_edge;
  };
  const double before = rms_near(noisy.mesh.vertices), after = rms_near(enh.mesh.vertices);
  std::printf("enhancement through meshlabserver: RMS distance to the sharp step near it %.3f -> %.3f edge lengths\n",
              before, after);
  EXPECT_LT(after, 0.75 * before);
  // Vertex quality = the move along the base normal: positive on the top shoulder, negative at the foot.
  const auto& q = enh.vertex_props.at("quality");
  double top = 0, foot = 0;
  for (size_t v = 0; v < q.size(); ++v) {
    const double rr = std::hypot(noisy.mesh.vertices[v].x(), noisy.mesh.vertices[v].y());
    if (rr > 0.5 - 2 * eroded.width && rr < 0.5 - 0.5 * eroded.width) top += q[v];
    if (rr > 0.5 + 0.5 * eroded.width && rr < 0.5 + 2 * eroded.width) foot += q[v];
  }
  EXPECT_GT(top, 0);
  EXPECT_LT(foot, 0);
}

TEST(ProminentFilters, ColoringIsMonotoneInItsQualityForEveryCurvature) {
  ReliefShape s;
  s.noise = 0.05;
  const Relief r = disc_on_plane(s, 100);
  for (int which = 0; which < 3; ++which) {
    std::string dir;
    ServerRun run = run_filters("prominent_coloring" + std::to_string(which), r.mesh, {coloring_filter(which)},
                                {"-o", "out.ply", "-m", "vc", "vq"}, &dir);
    ASSERT_EQ(run.status, 0) << run.output;
    const MeshFile out = read_mesh(dir + "/out.ply");
    const auto &q = out.vertex_props.at("quality"), &red = out.vertex_props.at("red");
    std::vector<size_t> order(q.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return q[a] < q[b]; });
    long inversions = 0;
    for (size_t i = 1; i < order.size(); ++i) inversions += red[order[i]] + 1 < red[order[i - 1]];  // rounding
    EXPECT_EQ(inversions, 0) << which;
    EXPECT_LT(red[order.front()], 60) << which;
    EXPECT_GT(red[order.back()], 195) << which;
  }
}

TEST(ProminentFilters, BadParametersStopWithAClearMessageAndTheMeshUnchanged) {
  const Relief r = disc_on_plane({}, 60);
  struct Case {
    std::string filter, expect;
  };
  const Case cases[] = {
      {coloring_filter(0, 0), "Contrast (lambda) (\"contrast\") must be between"},
      {coloring_filter(0, -1), "Contrast (lambda) (\"contrast\") must be between"},
      {coloring_filter(0, 1, 0), "Feature threshold (theta) (\"theta\") must be between"},
      {coloring_filter(0, 1, std::nan("")), "Feature threshold (theta) (\"theta\") must be between"},
      {enhance_filter("0"), "Smoothing scale (sigma_c) (\"sigma_c\") must be"},
      {enhance_filter("-3"), "Smoothing scale (sigma_c) (\"sigma_c\") must be"},
      {enhance_filter("auto", -5), "Flow iterations (\"flow_iterations\") must be between"},
  };
  int k = 0;
  for (const auto& c : cases) {
    std::string dir;
    ServerRun run = run_filters("prominent_bad_param" + std::to_string(k++), r.mesh, {c.filter},
                                {"-o", "out.ply", "-m", "vc"}, &dir);
    EXPECT_FALSE(run.crashed) << run.output;
    EXPECT_NE(run.status, 0) << run.output;
    EXPECT_NE(run.output.find(c.expect), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/out.ply")) << "a result was written";
  }
}

class ProminentBadInput : public ::testing::TestWithParam<int> {
 protected:
  ServerRun run(const std::string& name, const reliefkit::TriMesh& m) {
    const std::string f = GetParam() == 0 ? field_filter() : GetParam() == 1 ? enhance_filter() : coloring_filter();
    return run_filters(name + "_prominent" + std::to_string(GetParam()), m, {f}, {"-o", "out.ply"});
  }
};

TEST_P(ProminentBadInput, ClearMessageOrSuccessNeverACrash) {
  expect_bad_input_handled([this](const std::string& name, const reliefkit::TriMesh& m) { return run(name, m); });
}

INSTANTIATE_TEST_SUITE_P(AllThreeFilters, ProminentBadInput, ::testing::Values(0, 1, 2));
