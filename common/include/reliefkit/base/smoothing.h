// ReliefKit — diffusion smoothing of per-vertex fields and of a surface's positions.
//
// `diffuse` approximates a convolution with a Gaussian of standard deviation `sigma` (mesh units)
// by explicit heat-diffusion steps on the one-ring graph: each step replaces a value by
// x + 1/2 (mean of the neighbours - x). One step spreads a value with the run's
// MeshScale::step_variance per tangent direction (a quarter of the mean squared edge length), so
// sigma^2 / that many steps are run (at least one). The number of steps is the run's: a field on
// moved positions (a smoothed or deformed copy) is diffused as on the scan. Cost:
// O(steps * #edges), in parallel over vertices.
#pragma once

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/scale.h"
#include "reliefkit/base/surface.h"

namespace reliefkit {

/// Number of diffusion steps for a Gaussian of standard deviation `sigma` (mesh units) on a scan
/// of this scale (0 when sigma is not positive or the scale has no edges; at most 10000).
int diffusion_steps(const MeshScale& scale, double sigma);

/// Smooths `values` (#V entries) in place over the surface's one-rings.
void diffuse(const Surface& surface, double sigma, std::vector<double>& values);
void diffuse(const Surface& surface, double sigma, std::vector<Vec3>& values);

/// Diffuses vertex positions like `diffuse`, except that a boundary vertex (two boundary
/// neighbours) moves only along the boundary: it takes the mean of its boundary neighbours.
/// Plain diffusion pulls an open boundary inwards and bends the surface next to it, which
/// curvature-derivative curves then trace along the whole rim. `positions` need not be the
/// surface's own (the optimal scale smooths the positions it assembled).
void smooth_positions(const Surface& surface, double sigma, std::vector<Vec3>& positions);

/// The surface with its positions smoothed by smooth_positions: the same run (connectivity,
/// scale, noise), its own normals and Laplacian. The surface itself when sigma is not positive.
Surface smoothed_surface(const Surface& surface, double sigma);

}  // namespace reliefkit
