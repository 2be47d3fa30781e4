// Synthetic knapped flakes whose arêtes are known exactly, for the stone-tool tests of the curve
// filters. The flake is a closed lens over an ellipse (half axes 1 and 0.65): a flat-ish convex
// ventral face below, and above a convex blank (the cortex) into which concave flake scars are
// cut — each scar a bowl z = bottom + |p - centre|² / 2R, the dorsal surface the lowest of the
// blank and the bowls. Where two of them meet is an arête (a convex crease, as where a scar meets
// the cortex); where the dorsal face meets the ventral one is the flake's edge. The scars carry
// faint ripples (concentric around their point of percussion on the outline), the cortex a rough
// patch of bumps, the whole scanner noise; the triangles are irregular.
#pragma once

#include <cstdint>

#include "reliefs.h"

namespace rktest {

struct FlakeShape {
  int scars = 5;
  double ripple = 0.15;     // height of the scars' ripples, in mean edge lengths (wavelength 8 edges)
  double roughness = 0.5;   // height of the cortex's bumps, in mean edge lengths (6 to 12 edge lengths across)
  double noise = 0.1;       // scanner noise (Gaussian, each coordinate), in mean edge lengths
  double jitter = 0.4;      // irregular triangulation
  int cells = 160;          // grid cells across the outline's long axis, per face
  uint32_t seed = 1;
};

struct Flake {
  Relief relief;                     // mesh; boundary = dense samples of the arêtes
  std::vector<reliefkit::Vec3> edge; // dense samples of the flake's edge (dorsal meets ventral)
  double arete_length = 0;           // total length of the arêtes
};

Flake knapped_flake(const FlakeShape& shape);

/// Curves (a ridge layer) against a flake, within `tolerance` (mesh units): the share of the
/// arêtes' length found, the share of the curves' length on an arête or on the flake's edge, the
/// share of the edge found.
struct FlakeScore {
  double aretes_found = 0, precision = 0, edge_found = 0;
};
FlakeScore score_flake(const Flake& flake, const reliefkit::Polylines& curves, double tolerance);

}  // namespace rktest
