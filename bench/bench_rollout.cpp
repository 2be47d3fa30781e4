// "Unroll Around Axis" (reliefkit/rollout/unroll.h) on pieces of known geometry
// (tests/support/turned.h): per case the time, the width against the circumference, the change of
// the edges' lengths from the input to the rollout (median, 90th percentile), the slope of the
// rollout's heights against the true relief, and the stretch the rollout reports; then the time
// per million faces on regular and irregular triangles.
//   build/bench/bench_rollout [--size-only]   (the large cylinder also with its axis given: the time without the fit)
#include <chrono>
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
};

void run(const Case& c) {
  const rktest::Turned t = rktest::make_turned(c.options);
  UnrollParams p;
  p.base = c.base;
  if (c.given_axis) p.axis_source = AxisSource::given, p.given_axis = AxisLine{t.axis_point, t.axis_direction};
  const auto t0 = std::chrono::steady_clock::now();
  const Rollout r = unroll(Surface(t.mesh), p);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const int n = t.mesh.n_vertices();
  std::vector<double> change;
  for (const auto& f : r.mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = f[size_t(k)], b = f[size_t((k + 1) % 3)];
      const int oa = a < n ? a : r.copy_of[size_t(a - n)], ob = b < n ? b : r.copy_of[size_t(b - n)];
      const double before = (t.mesh.vertices[size_t(oa)] - t.mesh.vertices[size_t(ob)]).norm();
      if (before > 0) change.push_back(std::abs((r.mesh.vertices[size_t(a)] - r.mesh.vertices[size_t(b)]).norm() / before - 1));
    }
  double mx = 0, my = 0, sxy = 0, sxx = 0;
  for (int i = 0; i < n; ++i) mx += t.relief[size_t(i)] / n, my += r.height[size_t(i)] / n;
  for (int i = 0; i < n; ++i) sxy += (t.relief[size_t(i)] - mx) * (r.height[size_t(i)] - my), sxx += (t.relief[size_t(i)] - mx) * (t.relief[size_t(i)] - mx);
  const double circumference = 2 * M_PI * t.middle_radius;
  std::printf("%-30s %8d %6.2f  %+6.2f %%  %6.2f %% / %6.2f %%  %6s  %6.2f %% / %6.2f %%\n", c.name, t.mesh.n_faces(), seconds,
              100 * (r.width / circumference - 1), 100 * percentile(change, 0.5), 100 * percentile(change, 0.9),
              sxx > 0 ? std::to_string(sxy / sxx).substr(0, 5).c_str() : "-", 100 * r.stretch_median, 100 * r.stretch_p90);
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
  std::printf("%-30s %8s %6s  %8s  %s  %s  %s\n", "case", "faces", "s", "width", "edges median / p90", "slope", "reported stretch median / p90");
  if (!size_only) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      run({"embossed cylinder, irregular", turned(TurnedShape::cylinder, 0.2, false, true, seed), BaseShape::smooth});
      run({"cone, carved band, straight", turned(TurnedShape::cone, -0.4, true, false, seed), BaseShape::straight});
      run({"cone, carved band, smooth", turned(TurnedShape::cone, -0.4, true, false, seed), BaseShape::smooth});
      run({"globular band, bumps", turned(TurnedShape::globe, 0.3, false, true, seed), BaseShape::smooth});
    }
  }
  for (bool irregular : {false, true}) {
    TurnedOptions big = turned(TurnedShape::cylinder, 0.2, false, irregular, 1);
    big.edge = 0.06;  // about 1.6 M faces
    run({irregular ? "cylinder ~1.6M irregular" : "cylinder ~1.6M regular", big, BaseShape::smooth});
    run({irregular ? "  the same, axis given" : "  the same, axis given", big, BaseShape::smooth, true});
  }
}
