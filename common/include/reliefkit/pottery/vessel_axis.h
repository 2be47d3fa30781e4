// ReliefKit — the axis of a wheel-made vessel, or of a sherd of one, from its scan (issue 42; the
// pottery record of excavation reports, not a chapter of the thesis).
//
// A surface of revolution has every normal line meeting its axis: for the normal line through p
// with direction n and the axis through a with direction d, d · ((p − a) × n) = 0. In Plücker
// coordinates this is linear in (d, d̄ = a × d), so the axis is the smallest generalized
// eigenvector of a 6 × 6 moment matrix of the normal lines (Pottmann and Randrup, "Rotational and
// helical surface approximation for reverse engineering", Computing 1998): with d̄ solved out,
// the 3 × 3 Schur complement's smallest eigenvector is d. Faces are the samples, weighted by area
// (irregular triangles count by the surface they cover), then reweighted by how far their normal
// turns from the plane through the axis (Tukey's biweight at a scale from the median): break
// surfaces, decoration, handles and repairs drop out, the wall stays.
//
// What the fit cannot decide is refused with what was measured: every direction fits (a sphere:
// the two smallest eigenvalues nearly equal); every position fits (a flat tile: the normals span
// too little of the plane across the axis); the normals do not meet one line (a figurine: large
// angles on most of the surface). The uncertainty of the direction and of the axis' position is
// the larger of two jackknives over patches of the piece, so errors shared by neighbouring faces
// (an out-of-round pot, noise correlated over a few triangles) count: the normal lines' fit
// without each of 16 patches (4 around the axis × 4 along it), and the thinnest-profile step
// without each of 8 (4 × 2), which sees how loosely the profile holds a small sherd's axis.
#pragma once

#include <string>
#include <vector>

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/surface.h"

namespace reliefkit {

struct AxisLine {
  Vec3 point = Vec3::Zero();          // a point of the axis
  Vec3 direction = Vec3::UnitZ();     // unit
};

struct VesselAxisParams {
  /// The normals are those of the surface smoothed by a Gaussian of this many edge lengths:
  /// scanner noise turns a face's normal by tens of degrees on a finely meshed scan, the wall's
  /// curvature over a few edge lengths by far less.
  double smoothing_edges = 3;
  /// Faces whose normal turns more than this from the plane through the axis get no weight
  /// (degrees); 0: from the data (4.7 robust standard deviations of the angles, at least 2°).
  double outlier_angle_deg = 0;
  int max_iterations = 30;
  /// Throws InputError naming the first parameter out of its range.
  void validate() const;
};

struct VesselAxisFit {
  AxisLine axis;                    // in the input's frame; direction as fitted (sign not decided)
  double rms_angle_deg = 0;         // of the wall's normals from the planes through the axis (weighted)
  double wall_share = 0;            // area share of the faces kept (weight above half)
  double cutoff_deg = 0;            // the outlier angle used
  double direction_ambiguity = 0;   // λ1 / λ2 of the direction problem: near 1, every direction fits
  double position_spread = 0;       // how fully the normals span the plane across the axis (0..1)
  double angle_uncertainty_deg = 0; // standard error of the direction (jackknife, see above)
  double offset_uncertainty = 0;    // standard error of the axis' position (mesh units)
  int iterations = 0;
  std::vector<double> face_weight;  // 0..1 per face: 1 wall, 0 left out
  std::vector<Vec3> face_normal;    // per face: the smoothed surface's unit normal (zero on a face without area)
};

/// Per face, the unit normal of the surface smoothed by a Gaussian of `smoothing_edges` edge
/// lengths (the mean of its vertices' normals; zero on a face without area).
std::vector<Vec3> smoothed_face_normals(const Surface& surface, double smoothing_edges);

/// How far each face's normal turns from the plane through the axis and the face (degrees).
std::vector<double> off_axis_angles(const TriMesh& mesh, const std::vector<Vec3>& face_normal, const AxisLine& axis);

/// The axis of revolution of the surface (a whole vessel or a sherd). Throws InputError saying what
/// was measured when it is no piece of a surface of revolution or its axis is undetermined.
VesselAxisFit fit_vessel_axis(const Surface& surface, const VesselAxisParams& params = {});

}  // namespace reliefkit
