// "Unroll Around Axis" (reliefkit/rollout/unroll.h) on pieces of known geometry
// (tests/support/turned.h): per case the time, the width against the circumference, the change of
// the edges' lengths from the input to the rollout (median, 90th percentile), the slope of the
// rollout's heights against the true relief, the largest change of a face's angles (90th
// percentile, degrees), the stretch the rollout reports and the share of the area left out (not
// the outer wall); then the time per million faces on regular and irregular triangles.
//   build/bench/bench_rollout [--size-only]   (the large cylinder also with its axis given: the time without the fit)
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "reliefkit/base/scale.h"
#include "reliefkit/rollout/unroll.h"
#include "turned.h"

using namespace reliefkit;
using rktest::TurnedOptions;
using rktest::TurnedShape;

namespace {

struct Case {
  const char* name;
  TurnedOptions options;
  BaseShape base;
  bool given_axis = false;  // the true axis given: the time without the fit
  Development development = Development::conformal;
};

// The largest change of a face's angles from the input to the sheet (with its heights), in degrees.
double angle_change(const TriMesh& input, const Rollout& r, const std::array<int, 3>& f) {
  auto angle_at = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    return std::acos(std::clamp((b - a).normalized().dot((c - a).normalized()), -1.0, 1.0));
  };
  auto flat = [&](int v) { return r.mesh.vertices[size_t(v)]; };  // on the sheet, with its relief
  auto in = [&](int v) { return input.vertices[size_t(r.source[size_t(v)])]; };
  double worst = 0;
  for (int k = 0; k < 3; ++k) {
    const int a = f[size_t(k)], b = f[size_t((k + 1) % 3)], c = f[size_t((k + 2) % 3)];
    worst = std::max(worst, std::abs(angle_at(flat(a), flat(b), flat(c)) - angle_at(in(a), in(b), in(c))));
  }
  return worst * 180 / M_PI;
}

// The least-squares slope of the wall's heights against the true relief.
double height_slope(const rktest::Turned& t, const Rollout& r) {
  double mx = 0, my = 0, sxy = 0, sxx = 0;
  const double n = double(r.wall_vertices);
  for (long i = 0; i < r.wall_vertices; ++i) mx += t.relief[size_t(r.source[size_t(i)])] / n, my += r.height[size_t(i)] / n;
  for (long i = 0; i < r.wall_vertices; ++i) {
    const double truth = t.relief[size_t(r.source[size_t(i)])] - mx;
    sxy += truth * (r.height[size_t(i)] - my), sxx += truth * truth;
  }
  return sxx > 0 ? sxy / sxx : NAN;
}

void run(const Case& c) {
  const rktest::Turned t = rktest::make_turned(c.options);
  UnrollParams p;
  p.base = c.base;
  p.development = c.development;
  if (c.given_axis) p.axis_source = AxisSource::given, p.given_axis = AxisLine{t.axis_point, t.axis_direction};
  const auto t0 = std::chrono::steady_clock::now();
  const Rollout r = unroll(Surface(t.mesh), p);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<double> change, angles;
  for (const auto& f : r.mesh.faces) {
    angles.push_back(angle_change(t.mesh, r, f));
    for (int k = 0; k < 3; ++k) {
      const int a = f[size_t(k)], b = f[size_t((k + 1) % 3)];
      const int oa = r.source[size_t(a)], ob = r.source[size_t(b)];
      const double before = (t.mesh.vertices[size_t(oa)] - t.mesh.vertices[size_t(ob)]).norm();
      if (before > 0) change.push_back(std::abs((r.mesh.vertices[size_t(a)] - r.mesh.vertices[size_t(b)]).norm() / before - 1));
    }
  }
  const double circumference = 2 * M_PI * t.middle_radius;
  std::printf("%-34s %8d %6.2f  %+6.2f %%  %6.2f %% / %6.2f %%  %6.2f  %6.3f  %6.2f %% / %6.2f %%  %5.1f %%\n", c.name, t.mesh.n_faces(),
              seconds, 100 * (r.width / circumference - 1), 100 * percentile(change, 0.5), 100 * percentile(change, 0.9),
              percentile(angles, 0.9), height_slope(t, r), 100 * r.stretch_median, 100 * r.stretch_p90, 100 * r.left_out_area_share);
}

TurnedOptions turned(TurnedShape shape, double relief, bool band, bool irregular, unsigned seed) {
  TurnedOptions o;
  o.shape = shape, o.relief = relief, o.band = band, o.irregular = irregular, o.seed = seed;
  if (shape == TurnedShape::globe) o.radius = 20, o.length = 24;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const bool size_only = argc > 1 && !std::strcmp(argv[1], "--size-only");
  std::printf("%-34s %8s %6s  %8s  %s  %s  %s  %s  %s\n", "case", "faces", "s", "width", "edges median / p90", "angles p90",
              "slope", "reported stretch median / p90", "left out");
  if (!size_only) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      run({"embossed cylinder, irregular", turned(TurnedShape::cylinder, 0.2, false, true, seed), BaseShape::smooth});
      run({"cone, carved band, straight", turned(TurnedShape::cone, -0.4, true, false, seed), BaseShape::straight});
      run({"cone, carved band, smooth", turned(TurnedShape::cone, -0.4, true, false, seed), BaseShape::smooth});
      run({"globular band, bumps", turned(TurnedShape::globe, 0.3, false, true, seed), BaseShape::smooth});
      run({"globular band, bumps, equal-area", turned(TurnedShape::globe, 0.3, false, true, seed), BaseShape::smooth, false,
           Development::equal_area});
      TurnedOptions seal = turned(TurnedShape::cylinder, -0.5, false, true, seed);
      seal.frieze = true, seal.closed = true;
      run({"closed pierced seal, carved frieze", seal, BaseShape::straight});
    }
  }
  for (bool irregular : {false, true}) {
    TurnedOptions big = turned(TurnedShape::cylinder, 0.2, false, irregular, 1);
    big.edge = 0.06;  // about 1.6 M faces
    run({irregular ? "cylinder ~1.6M irregular" : "cylinder ~1.6M regular", big, BaseShape::smooth});
    run({irregular ? "  the same, axis given" : "  the same, axis given", big, BaseShape::smooth, true});
  }
}
