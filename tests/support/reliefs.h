// Synthetic reliefs with a known step location, for curve-detection tests: smoothed steps
// (0.5 (1 + tanh(d / w))) raised or sunken on a plane, a sphere and a cylinder. Each comes with
// a dense sampling of its true boundary (the step's mid-height line, where the profile
// inflects) and of the base normals, and can carry Gaussian noise along the normal.
#pragma once

#include "reliefkit/mesh.h"
#include "reliefkit/zero_crossings.h"

namespace rktest {

struct Relief {
  reliefkit::TriMesh mesh;
  std::vector<reliefkit::Vec3> base_normal;    // per vertex, of the smooth base surface
  std::vector<reliefkit::Vec3> boundary;       // dense samples of the true step line
  double mean_edge = 0;
};

struct ReliefShape {
  double height = 0.06;   // step height (negative: sunken)
  double width = 0.04;    // tanh width of the step
  double noise = 0;       // standard deviation along the normal, in mean edge lengths
  double jitter = 0.3;    // irregular triangulation
  uint32_t seed = 1;
};

/// Disc of radius 0.5 on the plane [-1, 1]^2 (n x n cells).
Relief disc_on_plane(const ReliefShape& s, int n = 150);
/// Cap of angular radius 0.5 on the unit sphere (icosphere of `levels` subdivisions).
Relief disc_on_sphere(const ReliefShape& s, int levels = 6);
/// A raised ring (angular radii 0.3 to 0.6) on the unit sphere: two step lines, one convex and
/// one concave in plan.
Relief ring_on_sphere(const ReliefShape& s, int levels = 6);
/// On a cylinder of radius 1, height 2 (400 x 128 cells): a disc of radius 0.4 raised by
/// s.height on one side and a disc of radius 0.3 sunken by s.height on the other.
Relief discs_on_cylinder(const ReliefShape& s, int nu = 400, int nz = 128);

/// discs_on_cylinder with about `faces` faces (cells about square): the benchmarks' relief.
Relief discs_on_cylinder_of_size(long faces, const ReliefShape& s);

/// On the same cylinder: a raised square (side 1.2) and a sunken square (side 0.9) with sharp
/// corners (superellipses of exponent 8), in the unrolled (arc length, z) coordinates.
Relief squares_on_cylinder(const ReliefShape& s);

struct Detection {
  double recall;     // fraction of the boundary with a curve within the tolerance
  double precision;  // fraction of the curve length within the tolerance of the boundary
};
/// Recall and precision of `curves` against the relief's boundary, tolerance in mesh units.
Detection score(const Relief& r, const reliefkit::Polylines& curves, double tolerance);

}  // namespace rktest
