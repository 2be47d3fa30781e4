// libFuzzer harness over the algorithm cores: a mesh and the parameters from raw bytes (NaN and
// infinite coordinates and parameters, indices out of range, coincident vertices, degenerate and
// duplicated faces all come out of it). A core must either succeed or throw InputError — any
// crash, sanitizer report, other exception or non-finite output is a finding.
//
// Input layout (missing bytes read as zero):
//   u8 vertices (mod 48) | u8 faces (mod 96) | u8 flags | f32 presmoothing | f32 threshold |
//   vertices x 3 coordinates (f32, or i8 when flags bit 3 is set: a coarse grid, so that
//   vertices coincide) | faces x 3 u8 vertex indices (mod vertices + 1: one past the end happens)
// flags bits 0-1: which core (demarcating, ridges and valleys, relief edges, curvature);
// bit 2: pre-smoothing given (else "auto"); bit 4: ridges and valleys / relief edges run
// multi-scale (the pre-smoothing value is then the smallest scale); bit 5 with core 3: the
// prominent enhancement (field, bilateral filter, 3 flow iterations) and coloring, theta = threshold.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "reliefkit/demarcating/demarcating.h"
#include "reliefkit/multiscale/multiscale.h"
#include "reliefkit/prominent/prominent.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefkit/base/curvature.h"
#include "reliefkit/base/repair.h"
#include "reliefkit/relief_edges/ridges.h"

using namespace reliefkit;

namespace {

struct Reader {
  const uint8_t* data;
  size_t size, pos = 0;
  uint8_t u8() { return pos < size ? data[pos++] : 0; }
  float f32() {
    uint8_t b[4] = {u8(), u8(), u8(), u8()};
    float f;
    std::memcpy(&f, b, 4);
    return f;
  }
};

void check_finite(const Polylines& p) {
  for (const auto& x : p.points)
    if (!x.allFinite()) std::abort();
  for (double s : p.strength)
    if (std::isnan(s)) std::abort();
}

// The multi-scale range: the smallest scale from the input when given (the largest 16, or the
// smallest when above), else the defaults.
OptimalScaleOptions scales(uint8_t flags, float smallest) {
  OptimalScaleOptions o;
  if (flags & 4) {
    o.min_scale_edges = smallest;
    if (std::isfinite(smallest) && smallest > o.max_scale_edges) o.max_scale_edges = smallest;
  }
  o.max_scale_auto = true;
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Reader in{data, size};
  const int nv = in.u8() % 48, nf = in.u8() % 96;
  const uint8_t flags = in.u8();
  const float presmoothing = in.f32(), threshold = in.f32();
  TriMesh m;
  for (int v = 0; v < nv; ++v) {
    if (flags & 8)
      m.vertices.emplace_back(int8_t(in.u8()), int8_t(in.u8()), int8_t(in.u8()));
    else
      m.vertices.emplace_back(in.f32(), in.f32(), in.f32());
  }
  for (int f = 0; f < nf; ++f) {
    const int mod = nv + 1;
    m.faces.push_back({in.u8() % mod, in.u8() % mod, in.u8() % mod});
  }
  const Length smooth = (flags & 4) ? Length::in_edges(presmoothing) : Length::automatic();
  try {
    (void)repair_for_computation(m);
    switch (flags & 3) {
      case 0: {
        DemarcatingParams p;
        p.presmoothing = smooth;
        p.relative_threshold = threshold;
        check_finite(compute_demarcating(m, p).curves);
        break;
      }
      case 1: {
        RidgeValleyParams p;
        p.presmoothing = smooth;
        p.relative_threshold = threshold;
        RidgeValleyResult r = (flags & 16) ? multiscale_ridges_valleys(m, scales(flags, presmoothing), p).curves
                                           : compute_ridges_valleys(m, p);
        check_finite(r.ridges);
        check_finite(r.valleys);
        break;
      }
      case 2: {
        ReliefEdgeParams p;
        p.presmoothing = smooth;
        p.strong_angle = std::isfinite(threshold) ? std::fabs(threshold) : threshold;
        check_finite((flags & 16) ? multiscale_relief_edges(m, scales(flags, presmoothing), p).curves.edges
                                  : compute_relief_edges(m, p).edges);
        break;
      }
      default: {
        if (flags & 32) {
          EnhanceParams p;
          p.field.presmoothing = smooth;
          p.field.theta = threshold;
          p.flow_iterations = 3;
          const EnhanceResult e = enhance_relief(m, p);
          for (size_t v = 0; v < e.positions.size(); ++v)
            if (!e.positions[v].allFinite() || !e.field.field[v].allFinite()) std::abort();
          const ColoringResult c = curvature_coloring(*e.field.curvature, &e.field.field, {}, ColoringCurvature::Prominent, 1);
          for (double g : c.grey)
            if (!(g >= 0 && g <= 1)) std::abort();
          break;
        }
        ScaledCurvature c = curvature_at_scale(m, smooth, CurvatureEstimator::Jet, nullptr);
        for (size_t v = 0; v < c.curvature->k1.size(); ++v)
          if (!std::isfinite(c.curvature->k1[v]) || !std::isfinite(c.curvature->k2[v])) std::abort();
      }
    }
  } catch (const InputError&) {
    // refused with a message: fine
  }
  return 0;
}
