// Synthetic finds with a known frame for the plate's layouts (issue 44): a clay tablet with wedges
// impressed in lines on both faces (the obverse flat, the reverse bulging, as cuneiform tablets
// are), a knapped blade (a ridged dorsal face with flake scars, a smooth ventral face with its
// bulb of percussion near the butt, tapering to the tip) and a coin with a design on each face. Each is made in its own frame — width
// along x, length (height) along y, the obverse or dorsal face towards +z — then turned by `turn`.
#pragma once

#include "reliefkit/base/mesh.h"

namespace rktest {

struct Find {
  reliefkit::TriMesh mesh;
  reliefkit::Vec3 front = reliefkit::Vec3::UnitZ();  // outward normal of the obverse / dorsal face
  reliefkit::Vec3 up = reliefkit::Vec3::UnitY();     // the tablet's top, the blade's tip
  double width = 0, height = 0;                      // along the turned x and y
  double thickness_at_middle = 0;                    // front to back through the middle
};

struct TabletOptions {
  double width = 40, height = 56, thickness = 18;  // mm
  int levels = 7;                                  // of the subdivided sphere it is shaped from (7: 327,680 faces)
  double wedge_depth = 0.6;
};
Find tablet(const TabletOptions& o, const reliefkit::Mat3& turn = reliefkit::Mat3::Identity());

struct BladeOptions {
  double length = 80, width = 26, dorsal = 7, ventral = 1.2;  // mm; dorsal, ventral: heights over the edge's plane
  int levels = 7;
};
Find blade(const BladeOptions& o, const reliefkit::Mat3& turn = reliefkit::Mat3::Identity());

/// A struck coin: a disc with a raised rim on both faces, a five-pointed star in relief on the
/// obverse (+z), a ring crossed by a bar on the reverse; its up the star's top point (+y).
struct CoinOptions {
  double diameter = 24, thickness = 2.4, relief = 0.35;  // mm
  int levels = 7;
};
Find coin(const CoinOptions& o, const reliefkit::Mat3& turn = reliefkit::Mat3::Identity());

}  // namespace rktest
