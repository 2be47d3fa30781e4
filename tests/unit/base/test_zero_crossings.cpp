#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "reliefkit/base/curvature.h"
#include "reliefkit/base/curve_selection.h"
#include "reliefkit/base/surface.h"
#include "reliefkit/base/zero_crossings.h"
#include "shapes.h"

using namespace reliefkit;

namespace {
TriMesh plane(int n, double jitter = 0.3) {
  return rktest::height_field([](double, double) { return 0.0; }, 1.0, n, jitter, 5);
}
std::vector<Vec3> up(const TriMesh& m) { return std::vector<Vec3>(m.n_vertices(), Vec3(0, 0, 1)); }
}  // namespace

// f(v, t) = (x - 0.3) * (t . X): along the field t = X its zero set is the line x = 0.3.
TEST(ZeroCrossings, StraightLineIsExactAndChained) {
  TriMesh m = plane(40);
  DirectionalField fld;
  fld.direction.assign(m.n_vertices(), Vec3(1, 0, 0));
  fld.value_along = [&](int v, const Vec3& t) { return (m.vertices[v].x() - 0.3) * t.x(); };
  for (int v = 0; v < m.n_vertices(); ++v) fld.value.push_back(fld.value_along(v, fld.direction[v]));
  fld.strength.assign(m.n_vertices(), 1.0);
  Polylines p = extract_zero_crossings(m, up(m), fld);
  ASSERT_FALSE(p.points.empty());
  for (const auto& q : p.points) EXPECT_NEAR(q.x(), 0.3, 1e-12);
  EXPECT_NEAR(p.total_length(), 2.0, 1e-9);
  auto ch = p.chains();
  ASSERT_EQ(ch.size(), 1u);
  EXPECT_EQ(ch[0].size(), p.points.size());
  EXPECT_EQ(p.rejected_faces, 0);
  // Threshold: nothing survives a strength above every point's.
  ZeroCrossingOptions strong;
  strong.min_strength = 2.0;
  EXPECT_TRUE(extract_zero_crossings(m, up(m), fld, strong).segments.empty());
}

TEST(ZeroCrossings, ClosedCircleChainsIntoOneLoop) {
  TriMesh m = plane(60);
  DirectionalField fld;
  fld.direction.assign(m.n_vertices(), Vec3(1, 0, 0));
  fld.value_along = [&](int v, const Vec3&) { return m.vertices[v].norm() - 0.5; };
  for (int v = 0; v < m.n_vertices(); ++v) fld.value.push_back(fld.value_along(v, fld.direction[v]));
  Polylines p = extract_zero_crossings(m, up(m), fld);
  auto ch = p.chains();
  ASSERT_EQ(ch.size(), 1u);
  EXPECT_EQ(ch[0].front(), ch[0].back());
  EXPECT_NEAR(p.total_length(), 2 * M_PI * 0.5, 0.01);
}

TEST(ZeroCrossings, InconsistentDirectionsAreRejectedOrRepaired) {
  TriMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.faces = {{0, 1, 2}};
  std::vector<Vec3> n(3, Vec3(0, 0, 1));
  DirectionalField fld;
  // f(v, t) = t.x * (x - 0.5): only meaningful along x.
  fld.value_along = [&](int v, const Vec3& t) { return t.x() * (m.vertices[v].x() - 0.5); };
  // Vertices 0 and 1 agree (along x); vertex 2 points along y: it is re-evaluated along x.
  fld.direction = {Vec3(1, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  for (int v = 0; v < 3; ++v) fld.value.push_back(fld.value_along(v, fld.direction[v]));
  EXPECT_EQ(fld.value[2], 0.0);  // its own value is meaningless (zero)
  Polylines p = extract_zero_crossings(m, n, fld);
  ASSERT_EQ(p.segments.size(), 1u);
  for (const auto& q : p.points) EXPECT_NEAR(q.x(), 0.5, 1e-12);  // crossings on edges 0-1 and 1-2
  // No pair within pi/4: the face is dropped.
  fld.direction = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, 0.1, 0).normalized()};
  for (int v = 0; v < 3; ++v) fld.value[v] = fld.value_along(v, fld.direction[v]);
  Polylines q = extract_zero_crossings(m, n, fld);
  EXPECT_TRUE(q.segments.empty());
  EXPECT_EQ(q.rejected_faces, 1);
}

TEST(ZeroCrossings, AxialFieldsIgnoreDirectionSign) {
  TriMesh m = plane(40);
  DirectionalField fld;
  fld.axial = true;
  fld.value_along = [&](int v, const Vec3& t) { return (m.vertices[v].y() + 0.2) * t.y(); };
  rktest::Rng rng(9);
  for (int v = 0; v < m.n_vertices(); ++v) {
    fld.direction.push_back(rng.uniform() < 0.5 ? Vec3(0, 1, 0) : Vec3(0, -1, 0));
    fld.value.push_back(fld.value_along(v, fld.direction.back()));
  }
  Polylines p = extract_zero_crossings(m, up(m), fld);
  ASSERT_FALSE(p.points.empty());
  for (const auto& q : p.points) EXPECT_NEAR(q.y(), -0.2, 1e-12);
  EXPECT_NEAR(p.total_length(), 2.0, 1e-9);
}

TEST(ZeroCrossings, DropShortChains) {
  TriMesh m = plane(60);
  DirectionalField fld;
  fld.direction.assign(m.n_vertices(), Vec3(1, 0, 0));
  // A long line x = 0.3 and a small circle of radius 0.06 around (-0.5, 0).
  fld.value_along = [&](int v, const Vec3&) {
    const Vec3& p = m.vertices[v];
    return (std::hypot(p.x() + 0.5, p.y()) - 0.06) * (p.x() - 0.3);
  };
  for (int v = 0; v < m.n_vertices(); ++v) fld.value.push_back(fld.value_along(v, fld.direction[v]));
  Polylines p = extract_zero_crossings(m, up(m), fld);
  EXPECT_EQ(p.chains().size(), 2u);
  Polylines q = drop_short_chains(p, 1.0);
  EXPECT_EQ(q.chains().size(), 1u);
  EXPECT_NEAR(q.total_length(), 2.0, 1e-3);
}

TEST(ZeroCrossings, SizeMismatchIsAnError) {
  TriMesh m = plane(4);
  DirectionalField fld;
  fld.value_along = [](int, const Vec3&) { return 0.0; };
  EXPECT_THROW(extract_zero_crossings(m, up(m), fld), InputError);
}

TEST(LinkGaps, JoinsEndsThatFaceEachOtherOnly) {
  // Two collinear pieces with a gap of 2 (joined), a third piece turning away at a right angle
  // beyond the gap's end (not joined: its end does not face the others), and a short piece whose
  // own two ends are close (not closed onto itself).
  Polylines c;
  auto piece = [&c](std::vector<Vec3> pts) {
    const int base = static_cast<int>(c.points.size());
    for (const auto& p : pts) {
      c.points.push_back(p);
      c.strength.push_back(1);
    }
    for (size_t i = 1; i < pts.size(); ++i) {
      c.segments.push_back({base + int(i) - 1, base + int(i)});
      c.segment_face.push_back(0);
    }
  };
  piece({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}});
  piece({{5, 0, 0}, {6, 0, 0}, {7, 0, 0}, {8, 0, 0}});
  piece({{10, 1, 0}, {10, 2, 0}, {10, 3, 0}});
  piece({{0, 5, 0}, {0.5, 5.5, 0}, {0, 6, 0}});
  const size_t before = c.segments.size();
  EXPECT_EQ(link_gaps(c, 2.5, 0.785), 1);
  ASSERT_EQ(c.segments.size(), before + 1);
  EXPECT_EQ(c.points[c.segments.back()[0]].x() + c.points[c.segments.back()[1]].x(), 8.0);  // 3 -> 5
  EXPECT_EQ(c.chains().size(), 3u);
  // Gaps wider than max_gap stay open.
  Polylines d;
  std::swap(c, d);
  piece({{0, 0, 0}, {1, 0, 0}});
  piece({{4, 0, 0}, {5, 0, 0}});
  EXPECT_EQ(link_gaps(c, 2.5, 0.785), 0);
}

// A line broken and shifted sideways by less than a triangle (its ends side by side, 0.4 apart
// across it, overlapping by 0.2) is a jog and is joined; shifted by 1.5 it is two lines.
TEST(LinkGaps, JoinsAJogButNotTwoParallelLines) {
  auto two_pieces = [](double shift) {
    Polylines c;
    for (int piece = 0; piece < 2; ++piece) {
      const int base = static_cast<int>(c.points.size());
      for (int i = 0; i < 5; ++i) {
        const double x = piece == 0 ? i : 3.8 + i;
        c.points.push_back({x, piece == 0 ? 0.0 : shift, 0});
        c.strength.push_back(1);
      }
      for (int i = 1; i < 5; ++i) c.segments.push_back({base + i - 1, base + i}), c.segment_face.push_back(0);
    }
    return c;
  };
  Polylines jog = two_pieces(0.4), apart = two_pieces(1.5);
  EXPECT_EQ(link_gaps(jog, 3.0, kLinkTurn), 1);
  EXPECT_EQ(jog.chains().size(), 1u);
  EXPECT_EQ(link_gaps(apart, 3.0, kLinkTurn), 0);
}

namespace {
// A straight polyline from `from` to `to` in `n` segments, every point of strength 1.
Polylines straight(const Vec3& from, const Vec3& to, int n) {
  Polylines c;
  for (int i = 0; i <= n; ++i) {
    c.points.push_back(from + (to - from) * (double(i) / n));
    c.strength.push_back(1);
    c.point_edge.push_back({i, i + 1});
    c.point_weight.push_back(0.5);
  }
  for (int i = 0; i < n; ++i) c.segments.push_back({i, i + 1}), c.segment_face.push_back(i);
  return c;
}
}  // namespace

// Which segments of one curve set lie within a radius of another's, including when the other's
// segments are far longer than the radius (a decimated mesh's long faces).
TEST(CurveProximity, SegmentsNearFindsThoseWithinTheRadius) {
  const Polylines base = straight({0, 0, 0}, {40, 0, 0}, 40), one_long = straight({0, 0, 0}, {40, 0, 0}, 1);
  const Polylines inside = straight({0, 1.5, 0}, {40, 1.5, 0}, 80), outside = straight({0, 2.5, 0}, {40, 2.5, 0}, 80);
  for (const Polylines* by : {&base, &one_long}) {
    for (char k : segments_near(inside, *by, 2.0)) EXPECT_EQ(k, 1);
    for (char k : segments_near(outside, *by, 2.0)) EXPECT_EQ(k, 0);
  }
  EXPECT_EQ(segments_near(inside, Polylines{}, 2.0), std::vector<char>(80, 0));
}

TEST(CurveProximity, AppendedCurvesKeepTheirOwnPoints) {
  Polylines c = straight({0, 0, 0}, {1, 0, 0}, 2);
  append_curves(c, straight({0, 5, 0}, {1, 5, 0}, 3));
  ASSERT_EQ(c.points.size(), 7u);
  ASSERT_EQ(c.segments.size(), 5u);
  EXPECT_EQ(c.point_edge.size(), 7u);
  EXPECT_EQ(c.segments[2][0], 3);  // the appended line's first segment starts at its own first point
  EXPECT_DOUBLE_EQ(c.points[c.segments[4][1]].y(), 5.0);
  EXPECT_EQ(c.chains().size(), 2u);
  EXPECT_NEAR(c.total_length(), 2.0, 1e-12);
}

// A long line 30 edges long with a branch (one piece), a dash 4 edges long, and a loop 4 x 2 = 8
// edges around (a dash too): 3 pieces, 2 dashes, 12 of 42 edge lengths in dashes.
TEST(CurveStatistics, PiecesAreJoinedSegmentsAndDashesThoseUnderTenEdges) {
  Polylines c;
  auto piece = [&c](std::vector<Vec3> pts, int join_to = -1) {
    const int base = static_cast<int>(c.points.size());
    for (const auto& p : pts) c.points.push_back(p), c.strength.push_back(1);
    if (join_to >= 0) c.segments.push_back({join_to, base}), c.segment_face.push_back(0);
    for (size_t i = 1; i < pts.size(); ++i) c.segments.push_back({base + int(i) - 1, base + int(i)}), c.segment_face.push_back(0);
  };
  piece({{0, 0, 0}, {25, 0, 0}});
  piece({{10, 1, 0}, {10, 5, 0}}, 0);  // from (0,0,0): sqrt(101) + 4 long, the line's branch
  piece({{0, 10, 0}, {4, 10, 0}});
  piece({{0, 20, 0}, {2, 20, 0}, {2, 22, 0}, {0, 22, 0}, {0, 20, 0}});
  c.points.push_back({50, 50, 0}), c.strength.push_back(1);  // a point no segment uses: not drawn
  const CurveStatistics st = curve_statistics(c, 1.0, 2000);
  EXPECT_EQ(st.pieces, 3);
  EXPECT_EQ(st.dashes, 2);
  const double line = 25 + std::sqrt(101.0) + 4;
  EXPECT_NEAR(st.length, line + 4 + 8, 1e-9);
  EXPECT_NEAR(st.dash_share(), 12 / (line + 12), 1e-9);
  EXPECT_NEAR(st.length_per_kface, (line + 12) / 2, 1e-9);
  EXPECT_EQ(curve_statistics(c, 0.1, 2000).dashes, 0);  // at a tenth of the edge, nothing is under 10 edges
  EXPECT_EQ(curve_statistics(Polylines{}, 1.0, 10).pieces, 0);
}

// Pieces of 12, 6 and 9.5 long and a branched one (8 + 4 through a shared point), min length 10:
// the 12 and the branched piece stay, whatever the strengths.
TEST(DropDashes, PiecesShorterThanTheLengthGoWholeBranchesCountingTogether) {
  Polylines c;
  auto piece = [&c](std::vector<Vec3> pts, int id) {
    const int base = static_cast<int>(c.points.size());
    for (const auto& p : pts) c.points.push_back(p), c.strength.push_back(5.0);
    for (size_t i = 1; i < pts.size(); ++i) c.segments.push_back({base + int(i) - 1, base + int(i)}), c.segment_face.push_back(id);
  };
  piece({{0, 0, 0}, {6, 0, 0}, {12, 0, 0}}, 0);
  piece({{0, 1, 0}, {6, 1, 0}}, 1);
  piece({{0, 2, 0}, {9.5, 2, 0}}, 2);
  piece({{0, 3, 0}, {4, 3, 0}, {8, 3, 0}}, 3);
  piece({{4, 3, 0}, {4, 7, 0}}, 3);  // a branch from the middle point: drawn as its own point, joined below
  c.segments.back()[0] = c.segments[c.segments.size() - 2][1] - 1;  // (4, 3): the branched piece's middle point
  const Polylines kept = drop_dashes(c, 10.0);
  std::vector<int> faces = kept.segment_face;
  std::sort(faces.begin(), faces.end());
  EXPECT_EQ(faces, (std::vector<int>{0, 0, 3, 3, 3}));
  EXPECT_EQ(drop_dashes(c, 0.0).segments.size(), c.segments.size());
}

// The contrast of k1 (local_contrast, radius 8 edge lengths): a crease on a smooth plane stands
// far out of its surroundings; the crests of a sinusoid (ripples 8 edge lengths apart) stand
// about π/2 spreads above them, a rough surface's own level, below kLineContrast.
TEST(LocalContrast, ACreaseStandsOutOfItsSurroundingsRipplesDoNot) {
  auto contrast_at_line = [](const std::function<double(double, double)>& z) {
    const TriMesh m = rktest::height_field(z, 1.0, 100, 0.3, 3);
    const Surface s = Surface::borrow(m);
    const Curvature c = compute_curvature(m);
    const double h = s.scale().edge;
    const std::vector<double> contrast = local_contrast(s, c.k1, 8 * h);
    double best = 0;  // the largest contrast within an edge length of the line x = 0, away from the border
    for (int v = 0; v < m.n_vertices(); ++v)
      if (std::abs(m.vertices[v].x()) < h && std::abs(m.vertices[v].y()) < 0.5) best = std::max(best, contrast[v]);
    return best;
  };
  const double crease = contrast_at_line([](double x, double) { return -0.1 * std::abs(x); });
  const double ripple = contrast_at_line([](double x, double) { return 0.004 * std::cos(2 * M_PI * x / 0.16); });
  std::printf("contrast at the crease %.2f, at a ripple's crest %.2f\n", crease, ripple);
  EXPECT_GT(crease, 2 * kLineContrast);
  EXPECT_LT(ripple, kLineContrast);
  EXPECT_GT(ripple, 1.0);
}
