// ReliefKit — the optimal scale of every vertex for ridges & valleys (thesis sections 5.3 and
// 5.5.1): the surface is taken through its scale space (reliefkit/scale_space.h); at each level
// the strength f = max(|k1|, |k2|) is measured at every vertex, and the scale at which t^γ f
// peaks is selected (reliefkit/scale_selection.h), t = σ² the Gaussian's variance.
// For a Gaussian ridge of width s0 (variance s0²) and γ = 1 the selected σ is √2 s0.
// This is the raw selection (eq. 5.2); filling in featureless regions (eq. 5.3) comes next.
#pragma once

#include <vector>

#include "reliefkit/mesh.h"

namespace reliefkit {

struct OptimalScaleOptions {
  double min_scale_edges = 1, max_scale_edges = 32;  // the range of σ, in edge lengths
  int levels_per_octave = 4;                          // scales per doubling of σ
  double gamma = 1.0;
  Progress progress = nullptr;
};

struct OptimalScale {
  std::vector<double> sigma;     // #V selected Gaussian scale (mesh units); 0 where no strength at any level
  std::vector<double> strength;  // #V the normalised strength t^γ f at the selected scale's nearest level
  std::vector<double> levels;    // the σ of the levels used (mesh units)
};

OptimalScale optimal_scale_ridges(const TriMesh& mesh, const OptimalScaleOptions& options = {});

}  // namespace reliefkit
