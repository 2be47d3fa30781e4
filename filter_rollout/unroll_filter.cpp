// "Unroll Around Axis": MeshLab adapter of reliefkit/rollout/unroll.h.
#include <chrono>

#include "mesh_bridge.h"
#include "params.h"
#include "reliefkit/rollout/unroll.h"
#include "rollout_filters.h"

namespace reliefkit::ml {
namespace {

const char* kInfo =
    "Unrolls a <b>cylinder seal</b>, a <b>decorated vessel</b> or a <b>column</b> around its axis onto a plane, so "
    "that the decoration all round it can be read, drawn and traced in one view; as the seal prints it on clay "
    "with <i>Seal impression</i>.<br><br>"
    "<b>Axis</b>: fitted (the normals of a surface of revolution meet its axis; as <i>Vessel Axis and Profile</i> "
    "fits it), +Z through the origin (a mesh <i>Vessel Axis and Profile</i> has oriented), or given.<br><br>"
    "<b>Base</b>: the surface of revolution the outer surface follows, from its median radius height by height: a "
    "<i>smooth profile</i> (a pot; bands and grooves narrower than half the window stay relief) or a <i>cylinder or "
    "cone</i> (a seal, a column, a beaker). Each point goes to its base point's place on the developed base "
    "(no stretch at all on cylinders and cones; a rounded profile conformally — shapes kept — or equal-area) and "
    "keeps its height over the base, so the rollout is a relief every curve filter and <i>Export "
    "Illustration Plate</i> read as such. On a rounded profile no sheet is without stretch: it is "
    "measured, logged and written as vertex quality.<br><br>"
    "<b>Seam</b>: the meridian where the sheet is cut: where the surface rises least off the base, or across the "
    "gap of a piece that does not go round, or at the angle given (degrees about the axis from the scan's +x).<br><br>"
    "<b>Output</b>: a new layer <i>&lt;mesh&gt; – rollout</i>, made current: the outer wall only (a seal's ends "
    "and bore, a pot's inside are left out and the log says how much), its vertices in the mesh's order, then "
    "copies of those of the faces across the seam and of the repeat; vertex colours kept; vertex quality and attribute "
    "<i>rollout_stretch</i> = the stretch, attribute <i>rollout_height</i> = the height over the base), and each "
    "curve layer of the mesh (<i>&lt;mesh&gt; – …</i>, edges only) unrolled with it. <i>Export Illustration "
    "Plate</i> of the new layer draws it to scale along the circumference, the seam dash-dot, and names it a "
    "rollout or a seal impression.";

const QStringList kAxisModes = {"Fitted", "+Z through the origin (as Vessel Axis and Profile leaves it)",
                                "Given (point and direction below)"};
const QStringList kBases = {"Smooth profile", "Cylinder or cone"};
const QStringList kDevelopments = {"Conformal (shapes kept)", "Equal-area (parallels at their true length)"};

void unroll_parameters(const MeshModel&, RichParameterList& par) {
  par.addParam(RichEnum("axis_mode", 0, kAxisModes, "Axis", "How the axis is found."));
  par.addParam(ml::RichPosition("axis_point", vcg::Point3f(0, 0, 0), "Axis point (given)", "A point of the given axis."));
  par.addParam(ml::RichDirection("axis_direction", vcg::Point3f(0, 0, 1), "Axis direction (given)", "The given axis' direction."));
  par.addParam(RichEnum("base", 0, kBases, "Base",
                        "The surface the relief stands on: a smooth profile (a pot), or a straight one (a seal, a column)."));
  par.addParam(RichEnum("development", 0, kDevelopments, "Development",
                        "How a rounded profile is laid flat (cylinders and cones are exact either way). Conformal: "
                        "every figure keeps its shape and every meridian is drawn alike, each height at a scale "
                        "that follows its radius (a neck drawn larger than it is). Equal-area: each parallel at its "
                        "true length, the figures away from the middle sheared."));
  par.addParam(RichFloat("base_window", 0.0f, "Base window (edge lengths)",
                         "How far along the axis the smooth profile follows the surface: bands and grooves narrower than "
                         "half of it stay relief. 0: half the piece's length."));
  par.addParam(RichBool("seam_auto", true, "Seam automatic",
                        "Cut where the surface rises least off the base (or across the gap of a piece that does not go round)."));
  par.addParam(RichFloat("seam_angle", 0.0f, "Seam angle (degrees)", "The seam's angle about the axis from the scan's +x, when not automatic."));
  par.addParam(RichBool("impression", false, "Seal impression", "Mirror the rollout and invert its relief: what the seal prints rolled over clay."));
  par.addParam(RichFloat("repeat", 0.0f, "Repeat past the seam (share of a turn)",
                         "The sheet continued past the seam by this share of a turn (0 to 1), so that the design "
                         "crossing the seam is seen whole: seal impressions are drawn with such an overlap. "
                         "Export Illustration Plate marks the seam dash-dot."));
  par.addParam(RichFloat("smoothing", 3.0f, "Normal smoothing (edge lengths)", "For the fitted axis: the normals of the surface smoothed over this many edge lengths."));
}

UnrollParams read_params(FilterCall& call) {
  UnrollParams p;
  const int axis = read_enum(call, "axis_mode", "Axis", kAxisModes.size());
  p.axis_source = axis == 0 ? AxisSource::fitted : axis == 1 ? AxisSource::oriented_z : AxisSource::given;
  if (p.axis_source == AxisSource::given) {
    const vcg::Point3f a = call.params.getPoint3m("axis_point"), d = call.params.getPoint3m("axis_direction");
    p.given_axis = AxisLine{Vec3(a[0], a[1], a[2]), Vec3(d[0], d[1], d[2])};
  }
  p.base = read_enum(call, "base", "Base", kBases.size()) == 0 ? BaseShape::smooth : BaseShape::straight;
  p.development = read_enum(call, "development", "Development", kDevelopments.size()) == 0 ? Development::conformal
                                                                                           : Development::equal_area;
  p.base_window_edges = read_float(call, "base_window", "Base window (edge lengths)", 0, 1e6);
  if (!read_bool(call, "seam_auto", "Seam automatic")) p.seam_deg = read_float(call, "seam_angle", "Seam angle (degrees)", -360, 360);
  p.impression = read_bool(call, "impression", "Seal impression");
  p.repeat_share = read_float(call, "repeat", "Repeat past the seam (share of a turn)", 0, 1);
  p.fit.smoothing_edges = read_float(call, "smoothing", "Normal smoothing (edge lengths)", 0, 50);
  p.progress = call.progress;
  return p;
}

// The curve layers of `mesh` (its derived layers with edges and no faces) as polylines.
std::vector<std::pair<MeshModel*, Polylines>> curve_layers_of(MeshDocument& doc, const MeshModel& mesh) {
  const QString prefix = derived_label(mesh, "");
  std::vector<std::pair<MeshModel*, Polylines>> out;
  for (MeshModel* m : document_layers(doc)) {
    if (m == &mesh || !m->label().startsWith(prefix) || m->cm.fn > 0 || m->cm.en == 0) continue;
    out.emplace_back(m, curves_of_layer(*m));
  }
  return out;
}

void apply_unroll(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const UnrollParams p = read_params(call);
  MeshModel& source = call.mesh();  // the new layer becomes current: the curve filters and the plate act on it next
  const auto curves = curve_layers_of(call.doc, source);
  View view = view_of(source, call.log);
  const Rollout r = unroll(surface_of(view), p);
  MeshModel* layer = add_mesh_layer(call.doc, derived_label(source, r.impression ? "seal impression" : "rollout"), r.mesh,
                                    r.stretch, {{"rollout_stretch", &r.stretch}, {"rollout_height", &r.height}}, true);
  if (source.hasDataMask(MeshModel::MM_VERTCOLOR)) {  // the scan's colours, on the copies too
    layer->updateDataMask(MeshModel::MM_VERTCOLOR);
    std::vector<vcg::Color4b> colour(size_t(view.mesh.n_vertices()));
    for_each_vertex(view, [&](int i, CVertexO* v) { colour[size_t(i)] = v->C(); });
    for (size_t i = 0; i < layer->cm.vert.size(); ++i) layer->cm.vert[i].C() = colour[size_t(r.source[i])];
  }
  for (const auto& [m, c] : curves)
    add_curve_layer(call.doc, m->label() + (r.impression ? " (seal impression)" : " (rollout)"),
                    unroll_curves(c, *r.map, p.repeat_share), vcg::Color4b(0, 0, 0, 255));
  set_sheet_marks(*layer, r.marks);
  for (const std::string& line : rollout_log_lines(r)) call.log(QString::fromStdString(line));
  call.log(QString("Unroll Around Axis: layer added (%1 vertices, %2 of them copies past the seam), %3 curve layer(s) unrolled; %4 s.")
               .arg(thousands(r.mesh.n_vertices()))
               .arg(thousands(long(r.source.size()) - r.wall_vertices))
               .arg(curves.size())
               .arg(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0, 'f', 2));
}

}  // namespace

FilterSpec unroll_filter(int id) {
  return FilterSpec{id,
                    "Unroll Around Axis",
                    kInfo,
                    ml::FilterInterface::Remeshing,
                    MeshModel::MM_NONE,
                    MeshModel::MM_NONE,
                    unroll_parameters,
                    apply_unroll,
                    true};
}

}  // namespace reliefkit::ml
