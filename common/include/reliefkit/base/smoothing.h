// ReliefKit — diffusion smoothing of per-vertex fields.
//
// `diffuse` approximates a convolution with a Gaussian of standard deviation `scale` (mesh
// units) by explicit heat-diffusion steps on the one-ring graph: each step replaces a value by
// x + 1/2 (mean of the neighbours - x). One step spreads a value with a variance of about
// (mean squared edge length)/4 per tangent direction, so scale^2 / that many steps are run
// (at least one). Cost: O(steps * #edges), in parallel over vertices.
#pragma once

#include "reliefkit/base/mesh.h"

namespace reliefkit {

/// Number of diffusion steps that `diffuse` runs for a Gaussian of the given scale.
int diffusion_steps(const TriMesh& mesh, double scale);

/// Smooths `values` (#V entries) in place; works for double and Vec3 fields.
void diffuse(const TriMesh& mesh, const VertexRing& ring, double scale, std::vector<double>& values);
void diffuse(const TriMesh& mesh, const VertexRing& ring, double scale, std::vector<Vec3>& values);

/// Diffuses vertex positions like `diffuse`, except that a boundary vertex (two boundary
/// neighbours) moves only along the boundary: it takes the mean of its boundary neighbours.
/// Plain diffusion pulls an open boundary inwards and bends the surface next to it, which
/// curvature-derivative curves then trace along the whole rim.
void smooth_positions(const TriMesh& mesh, const MeshTopology& topology, double scale, std::vector<Vec3>& positions);

}  // namespace reliefkit
