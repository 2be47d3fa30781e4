// Synthetic scans of wheel-made vessels and their sherds with a known axis and profile (the tests
// and the benchmark of reliefkit/pottery/vessel_record.h): a profile (jar, bowl, beaker) turned
// about the axis over part of the circumference, with the wall's thickness, a rounded rim or a
// rough break at the top, a rough break or the base at the bottom, rough breaks down the sides,
// incised grooves, scanner noise, irregular triangles, an out-of-round wall, a random pose.
#pragma once

#include <vector>

#include "reliefkit/base/mesh.h"
#include "reliefkit/pottery/vessel_record.h"

namespace rktest {

enum class VesselShape { jar, bowl, beaker };

struct SherdOptions {
  VesselShape shape = VesselShape::jar;
  double span_deg = 360;     // the share of the circumference kept
  double from = 0, to = 1;   // the part of the profile kept: 0 the base's middle (on the axis), 1 the rim
  double edge = 0.5;         // mean edge length (mm; a sherd scanned at 0.5 mm); the vessel is about 100 mm across
  double noise = 0;          // Gaussian, in edge lengths (each coordinate)
  bool irregular = false;    // grid points moved by up to 40 % of a step: triangles of mixed shapes
  double out_of_round = 0;   // radius times (1 + this cos 2θ)
  bool incised = false;      // three incised grooves round the outer wall, 1.5 edge lengths deep
  bool random_pose = true;
  unsigned seed = 1;
};

struct Sherd {
  reliefkit::TriMesh mesh;
  reliefkit::Vec3 axis_point, axis_direction;  // the true axis; the direction points to the rim
  std::vector<reliefkit::Vec2> outer, inner;    // the true profile (radius, height) of the part kept, base to rim
  double largest_radius = 0;                    // of the vessel's outer wall
  double rim_diameter = 0;                      // outer, at the top (when the rim is kept)
  double thickness = 0;                         // of the wall (normal to it)
  bool has_rim = false, has_base = false;
};

Sherd make_sherd(const SherdOptions& options);

/// A record's errors against the truth (lengths as shares of the largest radius).
struct SherdScore {
  double angle_deg = 0;           // between the axes
  double offset = 0;              // between the axes at the piece's centroid
  bool up_right = false;          // the record's up is the rim's side
  double profile_median = 0, profile_p90 = 0;  // the walls' profile points from the true walls
  long profile_points = 0;
  double sides_right = 0;         // share of those labelled outer (inner) wall nearer the true outer (inner) wall
  double rim_diameter = 0;        // |found - true| / true (0 when either has no rim)
};
SherdScore score_record(const Sherd& sherd, const reliefkit::VesselRecord& record);

}  // namespace rktest
