// "Vessel Axis and Profile" (reliefkit/pottery/vessel_record.h) on synthetic vessels and sherds of
// known axis and profile (tests/support/sherds.h): per case and seed, the time and the errors (axis
// angle, axis offset and profile as shares of the largest radius, rim diameter), the uncertainty
// the record states, and what "up" was decided from; then the time at about 1 M faces.
//   build/bench/bench_pottery [--seeds N] [--size-only] [--case TEXT]   (--case: only the cases whose name holds TEXT)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "sherds.h"

using namespace reliefkit;
using rktest::SherdOptions;
using rktest::VesselShape;

namespace {

struct Case {
  const char* name;
  SherdOptions options;
};

SherdOptions sherd(VesselShape shape, double span, double from, double to, double noise, bool irregular) {
  SherdOptions o;
  o.shape = shape, o.span_deg = span, o.from = from, o.to = to, o.noise = noise, o.irregular = irregular;
  return o;
}

void run(const Case& c, unsigned seed) {
  SherdOptions o = c.options;
  o.seed = seed;
  const rktest::Sherd sh = rktest::make_sherd(o);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const VesselRecord r = record_vessel(Surface(sh.mesh));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const rktest::SherdScore s = rktest::score_record(sh, r);
    std::printf("%-26s %u %8d %6.2f  %6.3f (%5.3f) %6.3f %%  %6.3f %% / %6.3f %%  %6.2f %% (%5.2f %%)  %s%s\n", c.name, seed,
                sh.mesh.n_faces(), seconds, s.angle_deg, r.angle_uncertainty_deg, 100 * s.offset, 100 * s.profile_median,
                100 * s.profile_p90, 100 * s.rim_diameter, sh.rim_diameter > 0 ? 100 * r.diameter_uncertainty / sh.rim_diameter : 0,
                s.up_right ? "" : "UPSIDE DOWN ", up_rule_name(r.up_rule));
    if (std::getenv("RK_VERBOSE")) std::printf("    up: %s\n", r.up_reason.c_str());
  } catch (const InputError& e) {
    std::printf("%-26s %u %8d refused: %s\n", c.name, seed, sh.mesh.n_faces(), e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  int seeds = 3;
  bool size_only = false;
  const char* only = "";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--seeds") && i + 1 < argc) seeds = std::atoi(argv[++i]);
    if (!std::strcmp(argv[i], "--case") && i + 1 < argc) only = argv[++i];
    if (!std::strcmp(argv[i], "--size-only")) size_only = true;
  }
  const Case cases[] = {
      {"jar whole", sherd(VesselShape::jar, 360, 0, 1, 0.05, false)},
      {"bowl whole", sherd(VesselShape::bowl, 360, 0, 1, 0.05, false)},
      {"beaker half", sherd(VesselShape::beaker, 180, 0.2, 1, 0.1, true)},
      {"jar rim sherd 30%", sherd(VesselShape::jar, 108, 0.7, 1, 0.1, true)},
      {"bowl rim sherd 20%", sherd(VesselShape::bowl, 72, 0.5, 1, 0.1, true)},
      {"jar rim sherd 10%", sherd(VesselShape::jar, 36, 0.75, 1, 0.1, true)},
      {"bowl base sherd 25%", sherd(VesselShape::bowl, 90, 0, 0.5, 0.1, true)},
      {"jar body sherd 25 deg", sherd(VesselShape::jar, 25, 0.55, 0.8, 0.1, true)},
      {"beaker body sherd 25 deg", sherd(VesselShape::beaker, 25, 0.35, 0.65, 0.1, true)},
  };
  if (!size_only) {
    std::printf("%-26s %s %8s %6s  %s\n", "case", "seed", "faces", "s", "angle deg (stated)  offset  profile median / p90  rim diameter (stated)  up");
    for (const Case& c : cases)
      if (std::strstr(c.name, only))
        for (unsigned seed = 1; seed <= unsigned(seeds); ++seed) run(c, seed);
    SherdOptions special = sherd(VesselShape::jar, 108, 0.4, 1, 0.1, true);
    special.out_of_round = 0.01;
    if (std::strstr("jar 30% out of round 1%", only))
      for (unsigned seed = 1; seed <= unsigned(seeds); ++seed) run({"jar 30% out of round 1%", special}, seed);
    special = sherd(VesselShape::jar, 360, 0, 1, 0.05, false);
    special.out_of_round = 0.01;
    if (std::strstr("jar whole out of round 1%", only))
      for (unsigned seed = 1; seed <= unsigned(seeds); ++seed) run({"jar whole out of round 1%", special}, seed);
    special = sherd(VesselShape::jar, 108, 0.4, 1, 0.1, true);
    special.incised = true;
    if (std::strstr("jar 30% incised", only)) run({"jar 30% incised", special}, 1);
  }
  if (*only) return 0;
  // Size: a half jar at about 1 M faces (edge 0.125 mm), regular and irregular triangles.
  for (bool irregular : {false, true}) {
    SherdOptions big = sherd(VesselShape::jar, 180, 0.2, 1, 0.1, irregular);
    big.edge = 0.25;  // about 1.2 M faces
    run({irregular ? "half jar 1M irregular" : "half jar 1M regular", big}, 1);
  }
}
