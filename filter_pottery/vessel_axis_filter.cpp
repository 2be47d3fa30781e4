// "Vessel Axis and Profile": MeshLab adapter of reliefkit/pottery/vessel_record.h.
#include <chrono>
#include <vcg/complex/algorithms/update/bounding.h>

#include "mesh_bridge.h"
#include "params.h"
#include "pottery_filters.h"
#include "reliefkit/pottery/vessel_record.h"

namespace reliefkit::ml {
namespace {

const char* kInfo =
    "Finds the <b>axis of a wheel-made vessel</b>, or of a <b>sherd</b> of one, from its scan, turns the scan onto "
    "it and records it as pottery is published: the <b>profile</b>, the <b>rim diameter</b> and the <b>preserved "
    "share of the rim</b> (EVE).<br><br>"
    "<b>Axis</b>: the normals of a surface of revolution all meet its axis; the line they meet best is fitted, "
    "leaving out the faces whose normals miss it (breaks, decoration, handles), then moved to where the wall's "
    "(radius, height) profile is thinnest. A piece that turns about no axis (a figurine, a flat tile, a sphere, "
    "which fits every axis) is refused with what was measured; give the axis then.<br><br>"
    "<b>Pose</b>: the mesh is moved rigidly (vertices in their order) so that the axis is +Z through the origin, the "
    "piece's lowest point at z = 0 and its middle at +x. The rim is up: the log says what decided it (a floor "
    "across the axis, a smooth rim against a rough break, the scan's own up when its axis is near +y, else the wider "
    "end); <i>Turn over</i> flips it.<br><br>"
    "<b>Output</b>: a new layer <i>&lt;mesh&gt; – profile</i>, the section through the axis at the piece's middle in "
    "the plane y = 0 (x = radius, z = height), vertex quality = the part (0 outer wall, 1 inner wall, 2 rim, 3 base, "
    "4 break); the mesh's vertex quality (and attribute <i>vessel_distance</i>) = each vertex's distance from the "
    "surface of revolution (+ outside the wall): handles, warping, decoration and repairs show with Colorize by "
    "vertex quality. The log gives the axis in the input's frame, the rim diameter with its uncertainty, the EVE, "
    "the wall's thickness and the fit's residual, in the mesh's units, and a line <i>Record:</i> for tables "
    "(reliefkit-batch puts it in its summary).";

const QStringList kAxisModes = {"Fitted", "Given (point and direction below)"};

void vessel_parameters(const MeshModel&, RichParameterList& par) {
  par.addParam(RichEnum("axis_mode", 0, kAxisModes, "Axis",
                        "Fitted from the scan, or as given (for a piece the fit refuses, or an axis known otherwise)."));
  par.addParam(ml::RichPosition("axis_point", vcg::Point3f(0, 0, 0), "Axis point (given)", "A point of the given axis."));
  par.addParam(ml::RichDirection("axis_direction", vcg::Point3f(0, 0, 1), "Axis direction (given)",
                                 "The given axis' direction (its sign does not matter: up is decided as for a fitted one)."));
  par.addParam(RichBool("flip", false, "Turn over", "Turn the piece over after up was decided (when the log's reason for up is wrong)."));
  par.addParam(RichFloat("smoothing", 3.0f, "Normal smoothing (edge lengths)",
                         "The normals are taken from the surface smoothed over this many edge lengths: scanner noise "
                         "turns single faces' normals by tens of degrees."));
}

VesselRecordParams read_params(FilterCall& call) {
  VesselRecordParams p;
  p.fit.smoothing_edges = read_float(call, "smoothing", "Normal smoothing (edge lengths)", 0, 50);
  p.flip = read_bool(call, "flip", "Turn over");
  if (read_enum(call, "axis_mode", "Axis", kAxisModes.size()) == 1) {
    const vcg::Point3f a = call.params.getPoint3m("axis_point"), d = call.params.getPoint3m("axis_direction");
    p.given_axis = AxisLine{Vec3(a[0], a[1], a[2]), Vec3(d[0], d[1], d[2])};
  }
  p.progress = call.progress;
  return p;
}

// The layer's every vertex and face normal moved rigidly (the view's repair does not apply here:
// the whole layer moves, vertices in their order).
void move_layer(MeshModel& m, const VesselRecord& r) {
  const Mat3& R = r.rotation;
  for (CVertexO& v : m.cm.vert) {
    if (v.IsD()) continue;
    const Vec3 p = R * Vec3(v.P()[0], v.P()[1], v.P()[2]) + r.translation;
    v.P() = Point3m(Scalarm(p.x()), Scalarm(p.y()), Scalarm(p.z()));
    const Vec3 n = R * Vec3(v.N()[0], v.N()[1], v.N()[2]);
    v.N() = Point3m(Scalarm(n.x()), Scalarm(n.y()), Scalarm(n.z()));
  }
  for (CFaceO& f : m.cm.face) {
    if (f.IsD()) continue;
    const Vec3 n = R * Vec3(f.N()[0], f.N()[1], f.N()[2]);
    f.N() = Point3m(Scalarm(n.x()), Scalarm(n.y()), Scalarm(n.z()));
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(m.cm);
}

// The profile's parts as curves in the plane y = 0; point strength = the part.
Polylines profile_curves(const VesselRecord& r) {
  Polylines c;
  for (const ProfileCurve& curve : r.profile) {
    const int first = int(c.points.size());
    for (const Vec2& q : curve.points) {
      c.points.emplace_back(q.x(), 0, q.y());
      c.strength.push_back(double(int(curve.part)));
    }
    for (int k = first; k + 1 < int(c.points.size()); ++k) c.segments.push_back({k, k + 1});
  }
  return c;
}

void apply_vessel_axis(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const VesselRecordParams p = read_params(call);
  View view = view_of(call.mesh(), call.log);
  const VesselRecord r = record_vessel(surface_of(view), p);
  write_vertex_attribute(call.mesh().cm, view, "vessel_distance", r.distance);
  call.mesh().updateDataMask(MeshModel::MM_VERTQUALITY);
  for_each_vertex(view, [&](int i, CVertexO* v) { v->Q() = Scalarm(r.distance[size_t(i)]); });
  move_layer(call.mesh(), r);
  add_curve_layer(call.doc, derived_label(call.mesh(), "profile"), profile_curves(r), vcg::Color4b(200, 30, 30, 255));
  for (const std::string& line : record_log_lines(r)) call.log(QString::fromStdString(line));
  call.log(QString("Vessel Axis and Profile: the mesh moved onto the axis (+Z, rim up); profile layer added; %1 s.")
               .arg(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0, 'f', 2));
}

}  // namespace

FilterSpec vessel_axis_filter(int id) {
  return FilterSpec{id,
                    "Vessel Axis and Profile",
                    kInfo,
                    ml::FilterInterface::Normal,
                    MeshModel::MM_NONE,
                    MeshModel::MM_VERTCOORD | MeshModel::MM_VERTNORMAL | MeshModel::MM_FACENORMAL |
                        MeshModel::MM_VERTQUALITY,
                    vessel_parameters,
                    apply_vessel_axis,
                    true};
}

}  // namespace reliefkit::ml
