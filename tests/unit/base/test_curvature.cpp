// Curvature and derivative tensor against closed forms: sphere, cylinder, torus, Monge patch.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "reliefkit/base/curvature.h"
#include "shapes.h"

using namespace reliefkit;
using rktest::median;

namespace {

struct TorusError {
  double k1, k2;  // median |error| / max|k|
};

TorusError torus_error(int nu, int nv, double jitter, CurvatureEstimator est = CurvatureEstimator::Jet) {
  const double R = 3, r = 1;
  TriMesh m = rktest::torus(R, r, nu, nv, jitter, 7);
  CurvatureOptions opt;
  opt.estimator = est;
  opt.derivatives = false;
  Curvature c = compute_curvature(m, opt);
  std::vector<double> e1, e2;
  for (int i = 0; i < m.n_vertices(); ++i) {
    double u, v;
    rktest::torus_params(R, r, m.vertices[i], u, v);
    e1.push_back(std::abs(c.k1[i] - 1 / r));
    e2.push_back(std::abs(c.k2[i] - std::cos(v) / (R + r * std::cos(v))));
  }
  return {median(e1) * r, median(e2) * r};
}

// Components of the cubic form given by (a,b,c,d) in frame (d1,d2), in the frame (x,y).
CurvatureDerivative in_frame(const CurvatureDerivative& t, const Vec3& d1, const Vec3& d2, const Vec3& x,
                             const Vec3& y) {
  auto form = [&](const Vec2& p, const Vec2& q, const Vec2& s) {
    double T[2][2][2] = {{{t.a, t.b}, {t.b, t.c}}, {{t.b, t.c}, {t.c, t.d}}};
    double r = 0;
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k) r += T[i][j][k] * p[i] * q[j] * s[k];
    return r;
  };
  Vec2 X(x.dot(d1), x.dot(d2)), Y(y.dot(d1), y.dot(d2));
  return {form(X, X, X), form(X, X, Y), form(X, Y, Y), form(Y, Y, Y)};
}

}  // namespace

TEST(Curvature, SphereIsUmbilicWithZeroDerivative) {
  for (double jitter : {0.0, 0.3}) {
    const double r = 2.0;
    TriMesh m = rktest::sphere(r, 5, jitter);
    Curvature c = compute_curvature(m);
    std::vector<double> e, dc;
    for (int i = 0; i < m.n_vertices(); ++i) {
      e.push_back(std::max(std::abs(c.k1[i] - 1 / r), std::abs(c.k2[i] - 1 / r)) * r);
      const auto& t = c.dcurv[i];
      dc.push_back(std::max({std::abs(t.a), std::abs(t.b), std::abs(t.c), std::abs(t.d)}) * r * r);
      EXPECT_GE(c.k1[i], c.k2[i]);
      EXPECT_NEAR(c.normal[i].dot(m.vertices[i].normalized()), 1.0, 1e-3);
    }
    EXPECT_LT(median(e), 3e-3) << "jitter " << jitter;
    EXPECT_LT(median(dc), jitter > 0 ? 0.05 : 0.01) << "jitter " << jitter;
    double area = 0;
    for (double a : c.point_area) area += a;
    EXPECT_NEAR(area, 4 * M_PI * r * r, 0.01 * 4 * M_PI * r * r);
    EXPECT_TRUE(c.bad_vertices.empty());
  }
}

TEST(Curvature, CylinderPrincipalValuesAndDirections) {
  const double r = 1.5;
  TriMesh m = rktest::cylinder(r, 4, 200, 100, 0.3);
  Curvature c = compute_curvature(m);
  std::vector<double> e1, e2, axis;
  for (int i = 0; i < m.n_vertices(); ++i) {
    if (std::abs(m.vertices[i].z()) > 1.5) continue;  // away from the open ends
    e1.push_back(std::abs(c.k1[i] - 1 / r) * r);
    e2.push_back(std::abs(c.k2[i]) * r);
    axis.push_back(std::abs(c.dir2[i].z()));  // minimal curvature runs along the axis
  }
  EXPECT_LT(median(e1), 5e-3);
  EXPECT_LT(median(e2), 5e-3);
  EXPECT_GT(median(axis), 0.999);
}

TEST(Curvature, TorusRegularAndJitteredWithinHalfPercent) {
  // >= 100 K faces: 400 x 128 x 2 = 102,400.
  for (double jitter : {0.0, 0.5}) {
    TorusError e = torus_error(400, 128, jitter);
    EXPECT_LE(e.k1, 0.005) << "jitter " << jitter;
    EXPECT_LE(e.k2, 0.005) << "jitter " << jitter;
  }
}

TEST(Curvature, FaceFitEstimatorOnRegularTorus) {
  TorusError e = torus_error(400, 128, 0.0, CurvatureEstimator::FaceFit);
  EXPECT_LE(e.k1, 0.005);
  EXPECT_LE(e.k2, 0.005);
  TorusError j = torus_error(400, 128, 0.5, CurvatureEstimator::FaceFit);
  std::printf("face-fit estimator, jittered 102K-face torus: median error k1 %.3f %%, k2 %.3f %%\n", 100 * j.k1,
              100 * j.k2);
}

TEST(Curvature, TorusErrorFallsWithRefinement) {
  for (double jitter : {0.0, 0.5}) {
    TorusError coarse = torus_error(100, 32, jitter), fine = torus_error(400, 128, jitter);
    EXPECT_LT(fine.k1, 0.5 * coarse.k1) << "jitter " << jitter;
    EXPECT_LT(fine.k2, 0.5 * coarse.k2) << "jitter " << jitter;
  }
}

// Monge patch z = (p x^2 + q y^2)/2 + (A x^3 + 3B x^2 y + 3C x y^2 + D y^3)/6 with normal +z.
// With ReliefKit's sign convention (curvature positive where the surface bends away from the
// normal) II = -Hessian at the origin, so k(x) = -p, k(y) = -q and the derivative tensor in the
// (x, y) frame is -(A, B, C, D).
struct MongeCase {
  double p = -1.0, q = -0.3, A = 0.6, B = -0.4, C = 0.25, D = 0.5;
  double z(double x, double y) const {
    return 0.5 * (p * x * x + q * y * y) + (A * x * x * x + 3 * B * x * x * y + 3 * C * x * y * y + D * y * y * y) / 6;
  }
};

static CurvatureDerivative monge_estimate(int n, double jitter, uint32_t seed, Curvature* out = nullptr,
                                          int* origin = nullptr) {
  MongeCase mc;
  int o = -1;
  TriMesh m = rktest::height_field([&](double x, double y) { return mc.z(x, y); }, 0.25, n, jitter, seed, &o);
  Curvature c = compute_curvature(m);
  CurvatureDerivative t = in_frame(c.dcurv[o], c.dir1[o], c.dir2[o], Vec3(1, 0, 0), Vec3(0, 1, 0));
  if (out) *out = c;
  if (origin) *origin = o;
  return t;
}

TEST(Curvature, MongePatchTensorRegularGrid) {
  MongeCase mc;
  Curvature c;
  int o;
  CurvatureDerivative t = monge_estimate(100, 0, 1, &c, &o);
  EXPECT_NEAR(c.k1[o], -mc.p, 0.01);
  EXPECT_NEAR(c.k2[o], -mc.q, 0.01);
  EXPECT_GT(std::abs(c.dir1[o].x()), 0.99);
  const double rel = std::max({std::abs(t.a + mc.A) / std::abs(mc.A), std::abs(t.b + mc.B) / std::abs(mc.B),
                               std::abs(t.c + mc.C) / std::abs(mc.C), std::abs(t.d + mc.D) / std::abs(mc.D)});
  std::printf("Monge tensor, regular grid: largest relative error of a..d %.2e\n", rel);
  EXPECT_LT(rel, 1e-4);  // measured 2.0e-5 (was a 5 % tolerance)
}

TEST(Curvature, MongePatchTensorJittered) {
  MongeCase mc;
  for (uint32_t seed : {1u, 2u, 3u}) {
    CurvatureDerivative t = monge_estimate(100, 0.5, seed);
    const double rel = std::max({std::abs(t.a + mc.A) / std::abs(mc.A), std::abs(t.b + mc.B) / std::abs(mc.B),
                                 std::abs(t.c + mc.C) / std::abs(mc.C), std::abs(t.d + mc.D) / std::abs(mc.D)});
    std::printf("Monge tensor, jittered (seed %u): largest relative error of a..d %.2e\n", seed, rel);
    EXPECT_LT(rel, 1e-3) << "seed " << seed;  // measured 0.8-3.6e-4 (was 10 %)
  }
}

// With quartic terms the cubic fit is no longer exact: the tensor must still come out within
// 10 % (median over jittered triangulations).
TEST(Curvature, MongePatchTensorWithQuarticTermsJittered) {
  MongeCase mc;
  std::vector<double> worst;
  for (uint32_t seed = 1; seed <= 9; ++seed) {
    int o = -1;
    TriMesh m = rktest::height_field(
        [&](double x, double y) { return mc.z(x, y) + 2.0 * (x * x * x * x + x * x * y * y + y * y * y * y); }, 0.25,
        100, 0.5, seed, &o);
    Curvature c = compute_curvature(m);
    CurvatureDerivative t = in_frame(c.dcurv[o], c.dir1[o], c.dir2[o], Vec3(1, 0, 0), Vec3(0, 1, 0));
    worst.push_back(std::max({std::abs(t.a + mc.A) / std::abs(mc.A), std::abs(t.b + mc.B) / std::abs(mc.B),
                              std::abs(t.c + mc.C) / std::abs(mc.C), std::abs(t.d + mc.D) / std::abs(mc.D)}));
  }
  std::printf("Monge tensor with quartic terms, jittered: median of the largest relative error %.2e\n", median(worst));
  EXPECT_LT(median(worst), 0.10);  // measured 0.066: the quartic terms the cubic fit cannot follow
}

TEST(Curvature, BoundaryVerticesOfAnOpenCylinder) {
  const double r = 1.5;
  TriMesh m = rktest::cylinder(r, 4, 200, 100, 0.3);
  Curvature c = compute_curvature(m);
  std::vector<double> e1, e2;
  for (int i = 0; i < m.n_vertices(); ++i) {
    if (std::abs(std::abs(m.vertices[i].z()) - 2) > 1e-9) continue;  // the two rims only
    ASSERT_TRUE(std::isfinite(c.k1[i]) && std::isfinite(c.dcurv[i].a));
    e1.push_back(std::abs(c.k1[i] - 1 / r) * r);
    e2.push_back(std::abs(c.k2[i]) * r);
  }
  ASSERT_EQ(e1.size(), 400u);
  EXPECT_LT(median(e1), 0.02);
  EXPECT_LT(median(e2), 0.02);
  EXPECT_TRUE(c.bad_vertices.empty());
}

TEST(Curvature, MongeTensorErrorFallsWithRefinement) {
  MongeCase mc;
  auto err = [&](int n) {
    CurvatureDerivative t = monge_estimate(n, 0, 1);
    return std::abs(t.a + mc.A) + std::abs(t.b + mc.B) + std::abs(t.c + mc.C) + std::abs(t.d + mc.D);
  };
  EXPECT_LT(err(100), err(26));
}

TEST(Curvature, DerivativeAlongMatchesCubic) {
  CurvatureDerivative t{1, 2, 3, 4};
  double th = 0.7, c = std::cos(th), s = std::sin(th);
  EXPECT_NEAR(t.along(c, s), c * c * c + 6 * c * c * s + 9 * c * s * s + 4 * s * s * s, 1e-12);
}
