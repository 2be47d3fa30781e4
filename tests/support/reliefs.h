// Synthetic reliefs with a known step location, for curve-detection tests: smoothed steps
// (0.5 (1 + tanh(d / w))) raised or sunken on a plane, a sphere and a cylinder. Each comes with
// a dense sampling of its true boundary (the step's mid-height line, where the profile
// inflects) and of the base normals, and can carry Gaussian noise along the normal.
#pragma once

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/zero_crossings.h"

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

/// On the plane [-1, 1]^2 (n x n cells): a five-pointed star (points at radius 0.38, notches at
/// 0.19, sharp corners) around (-0.45, 0) and a rectangle 0.5 x 0.9 with corners rounded to 0.1
/// around (0.55, 0), either or both raised by s.height, the step across the signed distance to
/// each outline.
Relief outlines_on_plane(const ReliefShape& s, bool with_star, bool with_rectangle, int n = 200);

struct Detection {
  double recall;     // fraction of the boundary with a curve within the tolerance
  double precision;  // fraction of the curve length within the tolerance of the boundary
};
/// Recall and precision of `curves` against the relief's boundary, tolerance in mesh units.
Detection score(const Relief& r, const reliefkit::Polylines& curves, double tolerance);

}  // namespace rktest

namespace rktest {

/// Features running along the axis of a cylinder of radius 1 (the thesis' quantitative experiment
/// of sect. 5.5.1, harder): Gaussian ridges / valleys, height ± depth exp(-x² / 2 width²) at arc
/// distance x from their line, or raised bands with tanh edges of the given width.
struct AxialFeature {
  enum Kind { Ridge, Valley, Band } kind;
  double arc;    // arc length of the line (band: of its first edge)
  double width;  // Gaussian standard deviation, or tanh width of the band's edges
  double depth;  // > 0: the ridge's height, the valley's depth, the band's height
  double band = 0;  // band: arc length between its two edges
  int group = 0;    // the test's own class (fine / coarse)
};

struct AxialCylinder {
  reliefkit::TriMesh mesh;
  double edge = 0;    // mean edge length
  double length = 0;  // along the axis
  std::vector<AxialFeature> features;
};

/// The cylinder meshed with `nu` cells around and square-ish cells along `length`, jittered, with
/// Gaussian noise of `noise` mean edge lengths along the normal.
AxialCylinder axial_cylinder(const std::vector<AxialFeature>& features, int nu, double length, double noise,
                             double jitter = 0.3, uint32_t seed = 1);

/// The 3-D line of a feature's curve: the ridge's crest, the valley's bottom, the band edge's
/// mid-height (first edge: side = 0, second: side = 1); as (angle, radius).
std::pair<double, double> axial_line(const AxialFeature& f, int side = 0);

struct AxialScore {
  std::vector<double> recall;  // per feature (a band: both edges), share of its length with a curve point within tol
  double precision = 0;        // share of the curves' length within tol of a true curve of the given kinds
                               // (the features' lines, and the banks of Gaussian valleys / feet of ridges,
                               // ridges / valleys of the surface too, between ±√3 and ±3 widths)
  double length = 0;           // total curve length
};
/// Scores curves against the lines of the features of the given kinds; the ends of the cylinder
/// (within `margin` of the rims) count for neither.
AxialScore score_axial(const AxialCylinder& c, const reliefkit::Polylines& curves,
                       const std::vector<AxialFeature::Kind>& kinds, double tol, double margin);

/// Twelve lines along a cylinder of `around` cells, every 150 edge lengths: valleys and ridges
/// alternating in pairs, fine (even, group 0) and coarse (odd, group 1), off the vertex columns by
/// a varying fraction of an edge; widths and depth in edge lengths.
std::vector<AxialFeature> fine_and_coarse_lines(int around, double fine_width, double coarse_width, double depth);

/// Ridges and valleys scored together against fine_and_coarse_lines (or any ridges / valleys of
/// groups 0 and 1): the mean recall of each group and the length-weighted precision.
struct FineCoarseScore {
  double fine = 0, coarse = 0, precision = 0;
  double f1() const;  // of the mean of the two recalls and the precision
};
FineCoarseScore score_fine_coarse(const AxialCylinder& c, const reliefkit::Polylines& ridges,
                                  const reliefkit::Polylines& valleys, double tol, double margin);

}  // namespace rktest
