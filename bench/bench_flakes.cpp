// Stone tools (issue 59): "Ridges and Valleys" at its defaults on synthetic knapped flakes whose
// arêtes are known exactly (tests/support/flakes.h: scars with faint ripples, a rough cortex,
// scanner noise 0.1 edge length, irregular triangles). Per seed: the share of the arêtes' length
// the ridges find and the share of the ridges' length on an arête or on the flake's edge (both
// within 2 edge lengths), the share of the edge found, the ridges' dash share and pieces.
//   build/bench/bench_flakes [--seeds 1,2,3]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>

#include "flakes.h"
#include "reliefkit/base/curve_selection.h"
#include "reliefkit/relief_edges/ridges.h"

using namespace reliefkit;

int main(int argc, char** argv) {
  std::vector<unsigned> seeds{1, 2, 3};
  if (argc == 3 && !std::strcmp(argv[1], "--seeds")) {
    seeds.clear();
    std::stringstream list(argv[2]);
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
    const double tol = 2 * f.relief.mean_edge;
    rktest::Relief lines = f.relief, edge = f.relief;
    lines.boundary.insert(lines.boundary.end(), f.edge.begin(), f.edge.end());
    edge.boundary = f.edge;
    const CurveStatistics st = curve_statistics(r.ridges, r.scale.edge, f.relief.mesh.n_faces());
    std::printf("%5u %8d %14.3f %10.3f %11.3f %11.3f %7lld\n", seed, f.relief.mesh.n_faces(),
                rktest::score(f.relief, r.ridges, tol).recall, rktest::score(lines, r.ridges, tol).precision,
                rktest::score(edge, r.ridges, tol).recall, st.dash_share(), st.pieces);
  }
  return 0;
}
