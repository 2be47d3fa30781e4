// Prominent field, enhancement and coloring (thesis chapter 6) on synthetic reliefs with known
// answers: a raised disc (the true prominent direction is radial near its rim) and a ridge along a
// circle; the enhancement restores an eroded step and is compared with the bilateral filter of
// Fleishman et al. 2003 (implemented below, independently of the core) and MeshLab's "Taubin
// Smooth" at its defaults (vcglib's own VertexCoordTaubin, the code MeshLab runs).
#include <gtest/gtest.h>

// clang-format off
#include <vcg/complex/complex.h>
#include <vcg/complex/algorithms/smooth.h>
#include <vcg/complex/algorithms/update/flag.h>
// clang-format on

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "reliefkit/base/angles.h"
#include "reliefkit/base/work_counts.h"
#include "reliefkit/prominent/prominent.h"
#include "reliefs.h"
#include "shapes.h"

using namespace reliefkit;

namespace {


// Angle between two lines (directions without sign), degrees.
double line_angle(const Vec3& a, const Vec3& b) {
  const double c = std::abs(a.normalized().dot(b.normalized()));
  return std::acos(std::min(1.0, c)) * kDegreesPerRadian;
}

// A ridge along the circle of radius 0.5: height `height` x exp(-(r - 0.5)^2 / 2 width^2) on the
// square [-1, 1]^2 (150 x 150 cells, jittered), with Gaussian noise of `noise` edge lengths in z.
reliefkit::TriMesh ridge_circle(double height, double width, double noise) {
  reliefkit::TriMesh m = rktest::height_field(
      [&](double x, double y) {
        const double d = std::hypot(x, y) - 0.5;
        return height * std::exp(-d * d / (2 * width * width));
      },
      1.0, 150, 0.3, 1);
  rktest::Rng rng(7);
  const double e = 2.0 / 150;
  for (auto& v : m.vertices) v.z() += noise * e * rng.normal();
  return m;
}

struct FieldScore {
  double median_error;  // degrees, vertices within `band` of the circle r = 0.5
  double median_strength;
  double neighbour_angle_away;  // mean angle between neighbouring field lines away from the feature
};

// The true prominent direction near the circle is radial (tangent plane: that of the surface).
FieldScore field_score(const reliefkit::TriMesh& m, const ProminentFieldResult& r, double band) {
  std::vector<double> err, strength;
  std::vector<char> away(m.vertices.size(), 0);
  for (int v = 0; v < m.n_vertices(); ++v) {
    const Vec3& x = m.vertices[v];
    if (std::abs(x.x()) > 0.9 || std::abs(x.y()) > 0.9) continue;
    const double rr = std::hypot(x.x(), x.y());
    if (std::abs(rr - 0.5) < band && rr > 0) {
      const Vec3 radial(x.x() / rr, x.y() / rr, 0);
      const Vec3& n = r.curvature->normal[v];
      err.push_back(line_angle(r.field[v], radial - n * n.dot(radial)));
      strength.push_back(r.strength[v]);
    } else if (std::abs(rr - 0.5) > 3 * band) {
      away[v] = 1;
    }
  }
  double sum = 0;
  long cnt = 0;
  const VertexRing& ring = r.topology->ring;
  for (int v = 0; v < m.n_vertices(); ++v)
    if (away[v])
      for (int k = ring.offset[v]; k < ring.offset[v + 1]; ++k)
        if (away[ring.vertex[k]]) sum += line_angle(r.field[v], r.field[ring.vertex[k]]), ++cnt;
  return {rktest::median(err), rktest::median(strength), cnt ? sum / cnt : 0};
}

}  // namespace

TEST(ProminentField, PerpendicularToTheFeaturesAndSmoothElsewhereAtTenPercentNoise) {
  rktest::ReliefShape s;
  s.noise = 0.1;
  const rktest::Relief disc = rktest::disc_on_plane(s, 150);
  const ProminentFieldResult rd = compute_prominent_field(disc.mesh);
  const FieldScore d = field_score(disc.mesh, rd, 2 * s.width);
  const reliefkit::TriMesh ridge = ridge_circle(0.03, 0.015, 0.1);
  const ProminentFieldResult rr = compute_prominent_field(ridge);
  const FieldScore g = field_score(ridge, rr, 2 * 0.015);
  std::printf("[prominent field, 10 %% noise] step (disc): median angle to the true direction %.2f deg, mean angle "
              "between neighbours away from it %.2f deg; ridge (circle): %.2f deg, %.2f deg; feature points %lld + "
              "%lld / %lld + %lld; solve %s\n",
              d.median_error, d.neighbour_angle_away, g.median_error, g.neighbour_angle_away, rd.ridge_points,
              rd.edge_points, rr.ridge_points, rr.edge_points, rd.solve.summary().c_str());
  // Measured: 1.19 and 0.91 deg (the bound: 10); neighbours 2.01 / 1.60 deg. Bounds about
  // twice that (they were 5 and 8 deg).
  EXPECT_LE(d.median_error, 2.5);
  EXPECT_LE(g.median_error, 2.0);
  EXPECT_LE(d.neighbour_angle_away, 4.0);
  EXPECT_LE(g.neighbour_angle_away, 3.5);
  for (const Vec3& f : rd.field) ASSERT_TRUE(f.allFinite() && std::abs(f.norm() - 1) < 1e-6);
}

// Eq. 6.2 between its ends (0 < alpha < 1), which the reliefs above never reach: an elliptic
// Gaussian bump whose curvature across its long axis is 2.5 x that along it at the top (alpha
// 0.75 there), falling to 0 where the ratio passes 4. Every vertex's alpha must follow eq. 6.2
// from its principal curvatures, and its prominent direction must be alpha g + (1 - alpha) t
// (Definition 6.3.1; g the relief direction, t the first principal direction): the weight on g
// grows towards relief edges (alpha 1), that on t towards ridges (alpha 0).
TEST(ProminentField, BetweenRidgeAndEdgeTheDirectionBlendsAsEq62Says) {
  const double sx = 0.1, sy = std::sqrt(2.5) * sx;
  const reliefkit::TriMesh m = rktest::height_field(
      [&](double x, double y) { return 0.05 * std::exp(-x * x / (2 * sx * sx) - y * y / (2 * sy * sy)); }, 1.0, 120, 0.3, 3);
  const ProminentFieldResult r = compute_prominent_field(m);
  const double k0 = r.curvature_threshold;
  double worst_alpha = 0, worst_angle = 0, sum = 0;
  int n = 0;
  for (int v = 0; v < m.n_vertices(); ++v) {
    const double a1 = std::abs(r.curvature->k1[v]), a2 = std::abs(r.curvature->k2[v]);
    const double big = std::max(a1, a2), small = std::min(a1, a2), k = small > 0 ? big / small : 1e300;
    const double alpha = big < k0 || k < 2 ? 1.0 : k > 4 ? 0.0 : (4 - k) / 2;  // eq. 6.2
    worst_alpha = std::max(worst_alpha, std::abs(r.alpha[v] - alpha));
    const Vec3 &g = r.relief_direction[v], &t = r.principal[v];
    // Where the two weights differ and the two directions do (elsewhere a swap would not show).
    if (!(alpha > 0 && alpha < 1 && std::abs(alpha - 0.5) > 0.1 && line_angle(g, t) > 20)) continue;
    const Vec3 want = (alpha * g + (1 - alpha) * t).normalized();
    const double err = std::acos(std::clamp(want.dot(r.prominent[v]), -1.0, 1.0)) * kDegreesPerRadian;
    worst_angle = std::max(worst_angle, err), sum += err, ++n;
  }
  std::printf("[prominent direction, 0 < alpha < 1] %d vertices with alpha in (0, 0.4) or (0.6, 1) and g, t over 20 deg "
              "apart; largest alpha error %.2e; angle to alpha g + (1 - alpha) t: mean %.2e, largest %.2e deg\n",
              n, worst_alpha, n ? sum / n : 0.0, worst_angle);
  // Measured: alpha exact, the direction 1.5e-6 deg off at most (rounding of acos near 1); with
  // the blend's weights swapped ((1 - alpha) g + alpha t): 26 deg on average, 59 at most.
  ASSERT_GE(n, 20);  // 278
  EXPECT_LT(worst_alpha, 1e-12);
  EXPECT_LT(worst_angle, 1e-5);
}

TEST(ProminentField, LineFieldKeepsWhatTheVectorSystemCancels) {
  // Along a ridge the relief direction points up both flanks, towards the crest from either side:
  // the same line, opposite vectors. The vector system of eq. 6.6 averages them away at the crest.
  const reliefkit::TriMesh ridge = ridge_circle(0.03, 0.015, 0.1);
  ProminentFieldParams p;
  const ProminentFieldResult line = compute_prominent_field(ridge, p);
  p.representation = FieldRepresentation::Vector;
  const ProminentFieldResult vec = compute_prominent_field(ridge, p);
  const FieldScore l = field_score(ridge, line, 0.5 * 0.015), v = field_score(ridge, vec, 0.5 * 0.015);
  std::printf("[line vs vector field, ridge crest] median angle error %.2f vs %.2f deg; median |z| %.3f vs %.3f; "
              "neighbours away %.2f vs %.2f deg\n",
              l.median_error, v.median_error, l.median_strength, v.median_strength, l.neighbour_angle_away,
              v.neighbour_angle_away);
  EXPECT_GT(v.median_error, 2 * l.median_error);
  EXPECT_LT(v.median_strength, 0.75 * l.median_strength);
}

// ---- Enhancement ----

namespace {

// Fleishman, Drori, Cohen-Or, "Bilateral mesh denoising", SIGGRAPH 2003: every vertex moves along
// its (mollified) normal by the bilateral average of its neighbours' heights over its tangent
// plane, neighbours within 2 sigma_c; sigma_s = 0.5 sigma_c as in the thesis. Brute force.
std::vector<Vec3> fleishman(const reliefkit::TriMesh& m, std::vector<Vec3> pos, double sigma_c, int iterations) {
  const int nv = m.n_vertices();
  for (int it = 0; it < iterations; ++it) {
    std::vector<Vec3> fn(m.faces.size());
    for (size_t f = 0; f < m.faces.size(); ++f) {
      const auto& t = m.faces[f];
      fn[f] = (pos[t[1]] - pos[t[0]]).cross(pos[t[2]] - pos[t[0]]);  // area-weighted
    }
    // Faces and vertices near each vertex, found on a uniform grid of cell 2 sigma_c.
    const double cell = 2 * sigma_c;
    auto key = [&](const Vec3& x) {
      return std::array<long, 2>{long(std::floor(x.x() / cell)), long(std::floor(x.y() / cell))};
    };
    std::map<std::array<long, 2>, std::vector<int>> vgrid, fgrid;
    for (int v = 0; v < nv; ++v) vgrid[key(pos[v])].push_back(v);
    for (size_t f = 0; f < m.faces.size(); ++f) {
      const auto& t = m.faces[f];
      fgrid[key((pos[t[0]] + pos[t[1]] + pos[t[2]]) / 3)].push_back(int(f));
    }
    std::vector<Vec3> out = pos;
    for (int v = 0; v < nv; ++v) {
      const auto k = key(pos[v]);
      Vec3 n = Vec3::Zero();
      for (long dx = -1; dx <= 1; ++dx)
        for (long dy = -1; dy <= 1; ++dy) {
          auto it2 = fgrid.find({k[0] + dx, k[1] + dy});
          if (it2 == fgrid.end()) continue;
          for (int f : it2->second) {
            const auto& t = m.faces[f];
            if (((pos[t[0]] + pos[t[1]] + pos[t[2]]) / 3 - pos[v]).norm() <= sigma_c) n += fn[f];
          }
        }
      if (!(n.norm() > 0)) continue;
      n.normalize();
      double sum = 0, wsum = 0;
      for (long dx = -1; dx <= 1; ++dx)
        for (long dy = -1; dy <= 1; ++dy) {
          auto it2 = vgrid.find({k[0] + dx, k[1] + dy});
          if (it2 == vgrid.end()) continue;
          for (int j : it2->second) {
            const double t = (pos[j] - pos[v]).norm();
            if (t > 2 * sigma_c) continue;
            const double h = n.dot(pos[j] - pos[v]);
            const double w = std::exp(-t * t / (2 * sigma_c * sigma_c)) *
                             std::exp(-h * h / (2 * 0.25 * sigma_c * sigma_c));
            sum += w * h, wsum += w;
          }
        }
      out[v] = pos[v] + n * (sum / wsum);
    }
    pos.swap(out);
  }
  return pos;
}

// MeshLab's "Taubin Smooth" at its defaults (lambda 0.5, mu -0.53, 10 steps): vcglib's code.
class TV;
class TF;
struct TUsed : public vcg::UsedTypes<vcg::Use<TV>::AsVertexType, vcg::Use<TF>::AsFaceType> {};
class TV : public vcg::Vertex<TUsed, vcg::vertex::Coord3d, vcg::vertex::Normal3d, vcg::vertex::BitFlags> {};
class TF : public vcg::Face<TUsed, vcg::face::VertexRef, vcg::face::BitFlags> {};
class TM : public vcg::tri::TriMesh<std::vector<TV>, std::vector<TF>> {};

std::vector<Vec3> meshlab_taubin(const reliefkit::TriMesh& m) {
  TM t;
  auto vi = vcg::tri::Allocator<TM>::AddVertices(t, m.n_vertices());
  for (int v = 0; v < m.n_vertices(); ++v, ++vi) vi->P() = vcg::Point3d(m.vertices[v].x(), m.vertices[v].y(), m.vertices[v].z());
  for (const auto& f : m.faces) vcg::tri::Allocator<TM>::AddFace(t, &t.vert[f[0]], &t.vert[f[1]], &t.vert[f[2]]);
  vcg::tri::UpdateFlags<TM>::FaceBorderFromNone(t);
  vcg::tri::Smooth<TM>::VertexCoordTaubin(t, 10, 0.5f, -0.53f, false);
  std::vector<Vec3> out(m.n_vertices());
  for (int v = 0; v < m.n_vertices(); ++v) out[v] = Vec3(t.vert[v].P()[0], t.vert[v].P()[1], t.vert[v].P()[2]);
  return out;
}

struct ShapeScore {
  double rms, rms_near;  // distance to the clean surface, edge lengths: all / within 2 widths of the rim
  double slope;          // steepest slope of the radial profile (binned means)
};

ShapeScore shape_score(const rktest::Relief& clean, const std::vector<Vec3>& pos, double band, double edge) {
  const std::vector<double> d = rktest::distance_to_surface(clean.mesh, pos, 0.04);  // reach: the step height
  double s = 0, sn = 0;
  long n = 0, nn = 0;
  constexpr int kBins = 120;
  std::vector<double> sum(kBins, 0);
  std::vector<int> cnt(kBins, 0);
  for (size_t v = 0; v < pos.size(); ++v) {
    const Vec3& x = clean.mesh.vertices[v];
    if (std::abs(x.x()) > 0.9 || std::abs(x.y()) > 0.9) continue;
    s += d[v] * d[v], ++n;
    if (std::abs(std::hypot(x.x(), x.y()) - 0.5) < band) sn += d[v] * d[v], ++nn;
    const int b = int((std::hypot(pos[v].x(), pos[v].y()) - 0.3) / 0.4 * kBins);
    if (b >= 0 && b < kBins) sum[b] += pos[v].z(), ++cnt[b];
  }
  double slope = 0;
  for (int b = 1; b < kBins; ++b)
    if (cnt[b] && cnt[b - 1]) slope = std::max(slope, std::abs(sum[b] / cnt[b] - sum[b - 1] / cnt[b - 1]) / (0.4 / kBins));
  return {std::sqrt(s / n) / edge, std::sqrt(sn / nn) / edge, slope};
}

}  // namespace

constexpr double kRestoreStrength = 12;

TEST(ProminentEnhancement, RestoresAnErodedStepBetterThanBilateralAndTaubin) {
  // The clean relief: a sharp step (tanh width 0.6 edge lengths). The scan: the same step eroded
  // (width 3 edge lengths) with 20 % noise.
  rktest::ReliefShape sharp;
  sharp.width = 0.008;
  const rktest::Relief clean = rktest::disc_on_plane(sharp, 150);
  rktest::ReliefShape eroded;
  const rktest::Relief worn = rktest::disc_on_plane(eroded, 150);
  eroded.noise = 0.2;
  const rktest::Relief noisy = rktest::disc_on_plane(eroded, 150);
  const double e = noisy.mean_edge, band = 2 * eroded.width;

  // Restoring a worn step goes beyond what the noisy scan supports: strength 12 (1 keeps within
  // the noise: near the step 0.446 here, as Taubin's 0.461).
  EnhanceParams restore;
  restore.strength = kRestoreStrength;
  const EnhanceResult en = enhance_relief(noisy.mesh, restore);
  const std::vector<Vec3> fl = fleishman(noisy.mesh, noisy.mesh.vertices, en.spatial_scale, EnhanceParams::kDefaultBilateralIterations);
  const std::vector<Vec3> tb = meshlab_taubin(noisy.mesh);
  const ShapeScore s_in = shape_score(clean, noisy.mesh.vertices, band, e), s_worn = shape_score(clean, worn.mesh.vertices, band, e),
                   s_fl = shape_score(clean, fl, band, e), s_tb = shape_score(clean, tb, band, e),
                   s_b = shape_score(clean, en.bilateral, band, e), s_r = shape_score(clean, en.positions, band, e);
  std::printf("[enhancement: eroded disc step, 20 %% noise; distance to the sharp clean step, RMS in edge lengths]\n"
              "| surface | all | near the step | steepest slope |\n|---|---|---|---|\n");
  auto row = [](const char* name, const ShapeScore& s) {
    std::printf("| %s | %.3f | %.3f | %.2f |\n", name, s.rms, s.rms_near, s.slope);
  };
  row("scan (eroded + noise)", s_in);
  row("eroded, without noise", s_worn);
  row("Fleishman et al. 2003 bilateral", s_fl);
  row("MeshLab Taubin Smooth (defaults)", s_tb);
  row("prominent bilateral (step 1)", s_b);
  row("prominent enhancement (steps 1 + 2)", s_r);
  row("clean sharp step", shape_score(clean, clean.mesh.vertices, band, e));
  std::printf("flow: %d iterations (automatic stop %s), %lld vertices stopped at their local height extremum; "
              "sigma_c %.2f edge lengths\n",
              en.flow_iterations, en.converged ? "reached" : "not reached", en.at_extremum, en.spatial_scale / e);
  EXPECT_LT(s_r.rms, s_fl.rms);           // measured 0.127 vs 0.231
  EXPECT_LT(s_r.rms_near, s_tb.rms_near);  // measured 0.232 vs 0.461
  EXPECT_LT(s_r.rms_near, 0.75 * s_tb.rms_near);
  EXPECT_GE(s_r.slope, s_worn.slope);      // measured 3.66 vs 0.79 (clean 3.63)
  EXPECT_TRUE(en.converged);
  // The strength trades faithfulness for legibility: at 1 the flow moves within the noise, at
  // kRestoreStrength far more (and to the clean step's slope, above).
  const EnhanceResult faithful = enhance_relief(noisy.mesh);
  auto motion = [](const EnhanceResult& x) {
    double m = 0;
    for (double u : x.height_change) m += std::abs(u);
    return m / x.height_change.size();
  };
  std::printf("mean height change: strength 1 %.4f, strength %g %.4f edge lengths\n", motion(faithful) / e,
              kRestoreStrength, motion(en) / e);
  EXPECT_GT(motion(en), 2 * motion(faithful));
  EXPECT_LT(shape_score(clean, faithful.positions, band, e).slope, s_r.slope);

  // No vertex beyond the local height extremum, even when the flow runs long and the curvature
  // cap is lifted (strength 100, 60 iterations): the step-1 surface's heights (z: the base is the
  // plane) within the stopping rule's radius, found by brute force here. The rule measures heights
  // along the estimated base normal, which near the step leans by up to `lean` from z: heights
  // of neighbours at distance rho differ by up to rho sin(lean) between the two frames.
  EnhanceParams hard;
  hard.strength = 100;
  hard.flow_iterations = 60;
  const EnhanceResult r = enhance_relief(noisy.mesh, hard);
  const auto& b = r.bilateral;
  double lean = 0;
  for (int v = 0; v < noisy.mesh.n_vertices(); ++v)
    lean = std::max(lean, std::acos(std::min(1.0, r.field.base.normal[v].z())));
  const double allowed = r.extremum_radius * std::sin(lean) + 0.01 * e;
  double worst = 0, worst_excess = -1e300;
  const double rho = r.extremum_radius;
  std::map<std::array<long, 2>, std::vector<int>> grid;
  auto cell = [&](const Vec3& x) { return std::array<long, 2>{long(std::floor(x.x() / rho)), long(std::floor(x.y() / rho))}; };
  for (int v = 0; v < noisy.mesh.n_vertices(); ++v) grid[cell(b[v])].push_back(v);
  for (int v = 0; v < noisy.mesh.n_vertices(); ++v) {
    double lo = b[v].z(), hi = b[v].z();
    const auto c = cell(b[v]);
    for (long dx = -1; dx <= 1; ++dx)
      for (long dy = -1; dy <= 1; ++dy) {
        auto it = grid.find({c[0] + dx, c[1] + dy});
        if (it != grid.end())
          for (int j : it->second)
            if ((b[j] - b[v]).norm() <= rho) lo = std::min(lo, b[j].z()), hi = std::max(hi, b[j].z());
      }
    const double z = r.positions[v].z();
    const double lean_v = std::acos(std::min(1.0, r.field.base.normal[v].z()));
    worst = std::max(worst, std::max(z - hi, lo - z));
    worst_excess = std::max(worst_excess, std::max(z - hi, lo - z) - (rho * std::sin(lean_v) + 0.01 * e));
  }
  std::printf("60 flow iterations at strength 100: largest excursion beyond the local height extremum (z): %.4f edge "
              "lengths (base normals lean by up to %.2f deg: %.4f allowed); beyond each vertex's own allowance "
              "rho sin(lean): %.4f\n", worst / e, lean * kDegreesPerRadian, allowed / e, worst_excess / e);
  EXPECT_LE(worst, allowed);
  EXPECT_LE(worst_excess, 0.0);
}

TEST(ProminentEnhancement, StepOneDenoisesASmoothReliefBetterThanBilateralAndTaubin) {
  // A relief that is smooth by design (tanh width 3 edge lengths) under 20 % noise: the flow would
  // sharpen it, so users switch it off (flow iterations 0) and keep step 1.
  rktest::ReliefShape s;
  const rktest::Relief clean = rktest::disc_on_plane(s, 150);
  s.noise = 0.2;
  const rktest::Relief noisy = rktest::disc_on_plane(s, 150);
  const double e = noisy.mean_edge, band = 2 * s.width;
  EnhanceParams p;
  p.flow_iterations = 0;
  const EnhanceResult r = enhance_relief(noisy.mesh, p);
  const ShapeScore s_in = shape_score(clean, noisy.mesh.vertices, band, e),
                   s_fl = shape_score(clean, fleishman(noisy.mesh, noisy.mesh.vertices, r.spatial_scale,
                                                       EnhanceParams::kDefaultBilateralIterations), band, e),
                   s_tb = shape_score(clean, meshlab_taubin(noisy.mesh), band, e),
                   s_r = shape_score(clean, r.positions, band, e);
  std::printf("[smooth disc step, 20 %% noise; distance to the clean surface, RMS in edge lengths]\n"
              "| surface | all | near the step | steepest slope |\n|---|---|---|---|\n");
  for (const auto& [name, sc] : {std::pair{"scan", s_in}, std::pair{"Fleishman et al. 2003 bilateral", s_fl},
                                 std::pair{"MeshLab Taubin Smooth (defaults)", s_tb},
                                 std::pair{"prominent bilateral (step 1, flow off)", s_r},
                                 std::pair{"clean", shape_score(clean, clean.mesh.vertices, band, e)}})
    std::printf("| %s | %.3f | %.3f | %.2f |\n", name, sc.rms, sc.rms_near, sc.slope);
  EXPECT_EQ(r.flow_iterations, 0);
  EXPECT_LT(s_r.rms, s_fl.rms);            // measured 0.041 vs 0.064
  EXPECT_LT(s_r.rms_near, 0.8 * s_tb.rms_near);  // measured 0.053 vs 0.071
  EXPECT_LT(s_r.rms_near, 0.5 * s_fl.rms_near);  // the prominent term keeps the step: 0.053 vs 0.147
}

// The steepest slope of a disc relief's radial profile: mean heights in rings one edge length wide
// (narrower rings measure the noise: the scan's own profile came out 1.4x steeper than the clean
// one's with rings a quarter edge wide).
double steepest_slope(const std::vector<Vec3>& pos, double edge) {
  const int bins = int(0.4 / edge);
  std::vector<double> sum(bins, 0);
  std::vector<int> cnt(bins, 0);
  for (const Vec3& x : pos) {
    const int b = int((std::hypot(x.x(), x.y()) - 0.3) / edge);
    if (b >= 0 && b < bins) sum[b] += x.z(), ++cnt[b];
  }
  double slope = 0;
  for (int b = 1; b < bins; ++b)
    if (cnt[b] && cnt[b - 1]) slope = std::max(slope, std::abs(sum[b] / cnt[b] - sum[b - 1] / cnt[b - 1]) / edge);
  return slope;
}

// Enhancing must not invent relief: on noisy copies of reliefs whose clean surface is known (steps
// from 1 to 3 edge lengths wide, 10 and 20 % noise), the enhanced step is no steeper than the
// clean one (within 0.9-1.2 of its steepest slope) and nearer to the clean surface than Taubin
// Smooth near the step.
TEST(ProminentEnhancement, SharpensNoMoreThanTheCleanSurface) {
  std::printf("[enhancement at defaults on noisy reliefs; slope: steepest radial slope / the clean one's; near: "
              "RMS distance to the clean surface within 2 widths of the step, edge lengths]\n"
              "| step width | noise | scan slope | enhanced slope | Taubin slope | scan near | enhanced near | Taubin near |\n"
              "|---|---|---|---|---|---|---|---|\n");
  for (double width : {0.04, 0.015})
    for (double noise : {0.1, 0.2}) {
      rktest::ReliefShape s;
      s.width = width;
      const rktest::Relief clean = rktest::disc_on_plane(s, 150);
      s.noise = noise;
      const rktest::Relief noisy = rktest::disc_on_plane(s, 150);
      const double e = noisy.mean_edge, band = 2 * std::max(width, 2 * e);
      const EnhanceResult enhanced = enhance_relief(noisy.mesh);
      const std::vector<Vec3> taubin = meshlab_taubin(noisy.mesh);
      const ShapeScore in = shape_score(clean, noisy.mesh.vertices, band, e),
                       en = shape_score(clean, enhanced.positions, band, e), tb = shape_score(clean, taubin, band, e);
      const double slope_c = steepest_slope(clean.mesh.vertices, e), slope_in = steepest_slope(noisy.mesh.vertices, e),
                   slope_en = steepest_slope(enhanced.positions, e), slope_tb = steepest_slope(taubin, e);
      std::printf("| %.1f | %.0f %% | %.2f | %.2f | %.2f | %.3f | %.3f | %.3f |\n", width / e, 100 * noise,
                  slope_in / slope_c, slope_en / slope_c, slope_tb / slope_c, in.rms_near, en.rms_near, tb.rms_near);
      EXPECT_GE(slope_en, 0.9 * slope_c);
      EXPECT_LE(slope_en, 1.2 * slope_c);
      EXPECT_LT(en.rms_near, tb.rms_near);
    }
}

// ---- Coloring ----

TEST(ProminentColoring, MonotoneInTheProminentCurvatureAndScaleFree) {
  rktest::ReliefShape s;
  s.noise = 0.05;
  const rktest::Relief disc = rktest::disc_on_plane(s, 100);
  const ProminentFieldResult f = compute_prominent_field(disc.mesh);
  const ColoringResult c = curvature_coloring(*f.curvature, &f.field, f.scale.counts, ColoringCurvature::Prominent, 1.0);
  // Monotone: sorted by kappa_p, the grey never decreases.
  std::vector<int> order(c.curvature.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = int(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return c.curvature[a] < c.curvature[b]; });
  for (size_t i = 1; i < order.size(); ++i) ASSERT_LE(c.grey[order[i - 1]], c.grey[order[i]]);
  EXPECT_LT(c.grey[order.front()], 0.2);  // the most concave dark, the most convex light
  EXPECT_GT(c.grey[order.back()], 0.8);
  // Contrast 1 puts the reference curvature, the 90th percentile of the counted |kappa_p| (found
  // here by sorting), at grey 0.75 (0.25 concave): a tenth of the counted vertices lie beyond.
  std::vector<double> counted;
  for (size_t v = 0; v < c.curvature.size(); ++v)
    if (f.scale.counts[v] && c.curvature[v] != 0) counted.push_back(std::abs(c.curvature[v]));
  std::sort(counted.begin(), counted.end());
  const double ref = counted[size_t(0.9 * double(counted.size() - 1))];
  long beyond = 0;
  for (size_t v = 0; v < c.curvature.size(); ++v)
    if (f.scale.counts[v] && c.curvature[v] != 0 && std::abs(c.grey[v] - 0.5) > 0.25) ++beyond;
  const double share = double(beyond) / double(counted.size());
  std::printf("[prominent coloring] reference |kappa_p| %.4g, lambda %.4g (1 / reference: %.4g); counted vertices beyond "
              "grey 0.25 / 0.75: %.5f (of %zu)\n", ref, c.lambda, 1 / ref, share, counted.size());
  // Measured: lambda exactly 1 / reference, 0.09999 beyond (of 10,201). With the 50th percentile as
  // the reference: lambda 22 x larger, 0.50 beyond.
  EXPECT_NEAR(c.lambda * ref, 1.0, 1e-12);
  EXPECT_NEAR(share, 0.1, 5e-4);
  for (size_t v = 0; v < order.size(); ++v)  // kappa_p is the curvature along the field
    ASSERT_NEAR(c.curvature[v], f.curvature->normal_curvature(int(v), f.field[v]), 1e-9);
  // x 1000: the same colours.
  reliefkit::TriMesh big = disc.mesh;
  for (auto& x : big.vertices) x *= 1000;
  const ProminentFieldResult fb = compute_prominent_field(big);
  const ColoringResult cb = curvature_coloring(*fb.curvature, &fb.field, fb.scale.counts, ColoringCurvature::Prominent, 1.0);
  double worst = 0;
  for (size_t v = 0; v < c.grey.size(); ++v) worst = std::max(worst, std::abs(c.grey[v] - cb.grey[v]));
  std::printf("[prominent coloring] lambda %.4g (mesh x1: %.4g, x1000: %.4g); largest grey difference x1 vs x1000: %.2e\n",
              c.lambda, c.lambda, cb.lambda, worst);
  EXPECT_LT(worst, 1e-3);
  EXPECT_NEAR(cb.lambda, 1000 * c.lambda, 1e-3 * cb.lambda);
}

// ---- Bad input ----

TEST(ProminentBadInput, RefusedWithAClearMessage) {
  auto message = [](auto f) -> std::string {
    try {
      f();
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  reliefkit::TriMesh empty;
  EXPECT_NE(message([&] { compute_prominent_field(empty); }).find("empty"), std::string::npos);
  reliefkit::TriMesh cloud;
  cloud.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_NE(message([&] { compute_prominent_field(cloud); }).find("point cloud"), std::string::npos);
  reliefkit::TriMesh nan = rktest::sphere(1, 2);
  nan.vertices[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message([&] { compute_prominent_field(nan); }), "");
  const reliefkit::TriMesh ok = rktest::sphere(1, 3);
  for (double theta : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    ProminentFieldParams p;
    p.theta = theta;
    EXPECT_NE(message([&] { compute_prominent_field(ok, p); }).find("theta"), std::string::npos) << theta;
  }
  for (double sc : {0.0, -2.0}) {
    EnhanceParams p;
    p.spatial_scale = Length::in_edges(sc);
    EXPECT_NE(message([&] { enhance_relief(ok, p); }).find("sigma_c"), std::string::npos) << sc;
  }
  const ProminentFieldResult f = compute_prominent_field(ok);
  for (double lambda : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()})
    EXPECT_NE(message([&] { curvature_coloring(*f.curvature, &f.field, {}, ColoringCurvature::Prominent, lambda); })
                  .find("lambda"),
              std::string::npos)
        << lambda;
}

TEST(ProminentBadInput, AwkwardMeshesGiveFiniteResults) {
  // Non-manifold (a fin on a plane), a degenerate face, and a closed sphere (no feature at all).
  reliefkit::TriMesh m = rktest::height_field([](double x, double y) { return 0.05 * std::tanh((x - 0.1 * y) / 0.05); }, 1, 30);
  const int a = m.faces[100][0], b = m.faces[100][1];
  m.vertices.push_back((m.vertices[a] + m.vertices[b]) / 2 + Vec3(0, 0, 0.2));
  m.faces.push_back({a, b, m.n_vertices() - 1});
  m.faces.push_back({a, a, b});
  for (const reliefkit::TriMesh& mesh : {m, rktest::sphere(1, 3)}) {
    EnhanceParams p;
    p.flow_iterations = 5;
    const EnhanceResult r = enhance_relief(mesh, p);
    for (size_t v = 0; v < r.positions.size(); ++v) {
      ASSERT_TRUE(r.positions[v].allFinite()) << v;
      ASSERT_TRUE(r.field.field[v].allFinite()) << v;
    }
    const ColoringResult c = curvature_coloring(*r.field.curvature, &r.field.field, {}, ColoringCurvature::Prominent, 1);
    for (double g : c.grey) ASSERT_TRUE(g > 0 && g < 1);
  }
}

// On the run's Surface the field and the enhancement build the scan's adjacency, scale and noise
// once (the noise-floor patch has its own one each) and one Laplacian: the base normals' clamped
// one, which the field's solve shares. The field reads chapter 4's per-vertex fields and takes
// its relief-edge tilt threshold from Relief Edges' weak hysteresis tilt.
TEST(ProminentField, OnTheRunsSurfaceTheGeometryIsComputedOnce) {
  rktest::ReliefShape shape;
  shape.noise = 0.1;
  const rktest::Relief disc = rktest::disc_on_plane(shape, 60);
  const Surface surface = Surface::borrow(disc.mesh);
  reset_work_counts();
  EnhanceParams p;
  p.flow_iterations = 2;
  const EnhanceResult r = enhance_relief(surface, p);
  const WorkCounts c = work_counts();
  EXPECT_EQ(c[Work::NoiseFloor], 1) << c.summary();
  EXPECT_EQ(c[Work::Adjacency], 1 + c[Work::NoiseFloor]) << c.summary();
  EXPECT_EQ(c[Work::MeshScale], 1 + c[Work::NoiseFloor]) << c.summary();
  EXPECT_EQ(c[Work::Noise], 1 + c[Work::NoiseFloor]) << c.summary();
  EXPECT_EQ(c[Work::Laplacian], 1) << c.summary();
  const ReliefEdgeResult edges = compute_relief_edges(surface);
  EXPECT_EQ(r.field.tilt_threshold, edges.weak_angle);
  EXPECT_EQ(r.field.relief_direction, edges.direction);
  EXPECT_EQ(r.field.fit_error, edges.fit_error);
}
