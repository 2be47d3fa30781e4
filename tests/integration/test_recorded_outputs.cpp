// Behaviour kept through refactors: every example script on the shared scans (coin, statuette,
// bunny) and drawings, through the real meshlabserver, compared with digests of the outputs that
// were recorded before the refactor (tests/data/recorded/*.json): layer sizes, quantiles and strided
// samples of vertex quality, colours and positions, and for curve layers their length and a sample
// of their points. RELIEFKIT_RECORD=1 writes the digests anew instead of comparing (only when a
// change of results is intended; say so in the commit).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "mesh_files.h"
#include "server.h"

using namespace rktest;
using reliefkit::Vec3;
using nlohmann::json;

namespace {

constexpr int kSamples = 400;        // strided samples per vertex property
constexpr int kCurveSamples = 1500;  // sampled segment midpoints per curve layer

struct Case {
  std::string name;    // digest file name
  std::string input;   // mesh (relative to the source tree, or "shared:" for ../shared/data/meshes), "" for none
  std::string script;  // examples/<script>
  std::vector<int> surfaces, curves;  // layers saved as PLY (quality, colour) and as OBJ (edges)
};

const std::vector<Case>& cases() {
  static const std::vector<Case> all = {
      {"coin_curvature", "examples/data/penny.ply", "curvature_colors.mlx", {0}, {}},
      {"coin_demarcating", "examples/data/penny.ply", "demarcating_shading.mlx", {0}, {1}},
      {"coin_relief_edges", "examples/data/penny.ply", "relief_edges.mlx", {0}, {1, 2, 3}},
      {"coin_multiscale", "examples/data/penny.ply", "multiscale.mlx", {0}, {1, 2, 3}},
      {"coin_prominent", "examples/data/penny.ply", "prominent.mlx", {0, 1}, {}},
      {"statuette_demarcating", "shared:fertility.obj", "demarcating_shading.mlx", {0}, {1}},
      {"statuette_relief_edges", "shared:fertility.obj", "relief_edges.mlx", {0}, {1, 2, 3}},
      {"statuette_multiscale", "shared:fertility.obj", "multiscale.mlx", {0}, {1, 2, 3}},
      {"statuette_prominent", "shared:fertility.obj", "prominent.mlx", {0, 1}, {}},
      {"bunny_relief_edges", "shared:stanford-bunny.obj", "relief_edges.mlx", {0}, {1, 2, 3}},
      {"bunny_multiscale", "shared:stanford-bunny.obj", "multiscale.mlx", {0}, {1, 2, 3}},
      {"bunny_prominent", "shared:stanford-bunny.obj", "prominent.mlx", {0, 1}, {}},
      {"drawing_curves", "", "drawing_curves.mlx", {}, {0}},
      {"drawing_relief", "", "drawing_relief.mlx", {0}, {1}},
      {"base_and_relief", "", "base_and_relief.mlx", {1, 2}, {}},
  };
  return all;
}

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::string recorded_path(const Case& c) { return source_dir() + "/tests/data/recorded/" + c.name + ".json"; }

// The input as PLY in the test's folder (meshlabserver's OBJ importer asserts on some files).
std::string prepare_input(const Case& c, const std::string& dir) {
  if (c.input.empty()) return "";
  const bool shared = c.input.rfind("shared:", 0) == 0;
  const std::string path = shared ? source_dir() + "/../shared/data/meshes/" + c.input.substr(7) : source_dir() + "/" + c.input;
  if (!std::filesystem::exists(path)) throw std::runtime_error(path + " missing (the shared scans lie beside the clone)");
  write_ply(dir + "/in.ply", read_mesh(path).mesh);
  return dir + "/in.ply";
}

// The example script with its example data copied into the test's folder (the drawing filters write
// their interpretation files beside the drawing).
std::string prepare_script(const Case& c, const std::string& dir) {
  for (const auto& e : std::filesystem::directory_iterator(source_dir() + "/examples/data"))
    if (e.path().extension() == ".png") std::filesystem::copy_file(e.path(), dir + "/" + e.path().filename().string());
  std::ifstream in(source_dir() + "/examples/" + c.script);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "value=\"examples/data/";
  for (size_t at = 0; (at = s.find(from, at)) != std::string::npos;) s.replace(at, from.size(), "value=\"" + dir + "/");
  write_text(dir + "/s.mlx", s);
  return dir + "/s.mlx";
}

std::vector<double> quantiles(std::vector<double> v) {
  std::vector<double> q;
  if (v.empty()) return q;
  std::sort(v.begin(), v.end());
  for (double p : {0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99}) q.push_back(v[size_t(p * (v.size() - 1))]);
  return q;
}

std::vector<double> strided(const std::vector<double>& v, int n) {
  std::vector<double> s;
  const size_t step = std::max<size_t>(1, v.size() / n);
  for (size_t i = 0; i < v.size() && int(s.size()) < n; i += step) s.push_back(v[i]);
  return s;
}

json surface_digest(const MeshFile& f) {
  json d{{"vertices", f.mesh.vertices.size()}, {"faces", f.mesh.faces.size()}};
  std::vector<double> x, y, z;
  for (const Vec3& p : f.mesh.vertices) x.push_back(p.x()), y.push_back(p.y()), z.push_back(p.z());
  d["x"] = strided(x, kSamples), d["y"] = strided(y, kSamples), d["z"] = strided(z, kSamples);
  for (const char* prop : {"quality", "red", "green", "blue"}) {
    auto it = f.vertex_props.find(prop);
    if (it == f.vertex_props.end()) continue;
    d[prop] = {{"quantiles", quantiles(it->second)}, {"samples", strided(it->second, kSamples)}};
  }
  return d;
}

double curve_length(const MeshFile& f) {
  double length = 0;
  for (const auto& e : f.edges) length += (f.mesh.vertices[e[0]] - f.mesh.vertices[e[1]]).norm();
  return length;
}

json curve_digest(const MeshFile& f) {
  const double length = curve_length(f);
  json pts = json::array();
  const size_t step = std::max<size_t>(1, f.edges.size() / kCurveSamples);
  for (size_t i = 0; i < f.edges.size(); i += step) {
    const Vec3 m = 0.5 * (f.mesh.vertices[f.edges[i][0]] + f.mesh.vertices[f.edges[i][1]]);
    pts.push_back({m.x(), m.y(), m.z()});
  }
  return {{"edges", f.edges.size()}, {"length", length}, {"midpoints", pts}};
}

double range_of(const json& q) { return std::max(1e-12, q.back().get<double>() - q.front().get<double>()); }

// Largest difference of two sample lists, relative to the recorded values' 1-99 % range.
double sample_error(const json& got, const json& want, double range) {
  double worst = 0;
  EXPECT_EQ(got.size(), want.size());
  for (size_t i = 0; i < std::min(got.size(), want.size()); ++i)
    worst = std::max(worst, std::abs(got[i].get<double>() - want[i].get<double>()) / range);
  return worst;
}

struct Errors {
  double values = 0, positions = 0, length = 0, off_curve = 0;
};

void compare_surface(const std::string& what, const json& got, const json& want, Errors& err) {
  EXPECT_EQ(got["vertices"], want["vertices"]) << what;
  EXPECT_EQ(got["faces"], want["faces"]) << what;
  for (const char* axis : {"x", "y", "z"}) {
    const auto& w = want[axis];
    std::vector<double> wv = w.get<std::vector<double>>();
    const double range = wv.empty() ? 1 : std::max(1e-12, *std::max_element(wv.begin(), wv.end()) - *std::min_element(wv.begin(), wv.end()));
    err.positions = std::max(err.positions, sample_error(got[axis], w, range));
  }
  for (const auto& [prop, w] : want.items()) {
    if (!w.is_object()) continue;
    ASSERT_TRUE(got.contains(prop)) << what << ": no " << prop;
    const double range = range_of(w["quantiles"]);
    err.values = std::max({err.values, sample_error(got[prop]["samples"], w["samples"], range),
                           sample_error(got[prop]["quantiles"], w["quantiles"], range)});
  }
}

void compare_curves(const std::string& what, const MeshFile& got, const json& want, double tol, Errors& err) {
  const double length = curve_length(got), wl = want["length"];
  ASSERT_GT(wl, 0) << what << ": recorded an empty layer";
  err.length = std::max(err.length, std::abs(length - wl) / wl);
  // The recorded midpoints as equal, tiny segments: near_share's length weights become counts.
  MeshFile points;
  for (const auto& p : want["midpoints"]) {
    const Vec3 m(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    const int i = int(points.mesh.vertices.size());
    points.mesh.vertices.push_back(m);
    points.mesh.vertices.push_back(m + Vec3(tol * 1e-3, 0, 0));
    points.edges.push_back({i, i + 1});
  }
  const double far = points.edges.empty() ? 0 : 1 - near_share(points, got, tol);
  err.off_curve = std::max(err.off_curve, far);
}

}  // namespace

class RecordedOutputs : public ::testing::TestWithParam<Case> {};

TEST_P(RecordedOutputs, SameAsRecordedBeforeTheRefactor) {
  const Case& c = GetParam();
  const std::string dir = temp_dir("recorded_" + c.name);
  const std::string input = prepare_input(c, dir);
  std::vector<std::string> args;
  if (!input.empty()) args = {"-i", input};
  for (int l : c.surfaces) args.insert(args.end(), {"-o", dir + "/layer" + std::to_string(l) + ".ply", "-l", std::to_string(l), "-m", "vc", "vq"});
  for (int l : c.curves) args.insert(args.end(), {"-o", dir + "/layer" + std::to_string(l) + ".obj", "-l", std::to_string(l)});
  args.insert(args.end(), {"-s", prepare_script(c, dir)});
  const ServerRun run = run_meshlabserver(args);
  ASSERT_EQ(run.status, 0) << run.output;
  json got;
  for (int l : c.surfaces) got["surface" + std::to_string(l)] = surface_digest(read_mesh(dir + "/layer" + std::to_string(l) + ".ply"));
  std::map<int, MeshFile> curves;
  for (int l : c.curves) {
    curves[l] = read_mesh(dir + "/layer" + std::to_string(l) + ".obj");
    got["curves" + std::to_string(l)] = curve_digest(curves[l]);
  }
  if (std::getenv("RELIEFKIT_RECORD")) {
    std::filesystem::create_directories(source_dir() + "/tests/data/recorded");
    std::ofstream(recorded_path(c)) << got.dump() << "\n";
    std::printf("recorded %s\n", recorded_path(c).c_str());
    return;
  }
  std::ifstream in(recorded_path(c));
  ASSERT_TRUE(in) << recorded_path(c) << " missing";
  const json want = json::parse(in);
  Errors err;
  for (int l : c.surfaces) compare_surface(c.name + " layer " + std::to_string(l), got["surface" + std::to_string(l)], want["surface" + std::to_string(l)], err);
  // Tolerance for curve points: a tenth of the mean sampled segment's length (meshes of any unit).
  for (int l : c.curves) {
    const json& w = want["curves" + std::to_string(l)];
    EXPECT_EQ(got["curves" + std::to_string(l)]["edges"], w["edges"]) << c.name << " curves " << l;
    const double tol = 0.1 * w["length"].get<double>() / std::max(1, w["edges"].get<int>());
    compare_curves(c.name + " curves " + std::to_string(l), curves[l], w, tol, err);
  }
  std::printf("%s: values %.2e, positions %.2e (of their range), curve length %.2e, recorded points off the curves %.3f\n",
              c.name.c_str(), err.values, err.positions, err.length, err.off_curve);
  // Float noise: outputs pass through single-precision PLY/OBJ files.
  EXPECT_LE(err.values, 1e-4) << c.name;
  EXPECT_LE(err.positions, 1e-5) << c.name;
  EXPECT_LE(err.length, 1e-4) << c.name;
  EXPECT_LE(err.off_curve, 0.0) << c.name;
}

INSTANTIATE_TEST_SUITE_P(SharedScansAndDrawings, RecordedOutputs, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });
