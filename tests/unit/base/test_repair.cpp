// Repair for the computation: each kind of damage an exporter produces, on a synthetic relief
// with a known step, must give the same curves as the undamaged mesh (or be refused).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "reliefkit/demarcating/demarcating.h"
#include "reliefkit/base/repair.h"
#include "reliefs.h"
#include "shapes.h"

using namespace reliefkit;

namespace {

rktest::Relief relief() {
  rktest::ReliefShape s;
  s.noise = 0.05;
  return rktest::disc_on_sphere(s, 5);
}

struct Outcome {
  rktest::Detection d;
  double length;
  size_t segments;
};

Outcome curves_of(const rktest::Relief& r, const TriMesh& mesh) {
  RepairedMesh rep = repair_for_computation(mesh);
  DemarcatingResult res = compute_demarcating(rep.mesh);
  return {rktest::score(r, res.curves, r.mean_edge), res.curves.total_length(), res.curves.segments.size()};
}

void expect_same(const Outcome& good, const Outcome& damaged, const char* what) {
  std::printf("%-28s recall %.3f precision %.3f, %zu segments, length %.6f\n", what, damaged.d.recall,
              damaged.d.precision, damaged.segments, damaged.length);
  EXPECT_EQ(damaged.segments, good.segments) << what;
  EXPECT_NEAR(damaged.length, good.length, 1e-9 * good.length) << what;
  // The same curves, their points listed in another order: the scores' sums may differ in the last bits.
  EXPECT_NEAR(damaged.d.recall, good.d.recall, 1e-12) << what;
  EXPECT_NEAR(damaged.d.precision, good.d.precision, 1e-12) << what;
}

}  // namespace

TEST(Repair, GoodMeshIsLeftAlone) {
  rktest::Relief r = relief();
  RepairedMesh rep = repair_for_computation(r.mesh);
  EXPECT_FALSE(rep.report.changed());
  EXPECT_EQ(rep.report.summary(), "");
  EXPECT_EQ(rep.mesh.faces, r.mesh.faces);
}

TEST(Repair, EveryKindOfDamageGivesTheGoodMeshCurves) {
  rktest::Relief r = relief();
  const Outcome good = curves_of(r, r.mesh);
  std::printf("%-28s recall %.3f precision %.3f, %zu segments\n", "good mesh", good.d.recall, good.d.precision,
              good.segments);
  ASSERT_GE(good.d.recall, 0.95);

  TriMesh flipped = r.mesh;  // every other face flipped, as some exporters deliver them
  for (size_t f = 0; f < flipped.faces.size(); f += 2) std::swap(flipped.faces[f][1], flipped.faces[f][2]);
  RepairedMesh rf = repair_for_computation(flipped);
  EXPECT_EQ(rf.report.flipped_faces, static_cast<long long>(flipped.faces.size() / 2));
  expect_same(good, curves_of(r, flipped), "every other face flipped");

  TriMesh inverted = r.mesh;  // a closed mesh inside out
  for (auto& f : inverted.faces) std::swap(f[1], f[2]);
  EXPECT_EQ(repair_for_computation(inverted).report.reversed_parts, 1);
  expect_same(good, curves_of(r, inverted), "closed mesh inside out");

  TriMesh soup;  // triangle soup: every face with vertices of its own (STL)
  for (const auto& f : r.mesh.faces) {
    const int b = soup.n_vertices();
    for (int j = 0; j < 3; ++j) soup.vertices.push_back(r.mesh.vertices[f[j]]);
    soup.faces.push_back({b, b + 1, b + 2});
  }
  RepairedMesh rs = repair_for_computation(soup);
  EXPECT_EQ(rs.report.welded_vertices, soup.n_vertices() - r.mesh.n_vertices());
  expect_same(good, curves_of(r, soup), "triangle soup");

  TriMesh doubled = r.mesh;  // every face listed twice
  doubled.faces.insert(doubled.faces.end(), r.mesh.faces.begin(), r.mesh.faces.end());
  EXPECT_EQ(repair_for_computation(doubled).report.duplicate_faces, r.mesh.n_faces());
  expect_same(good, curves_of(r, doubled), "every face duplicated");
}

TEST(Repair, NonOrientablePartIsLeftAsItWasAndSaid) {
  // A Moebius strip cannot be oriented coherently: the repair says so and changes nothing.
  TriMesh m;
  const int n = 60;
  for (int i = 0; i < n; ++i)
    for (int s = -1; s <= 1; s += 2) {
      double u = 2 * M_PI * i / n, w = 0.3 * s;
      m.vertices.push_back({(1 + w * std::cos(u / 2)) * std::cos(u), (1 + w * std::cos(u / 2)) * std::sin(u),
                            w * std::sin(u / 2)});
    }
  for (int i = 0; i < n; ++i) {
    int a = 2 * i, b = 2 * i + 1, c = 2 * ((i + 1) % n), d = c + 1;
    if (i == n - 1) std::swap(c, d);  // the half twist
    m.faces.push_back({a, c, b});
    m.faces.push_back({b, c, d});
  }
  RepairedMesh r = repair_for_computation(m);
  EXPECT_EQ(r.report.conflicting_parts, 1);
  EXPECT_EQ(r.report.flipped_faces, 0);
  EXPECT_EQ(r.mesh.faces, m.faces);
  EXPECT_NE(r.report.summary().find("cannot be oriented coherently"), std::string::npos);
}

TEST(Repair, OnlyAClosedPartInsideOutIsTurned) {
  // Three parts, their faces interleaved: a tetrahedron inside out, one the right way out, and an
  // open square. Every edge is traversed both ways, so no face needs turning to agree with its
  // neighbours: only the closed part with negative volume is turned, all of it.
  TriMesh m;
  auto tetrahedron = [&](Vec3 at, bool inward) {
    const int b = m.n_vertices();
    for (Vec3 p : {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)}) m.vertices.push_back(at + p);
    std::vector<std::array<int, 3>> f = {{b, b + 2, b + 1}, {b, b + 1, b + 3}, {b, b + 3, b + 2}, {b + 1, b + 2, b + 3}};
    if (inward)
      for (auto& t : f) std::swap(t[1], t[2]);
    return f;
  };
  const auto in = tetrahedron(Vec3(0, 0, 0), true), out = tetrahedron(Vec3(3, 0, 0), false);
  const int s = m.n_vertices();
  for (Vec3 p : {Vec3(0, 3, 0), Vec3(1, 3, 0), Vec3(1, 4, 0), Vec3(0, 4, 0)}) m.vertices.push_back(p);
  const std::vector<std::array<int, 3>> square = {{s, s + 1, s + 2}, {s, s + 2, s + 3}};
  for (int i = 0; i < 4; ++i) {
    m.faces.push_back(out[i]);
    if (i < 2) m.faces.push_back(square[i]);
    m.faces.push_back(in[i]);
  }
  RepairedMesh r = repair_for_computation(m);
  EXPECT_EQ(r.report.reversed_parts, 1);
  EXPECT_EQ(r.report.flipped_faces, 0);
  for (size_t f = 0; f < m.faces.size(); ++f) {
    const bool of_inward = std::find(in.begin(), in.end(), m.faces[f]) != in.end();
    auto want = m.faces[f];
    if (of_inward) std::swap(want[1], want[2]);
    EXPECT_EQ(r.mesh.faces[f], want) << "face " << f;
  }
}

TEST(Repair, FuzzerFindingsAreRefusedWithAMessage) {
  // tests/fuzz/regressions/repair-face-index-out-of-range: a face refers to a missing vertex.
  TriMesh bad = rktest::sphere(1, 1);
  bad.faces.push_back({0, 1, bad.n_vertices()});
  RepairedMesh r = repair_for_computation(bad);
  EXPECT_EQ(r.mesh.faces, bad.faces);
  EXPECT_THROW(compute_demarcating(bad), InputError);
  // tests/fuzz/regressions/presmoothing-overflow-huge-scale: edges of (almost) no length.
  TriMesh tiny = rktest::sphere(1e-300, 2);
  try {
    compute_demarcating(tiny);
    ADD_FAILURE() << "a mesh without usable edge length was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no usable edge length"), std::string::npos) << e.what();
  }
}
