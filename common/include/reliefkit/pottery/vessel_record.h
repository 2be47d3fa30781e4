// ReliefKit — the pottery record of a scanned vessel or sherd (issue 42): the piece turned onto its
// axis of revolution (vessel_axis.h) with the rim up, its profile (the section through the axis),
// the rim diameter, the preserved share of the rim, the wall's thickness, and each vertex's
// distance from the surface of revolution the profile sweeps.
//
// The profile is the piece's section at its middle meridian, as an illustrator's profile gauge
// takes it: exact (mesh edges cut by the plane, at the scan's resolution), decoration on that
// meridian included. Its parts are told apart by the surface they cut: the wall (normals meeting
// the axis) facing away from the axis is the outer wall, towards it the inner wall; a surface
// facing along the axis at the top is the rim, at the bottom the base (when that end is smooth,
// below); faces whose normals miss the axis (fit weight under one half) are breaks.
//
// Which end is up is decided, in this order, by: the base (a floor across the axis at one end);
// the rim (one end smooth, the other a break: the normals of the surface smoothed over an edge
// length turn from the fit's smoothed surface by at most 10 degrees, median over the end's
// faces); the scan's own up on screen (+y, when the axis runs within 30 degrees of it); the
// wider end. The log says which; `flip` turns it over. An end rougher than that is drawn as a
// break, not a rim.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "reliefkit/illustration/plate.h"
#include "reliefkit/pottery/vessel_axis.h"

namespace reliefkit {

enum class ProfilePart { outer_wall, inner_wall, rim, base, break_surface };
const char* profile_part_name(ProfilePart part);

/// A run of the profile in (radius, height) of the oriented piece.
struct ProfileCurve {
  std::vector<Vec2> points;
  ProfilePart part = ProfilePart::outer_wall;
};

enum class UpRule { base, rim, input_up, wider_end };
const char* up_rule_name(UpRule rule);

struct VesselRecordParams {
  VesselAxisParams fit;
  std::optional<AxisLine> given_axis;  // the axis as given (the input's frame) instead of fitting one
  bool flip = false;                   // turn the piece over after "up" was decided
  bool as_oriented = false;            // the piece lies on its axis already (+Z through the origin, rim up): kept as it lies
  Progress progress = nullptr;
  void validate() const;  // throws InputError
};

struct VesselRecord {
  AxisLine axis;                     // in the input's frame, direction pointing up (to the rim)
  UpRule up_rule = UpRule::wider_end;
  std::string up_reason;             // what decided it, in words with the figures
  bool flipped = false;
  bool top_is_rim = false, bottom_is_base = false;  // the ends as smooth as the wall (else breaks)
  double top_roughness = 0, bottom_roughness = 0, wall_roughness = 0;  // degrees (end_roughness in the .cpp)
  Mat3 rotation = Mat3::Identity();  // oriented = rotation * input + translation: axis +Z through
  Vec3 translation = Vec3::Zero();   // the origin, the piece's lowest point at z = 0, its middle meridian at +x
  std::optional<VesselAxisFit> fit;  // when the axis was fitted
  std::vector<ProfileCurve> profile;
  std::vector<std::vector<Vec2>> section_loops;  // the section's closed chains in the plane y = 0, (x, z), x of either sign
  bool has_rim = false, has_base = false;
  double rim_diameter = 0;           // mesh units (0 without a rim)
  double rim_share = 0;              // preserved share of the rim's circumference, 0..1 (EVE)
  double rim_height = 0;             // z of the rim's top in the oriented frame
  double thickness_low = 0, thickness_high = 0;  // the wall's thickness, 5th and 95th percentile (0: one wall only)
  double residual_rms = 0;           // rms distance of the wall's vertices from the surface of revolution
  double angle_uncertainty_deg = 0;  // of the axis (0 when given)
  double diameter_uncertainty = 0;   // of the rim diameter (0 when given or without a rim)
  std::vector<double> distance;      // per vertex: from the surface of revolution, + outside the wall's section
};

/// The record of a vessel or sherd. Throws InputError (with what was measured) when no axis can
/// be fitted, a given axis misses the piece, or the section through it is empty.
VesselRecord record_vessel(const Surface& surface, const VesselRecordParams& params = {});

/// The mesh moved rigidly as the record says (vertices and faces in their order).
TriMesh oriented_mesh(const TriMesh& mesh, const VesselRecord& record);

/// What the pottery plate draws of the record: the section's loops cut at the axis (the half at
/// x >= 0, closed along the axis), the profile's runs as lines when the section has no loop, the rim.
PotterySheet pottery_sheet(const VesselRecord& record);

/// The record for a log, line by line (units: the mesh's).
std::vector<std::string> record_log_lines(const VesselRecord& record);

}  // namespace reliefkit
