// "Vessel from Profile Drawing": MeshLab adapter of reliefkit/drawing/vessel_profile.h.
#include <QFileInfo>
#include <chrono>

#include "drawing_filters.h"
#include "drawing_image.h"
#include "mesh_bridge.h"
#include "params.h"
#include "reliefkit/drawing/drawing_relief.h"
#include "reliefkit/drawing/line_drawing.h"
#include "reliefkit/drawing/vessel_profile.h"

namespace reliefkit::ml {
namespace {

const char* kVesselInfo =
    "Makes a <b>wheel-made vessel</b> from its <b>profile drawing</b> as excavation reports publish pottery: the "
    "half-section, with a vertical axis, the wall's section on one side (filled black, hatched, or outlined) and "
    "the exterior on the other. The section is the wall's cross-section through the axis, so turning it round "
    "the axis gives the vessel exactly: outer and inner wall, rim, base. Where the drawing ends at a break (a "
    "missing base or rim) the vessel ends there too, and the log says so; nothing is invented.<br><br>"
    "<b>Input</b>: the drawing image (dark lines on light paper; stippling and dust are ignored). The axis is "
    "found (a drawn vertical axis line, else the middle of the drawn width) or given in pixels; which side holds "
    "the section is found (the long thin closed, filled or hatched region along the outline) or given. A profile "
    "drawn as a single line (no section) gives the outer wall alone.<br><br>"
    "<b>Output</b>: a new layer <i>&lt;image&gt; – vessel</i> (made current), in millimetres (<i>DPI</i>, "
    "<i>scale</i>), in the drawing's plane like the other drawing filters (image x right, y up; the axis vertical, "
    "the viewer on +z), vertex quality = the distance from the axis; and <i>&lt;image&gt; – profile</i>, the "
    "section's outline as it was read, to check it against the drawing.";

const QStringList kSides = {"Found in the drawing", "Left of the axis", "Right of the axis"};

void vessel_parameters(const MeshModel&, RichParameterList& par) {
  add_drawing_image_parameter(par, "The profile drawing: a half-section (or a profile line) of a vessel, dark lines "
                                   "on light paper (PNG, JPEG, TIFF, BMP).");
  add_dpi_and_scale_parameters(par);
  par.addParam(RichFloat("axis", -1.f, "Axis position (px, -1: found)",
                         "The axis' x in pixels of the image (from its left edge). -1: the drawn vertical axis line "
                         "near the middle, else the middle of the drawn width."));
  par.addParam(RichEnum("side", 0, kSides, "Section side",
                        "Where the wall's section is drawn: found (the long thin region along the outline), or given."));
  par.addParam(RichInt("segments", 0, "Segments around the axis (0: auto)",
                       "How many steps the profile is turned in. 0: edges round the widest ring about as long as the "
                       "profile's (48 to 360)."));
}

VesselParams read_vessel_params(FilterCall& call, double pixel_mm) {
  VesselParams vp;
  const double axis = read_float(call, "axis", "Axis position (px, -1: found)", -1, 1e7);
  if (axis >= 0) vp.axis_x = axis;  // the core refuses one outside the image
  vp.side = VesselSide(read_enum(call, "side", "Section side", kSides.size()));
  vp.segments = read_int(call, "segments", "Segments around the axis (0: auto)", 0, 100000);
  vp.pixel_size = pixel_mm;
  return vp;
}

// The outline as it was read, closed, in the drawing's plane (mm).
Polylines profile_curve(const VesselProfile& p, double pixel_mm) {
  DrawingCurves c;
  c.curves.push_back(p.outline);
  if (p.closed && !p.outline.empty()) c.curves.back().push_back(p.outline.front());
  return drawing_polylines(c, pixel_mm);
}

void apply_vessel(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  double pixel_mm = read_pixel_mm(call);
  if (call.progress) call.progress(5, "Reading the drawing");
  QString path;
  const cv::Mat image = read_drawing_parameter(call, pixel_mm, &path);
  const VesselParams vp = read_vessel_params(call, pixel_mm);
  if (call.progress) call.progress(20, "Finding the axis and the section");
  const VesselProfile profile = read_vessel_profile(image, vp);
  if (call.progress) call.progress(70, "Turning the profile");
  const TriMesh vessel = revolve_vessel_profile(profile, vp);
  std::vector<double> radius(vessel.vertices.size());
  for (size_t v = 0; v < radius.size(); ++v)
    radius[v] = std::hypot(vessel.vertices[v].x() - profile.axis_x * vp.pixel_size, vessel.vertices[v].z());
  const QString name = QFileInfo(path).completeBaseName();
  add_curve_layer(call.doc, name + QString::fromUtf8(" – profile"), profile_curve(profile, vp.pixel_size),
                  vcg::Color4b(200, 30, 30, 255));
  add_mesh_layer(call.doc, name + QString::fromUtf8(" – vessel"), vessel, radius, {}, true);
  call.log(QString("Vessel from Profile Drawing: %1; %2 vertices, %3 faces; %4 s.")
               .arg(QString::fromStdString(vessel_summary(profile, vp.pixel_size)))
               .arg(thousands(vessel.n_vertices()))
               .arg(thousands(vessel.n_faces()))
               .arg(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 0, 'f', 2));
  for (const std::string& line : vessel_log_lines(profile)) call.log(QString::fromStdString(line));
}

}  // namespace

FilterSpec vessel_from_profile_filter(int id) {
  FilterSpec s{id,
               "Vessel from Profile Drawing",
               kVesselInfo,
               ml::FilterInterface::MeshCreation,
               MeshModel::MM_NONE,
               MeshModel::MM_NONE,
               vessel_parameters,
               apply_vessel,
               true};
  s.needs_mesh = false;
  return s;
}

}  // namespace reliefkit::ml
