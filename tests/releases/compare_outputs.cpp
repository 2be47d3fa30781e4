// rk_compare_outputs A B — the outputs of two reliefkit-batch runs over the same files and filters,
// one with MeshLab 2020.09 and one with 2022.02 (tests/releases/compare-releases.sh), compared:
// every file's record (status, the filters run with the same parameter names and values, the
// layers written and their vertex, face and edge counts), and every layer file (positions within
// 1e-5 of the layer's size, each per-vertex property — quality, colour — within 1e-4 of its range,
// edges the same), and every SVG plate in a file's outputs folder (the same numbers — page, paths,
// scale bar — within 1e-3 mm; the embedded shading left out). Prints what differs; exit status 0
// when nothing does.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <cctype>
#include <cstdlib>
#include <set>
#include <sstream>
#include <string>

#include "mesh_files.h"
#include "results.h"

namespace fs = std::filesystem;
using namespace reliefkit::batch;

namespace {

int g_differences = 0;
int g_plates = 0;
void differ(const std::string& what) {
  std::printf("DIFFERENT: %s\n", what.c_str());
  ++g_differences;
}

double diagonal(const reliefkit::TriMesh& m) {
  if (m.vertices.empty()) return 1;
  reliefkit::Vec3 lo = m.vertices[0], hi = m.vertices[0];
  for (const auto& p : m.vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return std::max((hi - lo).norm(), 1e-30);
}

void compare_layer(const std::string& name, const fs::path& a, const fs::path& b) {
  const rktest::MeshFile x = rktest::read_mesh(a.string()), y = rktest::read_mesh(b.string());
  if (x.mesh.n_vertices() != y.mesh.n_vertices() || x.mesh.n_faces() != y.mesh.n_faces() || x.edges.size() != y.edges.size())
    return differ(name + ": counts " + std::to_string(x.mesh.n_vertices()) + "/" + std::to_string(x.mesh.n_faces()) + "/" +
                  std::to_string(x.edges.size()) + " vs " + std::to_string(y.mesh.n_vertices()) + "/" +
                  std::to_string(y.mesh.n_faces()) + "/" + std::to_string(y.edges.size()));
  double worst = 0;
  for (int i = 0; i < x.mesh.n_vertices(); ++i) worst = std::max(worst, (x.mesh.vertices[size_t(i)] - y.mesh.vertices[size_t(i)]).norm());
  if (worst > 1e-5 * diagonal(x.mesh)) differ(name + ": a vertex moved by " + std::to_string(worst));
  if (x.mesh.faces != y.mesh.faces) differ(name + ": the faces differ");
  if (x.edges != y.edges) differ(name + ": the edges differ");
  for (const auto& prop_y : y.vertex_props)
    if (!x.vertex_props.count(prop_y.first)) differ(name + ": property " + prop_y.first + " only in the second");
  for (const auto& [prop, values] : x.vertex_props) {
    const auto it = y.vertex_props.find(prop);
    if (it == y.vertex_props.end()) { differ(name + ": property " + prop + " missing in the second"); continue; }
    const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
    const double range = values.empty() ? 0 : *hi - *lo;
    double d = 0;
    for (size_t k = 0; k < values.size() && k < it->second.size(); ++k) d = std::max(d, std::abs(values[k] - it->second[k]));
    if (d > 1e-4 * std::max(range, 1e-12)) differ(name + ": property " + prop + " differs by " + std::to_string(d));
  }
}

// The numbers of an SVG plate — its page, paths and scale bar — without the embedded shading.
std::vector<double> svg_numbers(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string svg = text.str();
  for (size_t at = svg.find("<image"); at != std::string::npos; at = svg.find("<image", at))
    svg.erase(at, svg.find('>', at) - at + 1);  // std::regex overflows its stack on the base64
  std::vector<double> values;
  for (const char* c = svg.c_str(); *c;) {
    const bool starts = std::isdigit(static_cast<unsigned char>(*c)) || (*c == '-' && std::isdigit(static_cast<unsigned char>(c[1])));
    char* end = nullptr;
    if (starts) values.push_back(std::strtod(c, &end));
    c = starts && end > c ? end : c + 1;
  }
  return values;
}

void compare_plates(const std::string& name, const fs::path& a, const fs::path& b) {
  if (!fs::is_directory(a)) return;
  for (const auto& entry : fs::directory_iterator(a)) {
    if (entry.path().extension() != ".svg") continue;
    const fs::path other = b / entry.path().filename();
    if (!fs::exists(other)) { differ(name + ": " + entry.path().filename().string() + " only in the first"); continue; }
    const std::vector<double> x = svg_numbers(entry.path()), y = svg_numbers(other);
    ++g_plates;
    if (x.size() != y.size()) { differ(name + ": the plates have " + std::to_string(x.size()) + " and " + std::to_string(y.size()) + " numbers"); continue; }
    double worst = 0;
    for (size_t k = 0; k < x.size(); ++k) worst = std::max(worst, std::abs(x[k] - y[k]));
    if (worst > 1e-3) differ(name + ": the plates differ by " + std::to_string(worst) + " mm");
  }
}

// "name=value" with a path value reduced to its file name: the two runs read the same inputs
// through different folders (the Debian 13 root sees the tree elsewhere).
std::vector<std::string> comparable(std::vector<std::string> parameters) {
  for (auto& p : parameters) {
    const size_t eq = p.find('='), slash = p.rfind('/');
    if (eq != std::string::npos && slash != std::string::npos && slash > eq && p[eq + 1] == '/')
      p = p.substr(0, eq + 1) + p.substr(slash + 1);
  }
  return parameters;
}

void compare_record(const FileResult& x, const FileResult& y, const fs::path& a, const fs::path& b) {
  const std::string f = x.file;
  if (x.status != y.status) differ(f + ": status " + x.status + " vs " + y.status + " (" + x.error + " | " + y.error + ")");
  if (x.filters.size() != y.filters.size()) return differ(f + ": number of filters run");
  for (size_t k = 0; k < x.filters.size(); ++k)
    if (x.filters[k].filter != y.filters[k].filter || comparable(x.filters[k].parameters) != comparable(y.filters[k].parameters)) {
      std::string px, py;
      for (const auto& p : x.filters[k].parameters) px += p + " ";
      for (const auto& p : y.filters[k].parameters) py += p + " ";
      differ(f + ": " + x.filters[k].filter + " ran with [" + px + "] vs [" + py + "]");
    }
  if (x.outputs.size() != y.outputs.size()) return differ(f + ": number of layers written");
  for (size_t k = 0; k < x.outputs.size(); ++k) {
    const LayerOutput &lx = x.outputs[k], &ly = y.outputs[k];
    if (lx.file != ly.file || lx.vertices != ly.vertices || lx.faces != ly.faces || lx.edges != ly.edges) {
      differ(f + ": layer " + lx.file + " vs " + ly.file);
      continue;
    }
    compare_layer(f + " / " + lx.layer, a / lx.file, b / ly.file);
  }
  const fs::path outputs = fs::path(f).replace_extension();
  compare_plates(f, a / outputs, b / outputs);
}
}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: rk_compare_outputs OUTPUT_A OUTPUT_B\n");
    return 2;
  }
  const auto x = all_results(argv[1]), y = all_results(argv[2]);
  if (x.empty()) differ(std::string("no results in ") + argv[1]);
  if (x.size() != y.size()) differ("the runs handled " + std::to_string(x.size()) + " and " + std::to_string(y.size()) + " files");
  for (size_t k = 0; k < std::min(x.size(), y.size()); ++k) {
    if (x[k].file != y[k].file) { differ(x[k].file + " vs " + y[k].file); continue; }
    try {
      compare_record(x[k], y[k], argv[1], argv[2]);
    } catch (const std::exception& e) {
      differ(x[k].file + ": " + e.what());
    }
  }
  size_t layers = 0;
  for (const auto& r : x) layers += r.outputs.size();
  std::printf("%zu files, %zu layers, %d plates compared: %d difference(s)\n", x.size(), layers, g_plates, g_differences);
  return g_differences == 0 ? 0 : 1;
}
