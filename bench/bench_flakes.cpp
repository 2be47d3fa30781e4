// Stone tools (issue 59): "Ridges and Valleys" at its defaults on synthetic knapped flakes whose
// arêtes are known exactly (tests/support/flakes.h: scars with faint ripples, a rough cortex,
// scanner noise 0.1 edge length, irregular triangles). Per seed: the share of the arêtes' length
// the ridges find and the share of the ridges' length on an arête or on the flake's edge (both
// within 2 edge lengths), the share of the edge found, the ridges' dash share and pieces.
//   build/bench/bench_flakes [--seeds 1,2,3] [--svg PREFIX]
// --svg writes PREFIX<seed>.svg: the flake seen from above, the true arêtes and edge in grey,
// the ridges drawn in black.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "flakes.h"
#include "reliefkit/base/curve_selection.h"
#include "reliefkit/relief_edges/ridges.h"

using namespace reliefkit;

namespace {

// Top view (x, y) of the flake, 1 unit = 400 px.
void write_svg(const std::string& path, const rktest::Flake& f, const Polylines& ridges) {
  FILE* out = std::fopen(path.c_str(), "w");
  if (!out) return;
  auto px = [](double x) { return 420 + 400 * x; };
  auto py = [](double y) { return 280 - 400 * y; };
  std::fprintf(out, "<svg xmlns='http://www.w3.org/2000/svg' width='840' height='560'>\n"
                    "<rect width='840' height='560' fill='white'/>\n");
  for (const std::vector<Vec3>* truth : {&f.relief.boundary, &f.edge})
    for (const Vec3& p : *truth)
      std::fprintf(out, "<circle cx='%.1f' cy='%.1f' r='1.5' fill='#9c9'/>\n", px(p.x()), py(p.y()));
  for (const auto& s : ridges.segments) {
    const Vec3 &a = ridges.points[size_t(s[0])], &b = ridges.points[size_t(s[1])];
    std::fprintf(out, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='black' stroke-width='1.2'/>\n",
                 px(a.x()), py(a.y()), px(b.x()), py(b.y()));
  }
  std::fprintf(out, "</svg>\n");
  std::fclose(out);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<unsigned> seeds{1, 2, 3};
  std::string svg;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--svg")) svg = argv[i + 1];
    if (std::strcmp(argv[i], "--seeds")) continue;
    seeds.clear();
    std::stringstream list(argv[i + 1]);
    for (std::string s; std::getline(list, s, ',');) seeds.push_back(unsigned(std::atoi(s.c_str())));
  }
  std::printf("Ridges and Valleys (defaults) on synthetic knapped flakes; tolerance 2 edge lengths\n");
  std::printf("%5s %8s %14s %10s %11s %11s %7s\n", "seed", "faces", "arêtes found", "precision", "edge found",
              "dash share", "pieces");
  for (unsigned seed : seeds) {
    rktest::FlakeShape shape;
    shape.seed = seed;
    const rktest::Flake f = rktest::knapped_flake(shape);
    const RidgeValleyResult r = compute_ridges_valleys(f.relief.mesh);
    const rktest::FlakeScore sc = rktest::score_flake(f, r.ridges, 2 * f.relief.mean_edge);
    const CurveStatistics st = curve_statistics(r.ridges, r.scale.edge, f.relief.mesh.n_faces());
    std::printf("%5u %8d %14.3f %10.3f %11.3f %11.3f %7lld\n", seed, f.relief.mesh.n_faces(), sc.aretes_found,
                sc.precision, sc.edge_found, st.dash_share(), st.pieces);
    if (!svg.empty()) write_svg(svg + std::to_string(seed) + ".svg", f, r.ridges);
  }
  return 0;
}
