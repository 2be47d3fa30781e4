// Portable parameters through the real meshlabserver: every example script gives the same result
// on the coin stored in other units; old scripts with absolute lengths still run; bad parameter
// values and a curve layer selected by mistake stop with a clear message.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unordered_map>

#include "mesh_files.h"
#include "reliefkit/base/scale.h"
#include "reliefs.h"
#include "server.h"

using namespace rktest;
using reliefkit::Vec3;

namespace {

const std::string kCoin = rktest::source_dir() + "/examples/data/penny.ply";

MeshFile scaled(MeshFile m, double f) {
  for (auto& p : m.mesh.vertices) p *= f;
  return m;
}

struct ScriptOutputs {
  std::string script;
  std::vector<int> curve_layers;  // layers saved as OBJ and compared as curves
  bool colours = false;           // compare the vertex colours of layer 0
};

void PrintTo(const ScriptOutputs& s, std::ostream* os) { *os << s.script; }

}  // namespace

// One test per example script, so that ctest runs them side by side.
class EveryExampleScript : public ::testing::TestWithParam<ScriptOutputs> {};

TEST_P(EveryExampleScript, GivesTheSameResultInAnyUnit) {
  const ScriptOutputs& sc = GetParam();
  const MeshFile coin = read_mesh(kCoin);
  const double edge = reliefkit::mesh_scale(coin.mesh).edge;
    ASSERT_TRUE(std::filesystem::exists(rktest::source_dir() + "/examples/" + sc.script)) << sc.script;
    std::map<double, std::vector<MeshFile>> curves;
    std::map<double, MeshFile> surface;
    for (double f : {1.0, 1000.0, 0.001}) {
      const std::string dir = temp_dir("portable_" + sc.script + "_" + std::to_string(f));
      write_ply(dir + "/in.ply", scaled(coin, f).mesh);
      std::vector<std::string> args{"-i", dir + "/in.ply", "-o", dir + "/out.ply", "-l", "0", "-m", "vc", "vq"};
      for (int l : sc.curve_layers) {
        args.insert(args.end(), {"-o", dir + "/curves" + std::to_string(l) + ".obj", "-l", std::to_string(l)});
      }
      args.insert(args.end(), {"-s", rktest::source_dir() + "/examples/" + sc.script});
      ServerRun run = run_meshlabserver(args);
      ASSERT_FALSE(run.crashed) << run.output;
      ASSERT_NE(run.output.find("Edge length"), std::string::npos) << sc.script << " ×" << f << ": " << run.output;
      EXPECT_EQ(run.output.find("absolute length"), std::string::npos) << sc.script << " stores absolute lengths";
      surface[f] = read_mesh(dir + "/out.ply");
      for (int l : sc.curve_layers) curves[f].push_back(scaled(read_mesh(dir + "/curves" + std::to_string(l) + ".obj"), 1 / f));
    }
    for (double f : {1000.0, 0.001}) {
      for (size_t k = 0; k < sc.curve_layers.size(); ++k) {
        const MeshFile &a = curves[1.0][k], &b = curves[f][k];
        ASSERT_GT(a.edges.size(), 20u) << sc.script << " layer " << sc.curve_layers[k];
        const double recall = near_share(a, b, 0.5 * edge), precision = near_share(b, a, 0.5 * edge);
        std::printf("%-24s layer %d, coin x%g vs x1: %zu / %zu segments, recall %.3f precision %.3f\n", sc.script.c_str(),
                    sc.curve_layers[k], f, b.edges.size(), a.edges.size(), recall, precision);
        EXPECT_GE(recall, 0.98) << sc.script << " x" << f;
        EXPECT_GE(precision, 0.98) << sc.script << " x" << f;
      }
      if (sc.colours) {
        const auto &c0 = surface[1.0].vertex_props, &c1 = surface[f].vertex_props;
        ASSERT_TRUE(c0.count("red") && c1.count("red")) << sc.script;
        long differ = 0;
        for (size_t i = 0; i < c0.at("red").size(); ++i)
          for (const char* ch : {"red", "green", "blue"})
            if (std::abs(c0.at(ch)[i] - c1.at(ch)[i]) > 3) {
              ++differ;
              break;
            }
        const double share = double(differ) / c0.at("red").size();
        std::printf("%-24s colours, coin x%g vs x1: %.4f of the vertices differ by more than 3/255\n",
                    sc.script.c_str(), f, share);
        EXPECT_LE(share, 0.01) << sc.script << " x" << f;
      }
    }
}

INSTANTIATE_TEST_SUITE_P(PortableParameters, EveryExampleScript,
                         ::testing::Values(ScriptOutputs{"curvature_colors.mlx", {}, true},
                                           ScriptOutputs{"demarcating_shading.mlx", {1}, true},
                                           ScriptOutputs{"relief_edges.mlx", {1, 2, 3}, false},
                                           ScriptOutputs{"curvature.mlx", {}, false},
                                           ScriptOutputs{"multiscale.mlx", {1, 2, 3}, false},
                                           ScriptOutputs{"prominent.mlx", {}, true}),
                         [](const ::testing::TestParamInfo<ScriptOutputs>& i) {
                           std::string n = i.param.script.substr(0, i.param.script.find('.'));
                           return n;
                         });

TEST(PortableParameters, OldScriptsWithAbsoluteLengthsStillRun) {
  const std::string dir = temp_dir("old_script");
  const std::string script = mlx_script({mlx_filter(
      "Demarcating Curves", {param_float("threshold", 1), param_absperc("presmoothing", 8.6), param_float("min_length", 4),
                             param_bool("per_vertex", false), param_bool("quality", false), param_float("lift", 0)})});
  write_text(dir + "/s.mlx", script);
  ServerRun run = run_meshlabserver({"-i", kCoin, "-o", dir + "/c.obj", "-l", "1", "-s", dir + "/s.mlx"});
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("absolute length, 8.6 mesh units"), std::string::npos) << run.output;
  EXPECT_GT(read_mesh(dir + "/c.obj").edges.size(), 100u);
}

TEST(PortableParameters, BadValuesStopWithAClearMessage) {
  struct Case {
    std::string filter;
    std::vector<std::string> params;
    std::string expect;
  };
  const Case cases[] = {
      {"Demarcating Curves",
       {param_float("threshold", 1), param_string("presmoothing", "lots"), param_float("min_length", 4),
        param_bool("per_vertex", false), param_bool("quality", false), param_float("lift", 0)},
       "Pre-smoothing (\"presmoothing\") must be \"auto\" or a number of edge lengths"},
      {"Demarcating Curves",
       {param_float("threshold", std::nan("")), param_string("presmoothing", "auto"), param_float("min_length", 4),
        param_bool("per_vertex", false), param_bool("quality", false), param_float("lift", 0)},
       "Strength threshold (\"threshold\") must be between 0 and 1000"},
      {"Compute Curvature Tensor and Derivatives",
       {param_enum("estimator", 0, 2), param_string("presmoothing", "auto"), param_enum("quality", 99, 6)},
       "Vertex quality (\"quality\") must be a choice between 0 and 5 (got 99)"},
      {"Relief Edges",
       {param_string("presmoothing", "auto"), param_string("base_scale", "1e30"), param_string("edge_smoothing", "auto"),
        param_bool("restrict", true), param_float("strong_error", 0.5), param_float("weak_error", 0.8),
        param_float("strong_angle", 0), param_float("weak_angle", 0), param_float("min_length", 2),
        param_float("gap", 3), param_bool("per_vertex", true), param_bool("quality", false), param_float("lift", 0)},
       "Base surface scale (\"base_scale\") must be \"auto\" or a number of edge lengths between 0.5 and 10000"},
  };
  int k = 0;
  for (const auto& c : cases) {
    const std::string dir = temp_dir("bad_param_" + std::to_string(k++));
    write_text(dir + "/s.mlx", mlx_script({mlx_filter(c.filter, c.params)}));
    ServerRun run = run_meshlabserver({"-i", kCoin, "-o", dir + "/out.ply", "-s", dir + "/s.mlx"});
    EXPECT_FALSE(run.crashed) << run.output;
    EXPECT_NE(run.status, 0) << run.output;
    EXPECT_NE(run.output.find(c.expect), std::string::npos) << c.filter << ": " << run.output;
  }
}

TEST(PortableParameters, ACurveLayerSelectedByMistakeIsNamedAsSuch) {
  const std::string dir = temp_dir("curve_layer_current");
  MeshFile curves;
  curves.mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
  write_text(dir + "/curves.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nl 1 2\nl 2 3\n");
  write_text(dir + "/s.mlx",
             mlx_script({mlx_filter("Demarcating Curves",
                                    {param_float("threshold", 1), param_string("presmoothing", "auto"),
                                     param_float("min_length", 4), param_bool("per_vertex", false),
                                     param_bool("quality", false), param_float("lift", 0)})}));
  ServerRun run = run_meshlabserver({"-i", kCoin, "-i", dir + "/curves.obj", "-s", dir + "/s.mlx"});
  EXPECT_FALSE(run.crashed) << run.output;
  EXPECT_NE(run.output.find("select the scanned mesh layer"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("Poisson"), std::string::npos) << run.output;
}

TEST(EmptyResults, SayWhatWasSeenAndWhatToChange) {
  const std::string dir = temp_dir("empty_results");
  write_text(dir + "/s.mlx",
             mlx_script({mlx_filter("Demarcating Curves",
                                    {param_float("threshold", 1000), param_string("presmoothing", "auto"),
                                     param_float("min_length", 4), param_bool("per_vertex", false),
                                     param_bool("quality", false), param_float("lift", 0)})}));
  ServerRun run = run_meshlabserver({"-i", kCoin, "-o", dir + "/c.obj", "-l", "1", "-s", dir + "/s.mlx"});
  EXPECT_FALSE(run.crashed) << run.output;
  EXPECT_NE(run.output.find("No demarcating curve is above the threshold"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("The strongest crossing seen has strength"), std::string::npos) << run.output;
}

TEST(RepairInMeshLab, DamagedCopiesGiveTheGoodMeshCurvesAndSaySo) {
  ReliefShape s;
  s.noise = 0.05;
  const Relief r = disc_on_sphere(s, 5);
  const std::string filter = mlx_filter(
      "Demarcating Curves", {param_float("threshold", 1), param_string("presmoothing", "auto"),
                             param_float("min_length", 4), param_bool("per_vertex", true),
                             param_bool("quality", false), param_float("lift", 0)});
  auto run = [&](const std::string& name, const reliefkit::TriMesh& m, std::string* log) {
    std::string dir;
    ServerRun sr = run_filters(name, m, {filter}, {"-o", "c.obj", "-l", "1"}, &dir);
    EXPECT_EQ(sr.status, 0) << name << ": " << sr.output;
    if (log) *log = sr.output;
    return read_mesh(dir + "/c.obj");
  };
  const MeshFile good = run("repair_good", r.mesh, nullptr);
  ASSERT_GT(good.edges.size(), 100u);
  reliefkit::TriMesh flipped = r.mesh, soup, doubled = r.mesh;
  for (size_t f = 0; f < flipped.faces.size(); f += 2) std::swap(flipped.faces[f][1], flipped.faces[f][2]);
  for (const auto& f : r.mesh.faces) {
    const int b = soup.n_vertices();
    for (int j = 0; j < 3; ++j) soup.vertices.push_back(r.mesh.vertices[f[j]]);
    soup.faces.push_back({b, b + 1, b + 2});
  }
  doubled.faces.insert(doubled.faces.end(), r.mesh.faces.begin(), r.mesh.faces.end());
  const std::pair<const char*, const reliefkit::TriMesh*> cases[] = {
      {"flipped", &flipped}, {"soup", &soup}, {"doubled", &doubled}};
  for (const auto& [name, mesh] : cases) {
    std::string log;
    const MeshFile damaged = run(std::string("repair_") + name, *mesh, &log);
    EXPECT_NE(log.find("Repaired for the computation"), std::string::npos) << name << ": " << log;
    EXPECT_EQ(damaged.edges.size(), good.edges.size()) << name;
    const double tol = 1e-4 * r.mean_edge;
    EXPECT_DOUBLE_EQ(near_share(damaged, good, tol), 1.0) << name;
    EXPECT_DOUBLE_EQ(near_share(good, damaged, tol), 1.0) << name;
  }
}
