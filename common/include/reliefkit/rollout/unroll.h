// ReliefKit — rollouts (issue 43): a scan unrolled around an axis onto a plane, so that the
// decoration round a vessel, a column or a cylinder seal can be drawn flat.
//
// The base is the surface of revolution the piece's outer surface follows: one radius per height
// along the axis, from the area-weighted median radius of the faces facing outwards height by
// height — either straight (a cylinder or cone: a robust line through those radii) or a smooth
// profile (robust local regression over a window, so that bands and grooves round the piece
// narrower than half the window stay relief). Every point is mapped to (across, along, height):
// its base point's position on the developed base, and its height over the base along the
// base's normal, so the relief keeps its heights.

// The development puts the parallels of the base on concentric arcs about the apex of the cone
// tangent to the base at its middle parallel (straight lines for a cylinder), so it is exact (no
// stretch) on cylinders and cones. Between them, on a rounded profile (a globular pot), two
// choices: conformal (the default: the surface's isothermal coordinates mapped by the
// exponential that develops that cone — shapes kept, every meridian alike, each height drawn at
// a scale that follows its radius) or equal-area (a generalized Bonne projection: each parallel
// at its true length, the middle meridian true, the others shearing away from it). Either way
// the stretch is measured per edge and reported. Both chosen over developing bands as separate
// cones (GigaMesh): one sheet, no gaps between bands, the same map for the curves.
//
// The seam is a meridian: given as an angle, or chosen where the fewest faces carry relief (for
// a piece that is not closed round the axis: the middle of the widest empty sector). Faces across
// it are moved to one side by copies of their vertices on the other, so the rollout is one sheet.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/surface.h"
#include "reliefkit/base/zero_crossings.h"
#include "reliefkit/pottery/vessel_axis.h"

namespace reliefkit {

enum class AxisSource { fitted, oriented_z, given };
enum class BaseShape { smooth, straight };
/// How the base is developed onto the plane; both exact (no stretch) on cylinders and cones.
enum class Development {
  conformal,   // angles kept: a rounded belly's parallels scaled with their radius, every meridian alike
  equal_area   // generalized Bonne: parallels at their true length, areas kept, meridians sheared away from the middle
};

struct UnrollParams {
  AxisSource axis_source = AxisSource::fitted;
  AxisLine given_axis;                // used when axis_source == given
  VesselAxisParams fit;               // when fitted
  BaseShape base = BaseShape::smooth;
  Development development = Development::conformal;
  double base_window_edges = 0;       // the smooth profile's window; 0: half the length along the axis (at least 20 edges)
  std::optional<double> seam_deg;     // about the axis, from the reference direction; else automatic
  bool impression = false;            // mirrored, relief inverted: what a seal prints on clay
  double repeat_share = 0;            // the sheet continued past the seam by this share of a turn (0..1):
                                      // seal impressions are drawn with an overlap
  Progress progress = nullptr;
  void validate() const;              // throws InputError naming the parameter
};

/// The base surface of revolution: its profile as (radius, height) points along the axis, with
/// the arc length from the first.
struct BaseProfile {
  std::vector<Vec2> rz;     // radius, height; heights increasing
  std::vector<double> s;    // arc length along the profile
  std::vector<double> u;    // the isothermal coordinate: the integral of ds / radius from the first point
  double facing = 1;        // +1 when the mesh's faces face away from the axis (as oriented), -1 when towards it
  /// The nearest point of the profile to (r, z): its arc length, the point, the outward unit
  /// normal there (towards larger radius on a vertical wall).
  struct Foot {
    double s = 0;
    Vec2 point = Vec2::Zero(), normal = Vec2::UnitX();
  };
  Foot foot(const Vec2& rz_point) const;
  Vec2 at(double arc_length) const;        // the profile's point at an arc length (clamped)
  double slope_at(double arc_length) const; // d radius / d arc length there
  double isothermal(double arc_length) const;  // u at an arc length (clamped; exact on each straight piece)
  /// s and u from rz (radii clamped to a thousandth of the largest: a profile reaching the axis).
  void measure();
};

/// The map from the axis' frame to the rollout's plane.
class RolloutMap {
 public:
  RolloutMap(const AxisLine& axis, const Vec3& reference, BaseProfile base, double seam_angle, bool impression,
             Development development);
  /// What does not depend on the seam: a point's angle about the axis from the reference
  /// direction, its foot on the base and its height over it.
  struct Local {
    double azimuth = 0;
    BaseProfile::Foot foot;
    double height = 0;
  };
  struct Point {
    Vec3 position;      // across (along the circumference), along (the profile), height over the base
    double angle = 0;   // about the axis from the middle meridian, in (-pi, pi]
    Vec3 base_point;    // the foot on the base surface, in the input's frame
  };
  Local local(const Vec3& p) const;
  /// `turns`: added to the angle from the middle meridian in whole turns (a seam copy: +1).
  Point place(const Local& l, int turns = 0) const;
  Point map(const Vec3& p, int turns = 0) const { return place(local(p), turns); }
  double angle_of(const Vec3& p) const;  // about the axis from the middle meridian, in (-pi, pi]
  double angle_from_azimuth(double azimuth) const;
  /// The meridian at `angle` from the middle one, on the sheet (the base developed): a seam's line.
  std::vector<Vec3> meridian(double angle) const;
  double reference_radius() const { return r0_; }
  double seam_angle() const { return seam_; }
  Development development() const { return development_; }
  const BaseProfile& base() const { return base_; }
  const AxisLine& axis() const { return axis_; }

 private:
  Vec2 develop(double angle, double arc_length) const;
  Vec3 on_sheet(double angle, double arc_length, double height) const;  // mirrored for an impression
  AxisLine axis_;
  Vec3 u_, v_;            // the reference direction and the third, square to the axis
  BaseProfile base_;
  double seam_ = 0;       // the seam's angle from the reference direction
  double s0_ = 0, r0_ = 0, apex_ = 0;  // reference parallel; its radius; signed distance to the arcs' centre (0: a cylinder)
  double u0_ = 0;                      // the isothermal coordinate of the reference parallel
  bool impression_ = false;
  Development development_ = Development::conformal;
};

/// What the plate draws besides the surface: the seam's lines and what the sheet is.
struct SheetMarks {
  std::vector<std::vector<Vec3>> seams;  // on the sheet: its first edge, and the seam where the sheet
                                         // (or its repeat past the seam) goes on
  bool impression = false;
  double circumference = 0;              // along the sheet at the reference radius (mesh units)
  double reference_radius = 0;
  double repeat_share = 0;
};

/// Lines of text naming the sheet on a plate: "Rollout" or "Seal impression", its circumference at
/// `unit_mm` millimetres per mesh unit, the seam's line, the share repeated.
std::vector<std::string> sheet_labels(const SheetMarks& marks, double unit_mm);

struct Rollout {
  TriMesh mesh;                    // the outer wall's vertices in the input's order, then the copies: of
                                   // the vertices of faces across the seam, and of the faces repeated past it
  std::vector<int> source;         // per vertex of mesh: the input vertex it is (or is a copy of)
  long wall_vertices = 0;          // the first ones, the input's own; the others copies one turn on
  long left_out_faces = 0;         // not the outer wall: a bore, an inside, the ends of a closed piece
  double left_out_area_share = 0;
  std::vector<double> height;      // per vertex of mesh: over the base (the relief; inverted for an impression)
  std::vector<double> stretch;     // per vertex of mesh: the mean change of its edges' lengths from the base to the sheet (0.01 = 1 %)
  double stretch_median = 0, stretch_p90 = 0;  // over the faces' edges
  double width = 0;                // the reference parallel's length: the circumference at reference_radius
  AxisSource axis_source = AxisSource::fitted;
  std::optional<VesselAxisFit> fit;
  std::optional<RolloutMap> map;
  double seam_relief = 0;          // the relief the seam crosses (rms height off the base near it)
  double relief_rms = 0;           // how far the surface lies from its base (rms over the input's vertices)
  bool seam_automatic = false, seam_in_gap = false;
  bool impression = false;
  long seam_copies = 0;            // the copies made to cut the faces across the seam
  long repeated_faces = 0;         // faces copied past the seam (UnrollParams::repeat_share)
  SheetMarks marks;
};

/// Unrolls the surface. Throws InputError with what was measured when no axis is determined (a
/// sphere, a plane), the mesh has no faces, the base cannot be built, or — with the axis fitted —
/// the surface lies more than a tenth of the base's radius (rms) from its base: it does not turn
/// about that axis (a coin's face, an ingot), and its rollout would be no sheet of a relief.
Rollout unroll(const Surface& surface, const UnrollParams& params = {});

/// The curves unrolled with the mesh: each point mapped; a segment across the seam cut there
/// into two, one on each edge of the sheet; the segments within `repeat_share` of a turn after
/// the seam repeated past it, as the mesh's faces are.
Polylines unroll_curves(const Polylines& curves, const RolloutMap& map, double repeat_share = 0);

/// Log lines for the filter: axis, base, seam, stretch, impression.
std::vector<std::string> rollout_log_lines(const Rollout& r);

}  // namespace reliefkit
