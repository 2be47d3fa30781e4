// Synthetic pieces to unroll, with known geometry (the tests and benchmark of
// reliefkit/rollout/unroll.h): a cylinder (a seal), a cone or a globular band (a pot's belly)
// turned about an axis, a design embossed or carved on it at known heights, in a random pose.
// The globe is oblate (0.75 R along the axis): a sphere's zone turns about every axis through its centre.
#pragma once

#include <vector>

#include "reliefkit/base/mesh.h"

namespace rktest {

enum class TurnedShape { cylinder, cone, globe };

struct TurnedOptions {
  TurnedShape shape = TurnedShape::cylinder;
  double radius = 15;           // mm: the cylinder's; the cone's at its middle; the globe's at its widest
  double length = 30;           // along the axis
  double cone_half_angle_deg = 12;
  double edge = 0.3;            // mean edge length
  double relief = 0.2;          // the design's height (negative: carved)
  bool band = false;            // a band round the middle (a fifth of the length) instead of the blobs
  bool frieze = false;          // a seal's design instead: four standing figures facing right (arm raised
                                // forwards: a mirror shows), a star between each two, a border line above
                                // and below; lines 1.6 edge lengths wide, eased
  bool irregular = false;       // grid points moved by up to 30 % of a step
  bool closed = false;          // a cylinder closed as a seal is: both ends flat, pierced along the axis by a bore
  double bore_radius = 3;
  bool random_pose = true;
  unsigned seed = 1;
};

struct Turned {
  reliefkit::TriMesh mesh;
  reliefkit::Vec3 axis_point = reliefkit::Vec3::Zero(), axis_direction = reliefkit::Vec3::UnitZ();
  std::vector<double> relief;   // per vertex: its true height over the base, along the base's normal (NaN off the wall)
  int wall_faces = 0;           // the first faces: the outer wall; then the ends and the bore
  double middle_radius = 0;     // the base's radius halfway along its profile
};

Turned make_turned(const TurnedOptions& options);

}  // namespace rktest
