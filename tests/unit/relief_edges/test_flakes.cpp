// The synthetic knapped flakes (flakes.h) whose arêtes the stone-tool tests of the curve filters
// are scored against: a closed surface, the arêtes and the flake's edge on it, and the arêtes
// where the dorsal surface creases (the faces on either side of an edge on them turn by several
// degrees, more than twice what they turn by anywhere two edge lengths away from them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "flakes.h"
#include "reliefkit/base/curve_selection.h"
#include "reliefkit/relief_edges/ridges.h"
#include "shapes.h"

using namespace reliefkit;

namespace {

// Each undirected edge's number of faces.
std::map<std::pair<int, int>, int> edge_faces(const TriMesh& m) {
  std::map<std::pair<int, int>, int> count;
  for (const auto& f : m.faces)
    for (int k = 0; k < 3; ++k) ++count[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}];
  return count;
}

}  // namespace

TEST(Flakes, AClosedLensWithItsAretesAndEdgeOnItsSurface) {
  rktest::FlakeShape shape;
  shape.noise = 0;  // the samples exactly on the surface but for the triangles' chords
  const rktest::Flake f = rktest::knapped_flake(shape);
  for (const auto& [edge, faces] : edge_faces(f.relief.mesh)) ASSERT_EQ(faces, 2) << edge.first << " " << edge.second;
  ASSERT_GT(f.relief.boundary.size(), 2000u);
  ASSERT_EQ(f.edge.size(), size_t(8 * shape.cells));
  const double h = f.relief.mean_edge;
  for (const auto* samples : {&f.relief.boundary, &f.edge}) {
    const std::vector<double> d = rktest::distance_to_surface(f.relief.mesh, *samples, 4 * h);
    EXPECT_LT(rktest::percentile(d, 0.99), 0.3 * h);
  }
}

TEST(Flakes, TheAretesAreCreasesOfTheDorsalSurface) {
  rktest::FlakeShape shape;
  shape.noise = 0, shape.ripple = 0, shape.roughness = 0;
  shape.cells = 80;
  const rktest::Flake f = rktest::knapped_flake(shape);
  const TriMesh& m = f.relief.mesh;
  // The dihedral angle across every interior dorsal edge, and whether an arête sample lies within
  // an edge length of its midpoint.
  std::map<std::pair<int, int>, std::vector<Vec3>> normals;
  for (const auto& t : m.faces) {
    const Vec3 n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).normalized();
    for (int k = 0; k < 3; ++k) normals[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}].push_back(n);
  }
  const double h = f.relief.mean_edge;
  std::vector<double> on_arete, elsewhere;
  for (const auto& [e, n] : normals) {
    const Vec3 mid = 0.5 * (m.vertices[e.first] + m.vertices[e.second]);
    if (n.size() != 2 || mid.z() < 0.02) continue;  // the dorsal face, away from its rim
    const double turn = std::acos(std::clamp(n[0].dot(n[1]), -1.0, 1.0)) * 180 / M_PI;
    double nearest = 1e300;
    for (const auto& p : f.relief.boundary) nearest = std::min(nearest, (p - mid).squaredNorm());
    if (std::sqrt(nearest) < 0.5 * h) on_arete.push_back(turn);
    if (std::sqrt(nearest) > 2 * h) elsewhere.push_back(turn);
  }
  ASSERT_GT(on_arete.size(), 200u);
  EXPECT_GT(rktest::median(on_arete), 5.0);
  EXPECT_LT(rktest::percentile(elsewhere, 0.99), 0.5 * rktest::median(on_arete));
}

// "Ridges and Valleys" at its defaults on a flake (seed 1, 102,400 faces): the flake's edge whole,
// no dashes, little on the cortex and the scars' ripples. Measured (bench/bench_flakes, seeds 1-3):
// edge found 0.998-1.000, precision 0.83-0.89, arêtes found 0.57-0.66, no dashes. Issue 59 asks for
// 0.9 of the arêtes: those missed lie between two scars, shallow creases beside the scars'
// ripples (bench_flakes --svg draws them; docs/curve-layers.md).
TEST(Flakes, RidgesAtDefaultsDrawTheEdgeWholeAndLittleElse) {
  rktest::FlakeShape shape;
  const rktest::Flake f = rktest::knapped_flake(shape);
  const RidgeValleyResult r = compute_ridges_valleys(f.relief.mesh);
  const rktest::FlakeScore sc = rktest::score_flake(f, r.ridges, 2 * f.relief.mean_edge);
  const CurveStatistics st = curve_statistics(r.ridges, r.scale.edge, f.relief.mesh.n_faces());
  std::printf("edge found %.3f, precision %.3f, arêtes found %.3f, dash share %.3f\n", sc.edge_found, sc.precision,
              sc.aretes_found, st.dash_share());
  EXPECT_GE(sc.edge_found, 0.98);
  EXPECT_GE(sc.precision, 0.78);
  EXPECT_GE(sc.aretes_found, 0.5);
  EXPECT_LE(st.dash_share(), 0.1);
}
