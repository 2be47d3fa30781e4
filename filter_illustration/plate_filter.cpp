// ReliefKit — "Export Illustration Plate" (see plate_filter.h): the layers gathered, the plate laid
// out by the core, written as SVG (the core) and PDF (Qt's QPdfWriter, the same page drawn).
#include "plate_filter.h"
#include <algorithm>
#include <cmath>

#include <QElapsedTimer>
#include <QFontMetricsF>
#include <QFile>
#include <QFileInfo>
#include <QPainter>
#include <QPainterPath>
#include <QPdfWriter>
#include <opencv2/imgcodecs.hpp>
#include <optional>

#include "mesh_bridge.h"
#include "params.h"
#include "reliefkit/illustration/plate.h"
#include "reliefkit/pottery/vessel_record.h"
#include "reliefkit/rollout/unroll.h"

namespace reliefkit::ml {
namespace {

const char* kPlateInfo =
    "Writes an <b>illustration plate</b> of the current mesh for a report: an orthographic view at the "
    "scale you state (1:1, 2:1...) or the largest standard one that fits A4, the curve layers as black "
    "vector lines in three pen weights (the parts behind the surface removed), the surface's shading "
    "as grey under them, a cross-section's profile beside the drawing if you ask, a scale bar in "
    "millimetres and the scale. Output: an SVG file and, optionally, a PDF beside it (same name), at "
    "the page size asked — ready for a report or for further work in Inkscape or Illustrator.<br><br>"
    "<b>Curve layers</b>: every layer of curves (edges without faces: Demarcating Curves, Relief "
    "Edges, Ridges and Valleys...), or the ones you name. <b>Shading</b>: the mesh's vertex colours "
    "(run <i>Prominent Coloring</i> or <i>Curvature Shading</i> first: they read best), or light "
    "from the top left. <b>Mesh unit</b>: how many millimetres one unit of the scan is (1 for scans "
    "in mm); the log gives the object's size at that unit — check it.";

const QStringList kViews{"Automatic (a relief faced; an object upright, facing its widest side)", "From +Z (MeshLab's default view)",
                         "Given direction",
                         "Pottery (a vessel or sherd on its axis: Vessel Axis and Profile first)"};
constexpr int kPotteryView = 3;
const QStringList kLayouts{"One view", "Tablet (fat cross: obverse, reverse and the four edges)",
                           "Lithic (dorsal face, right profile, ventral face)", "Two faces (obverse, reverse)",
                           "Figurine (front, right side, back)"};
const QStringList kShadings{"Automatic (vertex colours if any, else light)", "Vertex colours", "Light from the top left",
                            "None (white paper)", "Raking light", "Multi-directional light", "Openness (ambient occlusion)",
                            "Radiance scaling"};
constexpr int kFirstCoreShading = 4;  // the rest are rendered by the core from the view
const QStringList kPages{"Fit the drawing", "A4 portrait", "A4 landscape"};
const QStringList kWeights{"By curve strength (three weights)", "By layer (the first heaviest)", "One weight"};
const QStringList kSections{"None", "Vertical (profile to the right)", "Horizontal (profile below)"};

void plate_parameters(const MeshModel&, RichParameterList& par) {
  par.addParam(ml::RichSaveFile("file", "", "*.svg", "Plate file (SVG)",
                            "Where the plate goes (a relative name: beside the mesh's file). Empty: <mesh>-plate.svg "
                            "beside the mesh's file."));
  par.addParam(RichBool("pdf", true, "Also as PDF", "Writes the same page as a PDF beside the SVG."));
  par.addParam(RichString("layers", "all", "Curve layers",
                          "\"all\": every layer of curves; or the names of the layers to draw, separated by ';', where '*' "
                          "stands for any text (\"*ridges\": the ridges of whatever mesh a script meets)."));
  par.addParam(RichEnum("view", 0, kViews, "View", "Automatic: a relief (a coin, a plaque, a sherd: its least extent "
                                                   "under a third of the others) faced along its least extent, from "
                                                   "the side its normals face; any other object (a figurine, a bust, "
                                                   "a tablet) upright — the scan's up kept, its largest extent up when "
                                                   "it lies on its side — facing its widest side. Pottery: a "
                                                   "vessel or sherd turned onto its axis by Vessel Axis and Profile, "
                                                   "drawn in half-section (axis dash-dot, the section filled on the "
                                                   "left, the exterior on the right, the rim line, the rim diameter "
                                                   "and its preserved share; at 1:1 or reduced)."));
  par.addParam(RichDirection("direction", vcg::Point3f(0, 0, -1), "View direction (given)", "Looking along this direction."));
  par.addParam(RichEnum("layout", 0, kLayouts, "Layout",
                        "Several views of the object on one sheet, at one scale, each named, one scale bar: a cuneiform "
                        "tablet as the fat cross (obverse in the middle, the edges beside the faces they join, the "
                        "reverse below, turned as tablets are turned); a stone tool's dorsal face, right profile and "
                        "ventral face along its long axis; a coin's or seal's two faces; a figurine's front, right side "
                        "and back. The object's front is its widest side (least extent), its up the scan's up (its "
                        "largest extent when it lies on its side): adjust with the two switches below. One view: as View says."));
  par.addParam(RichBool("turn_over", false, "Turn over (layouts)", "The front drawn is the other side (the reverse "
                                                                    "as obverse, the ventral face as dorsal)."));
  par.addParam(RichBool("upside_down", false, "Upside down (layouts)", "Up is down: the object turned in the page."));
  par.addParam(RichString("reverse_layer", "", "Reverse layer (two faces)",
                          "For Two faces: the layer holding the reverse when the two faces were scanned apart; empty: "
                          "the back of this mesh."));
  par.addParam(RichFloat("unit_mm", 1.0f, "Mesh unit (mm)", "Millimetres per unit of the mesh: 1 for a scan in mm, 10 for cm, 25.4 for inches."));
  par.addParam(RichFloat("ratio", 0.0f, "Scale (drawn / real, 0: auto)",
                         "1 for 1:1, 2 for 2:1, 0.5 for 1:2. 0: automatic, the largest standard scale (5:1, 2:1, 1:1, "
                         "1:2...) at which the plate fits the page (A4 when the page fits the drawing)."));
  par.addParam(RichEnum("shading", 0, kShadings, "Shading",
                        "The grey under the lines: the vertex colours (Prominent Coloring, Curvature Shading), light from "
                        "the top left, white paper, or rendered here from the view, headless: raking light (low, from the "
                        "azimuth and elevation below: strokes and tool marks stand out), multi-directional light (lights "
                        "all round at 45 degrees, averaged: a slope shading, no direction favoured), openness (the share of the sky "
                        "each point sees within the radius below: grooves and incisions dark, as LiDAR archaeologists "
                        "read surfaces), radiance scaling (light from the top left, convex parts brightened and concave "
                        "parts darkened by the curvature, after MeshLab's on-screen mode). With one of these four "
                        "a plate needs no curve layer: the shading alone is drawn (a tablet's wedges under raking light)."));
  par.addParam(RichFloat("light_azimuth", 315.0f, "Light azimuth (degrees)",
                         "Where raking light comes from: degrees clockwise from the top of the page (315: the top left)."));
  par.addParam(RichFloat("light_elevation", 20.0f, "Light elevation (degrees)",
                         "Of raking light and the light stack, above the surface seen from the view (10-30 rakes)."));
  par.addParam(RichFloat("openness_radius", 10.0f, "Openness radius (edge lengths)",
                         "How far round each point the surface may hide its sky (openness)."));
  par.addParam(RichInt("light_stack", 0, "Light stack (images)",
                       "0: none. Else that many images of the surface lit by raking light from directions evenly round "
                       "(at the elevation above), written beside the plate with the .lp file that RTI viewers (RTIBuilder, "
                       "Relight) read."));
  par.addParam(RichInt("dpi", 300, "Shading resolution (dpi)", "Of the shading raster on the page (the lines are vectors)."));
  par.addParam(RichFloat("width", 0.35f, "Line width (mm)", "Of the curves (a technical pen's 0.35 mm by default)."));
  par.addParam(RichEnum("weights", 0, kWeights, "Line weights",
                        "By strength: the strongest third of the curves 0.5 mm, the weakest third 0.25 mm (for the "
                        "0.35 mm width). By layer: the first layer 0.5 mm, the second 0.35, the others 0.25."));
  par.addParam(RichEnum("section", 0, kSections, "Cross-section",
                        "The profile of the object cut along a line of the drawing, drawn beside it at the same scale; "
                        "the line marked dash-dot. In a layout, the first view is cut (the dorsal face: a tool's "
                        "cross-section below it when horizontal; the obverse, the front) and the profile drawn below "
                        "it or right of the views."));
  par.addParam(RichBool("section_fill", true, "Fill the section", "A closed profile (a closed mesh cut through: a sherd, a "
                                                                 "tool) filled black, as pottery sections are drawn."));
  par.addParam(RichFloat("section_at", 0.5f, "Section place", "Where the section's line crosses the drawing: a fraction of "
                                                              "its width (vertical) or height (horizontal); 0.5 the middle."));
  par.addParam(RichEnum("page", 0, kPages, "Page", "Fit: the drawing with 10 mm margins. A4: the drawing centred on the page."));
}

// A layer's edges as curves, its vertex quality (the curve filters' strength) as their strength.
PlateCurves curves_of(MeshModel& m, double width_mm) {
  Polylines c = curves_of_layer(m);
  return PlateCurves{m.label().toStdString(), std::move(c.points), std::move(c.segments), width_mm, std::move(c.strength)};
}

// The layers of curves to draw: every layer of edges without faces, or the ones named (each must
// be there and hold curves).
// A wanted name matches a layer's name exactly or, with '*' in it, as a pattern: each '*' stands
// for any text ("*ridges": the ridges of whatever mesh a script meets).
bool name_matches(const QString& wanted, const QString& label) {
  if (!wanted.contains('*')) return wanted == label;
  const QStringList parts = wanted.split('*');
  if (!label.startsWith(parts.front()) || !label.endsWith(parts.back()) ||
      label.size() < parts.front().size() + parts.back().size())
    return false;
  int at = parts.front().size();
  const int end = label.size() - parts.back().size();
  for (int k = 1; k + 1 < parts.size(); ++k) {
    at = label.indexOf(parts[k], at);
    if (at < 0 || at + parts[k].size() > end) return false;
    at += parts[k].size();
  }
  return true;
}

std::vector<PlateCurves> curve_layers(FilterCall& call, const QString& wanted, double width_mm) {
  QStringList names;
  for (const QString& n : wanted.split(';')) if (!n.trimmed().isEmpty()) names << n.trimmed();
  const bool all = names.isEmpty() || (names.size() == 1 && names[0].toLower() == "all");
  std::vector<char> matched(size_t(names.size()), 0);
  std::vector<PlateCurves> layers;
  for (MeshModel* m : document_layers(call.doc)) {
    const bool curves = m->cm.fn == 0 && m->cm.en > 0;
    bool named = false;
    for (int k = 0; k < names.size(); ++k)
      if (!all && name_matches(names[k], m->label())) named = matched[size_t(k)] = 1;
    if (!(all ? curves : named)) continue;
    if (!curves)
      throw InputError(qUtf8Printable("The layer \"" + m->label() + "\" holds " + (m->cm.fn > 0 ? "a surface" : "no edges") +
                                      ", not curves: name a layer of curves (Demarcating Curves, Relief Edges...)."));
    layers.push_back(curves_of(*m, width_mm));
  }
  QStringList missing;
  for (int k = 0; k < names.size(); ++k) if (!all && !matched[size_t(k)]) missing << names[k];
  if (!missing.isEmpty()) throw InputError(qUtf8Printable("No layer is called " + missing.join(" or ") + "."));
  return layers;
}

// Grey per view vertex from the vertex colours (luminance), or empty (the core's Lambertian light).
std::vector<double> shading_of(MeshModel& m, const View& view, int choice) {
  const bool colours = m.hasDataMask(MeshModel::MM_VERTCOLOR);
  if (choice == 1 && !colours) throw InputError("The mesh has no vertex colours: run Prominent Coloring or Curvature Shading first, or choose the light.");
  if (choice == 3) return std::vector<double>(view.mesh.vertices.size(), 1.0);
  if (choice == 2 || choice >= kFirstCoreShading || !colours) return {};
  std::vector<double> grey(view.mesh.vertices.size());
  for_each_vertex(view, [&](int i, const CVertexO* v) {
    const auto& c = v->cC();
    grey[size_t(i)] = (0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]) / 255.0;
  });
  return grey;
}

void write_pdf(const Plate& plate, const QString& path);

// The core's shading asked for (choices from kFirstCoreShading), or none.
std::optional<PlateShadingParams> core_shading(FilterCall& call) {
  const int choice = read_enum(call, "shading", "Shading", kShadings.size());
  if (choice < kFirstCoreShading) return std::nullopt;
  PlateShadingParams s;
  s.kind = PlateShadingKind(choice - kFirstCoreShading);
  s.azimuth_deg = read_float(call, "light_azimuth", "Light azimuth (degrees)", -3600, 3600);
  s.elevation_deg = read_float(call, "light_elevation", "Light elevation (degrees)", 0.01, 90);
  s.radius_edges = read_float(call, "openness_radius", "Openness radius (edge lengths)", 0.01, 1000);
  return s;
}

PlateParams plate_params(FilterCall& call) {
  PlateParams p;
  p.unit_mm = read_float(call, "unit_mm", "Mesh unit (mm)", 1e-9, 1e9);
  p.ratio = read_float(call, "ratio", "Scale (drawn / real, 0: auto)", 0, 1000);
  p.dpi = read_int(call, "dpi", "Shading resolution (dpi)", 50, 2400);
  const int page = read_enum(call, "page", "Page", kPages.size());
  if (page > 0) p.page_width_mm = page == 1 ? 210 : 297, p.page_height_mm = page == 1 ? 297 : 210;
  p.weights = LineWeights(read_enum(call, "weights", "Line weights", kWeights.size()));
  p.section.axis = SectionAxis(read_enum(call, "section", "Cross-section", kSections.size()));
  p.section.at = read_float(call, "section_at", "Section place", 0, 1);
  p.section.fill = read_bool(call, "section_fill", "Fill the section");
  return p;
}

// The pottery convention: the piece as "Vessel Axis and Profile" left it (axis +Z, rim up), its
// record made again as it lies; its own profile layer is not drawn on the exterior.
Plate pottery_plate(FilterCall& call, const Surface& surface, const std::vector<double>& grey, std::vector<PlateCurves>& layers,
                    const PlateParams& p) {
  VesselRecordParams rp;
  rp.as_oriented = true;
  const VesselRecord record = record_vessel(surface, rp);
  const std::string own_profile = derived_label(call.mesh(), "profile").toStdString();
  layers.erase(std::remove_if(layers.begin(), layers.end(), [&](const PlateCurves& l) { return l.name == own_profile; }), layers.end());
  for (const std::string& line : record_log_lines(record))
    if (line.rfind("Rim", 0) == 0 || line.rfind("No rim", 0) == 0) call.log(QString::fromStdString("Pottery plate: " + line));
  return make_pottery_plate(surface.mesh(), grey, layers, pottery_sheet(record), p);
}

// A rollout made by Unroll Around Axis in this session: facing the sheet (from +Z, its axis up),
// its seam dash-dot, named a rollout or a seal impression with its circumference.
void mark_rollout(FilterCall& call, PlateParams& p) {
  const std::optional<SheetMarks> marks = sheet_marks_of(call.mesh());
  if (!marks) return;
  p.guides = marks->seams;
  p.titles = sheet_labels(*marks, p.unit_mm);
  call.log("Plate of a rollout: its seam drawn dash-dot, its title \"" + QString::fromStdString(p.titles.front()) + "\".");
}

PlateView plate_view(FilterCall& call, const View& view) {
  PlateView v;
  const int view_choice = read_enum(call, "view", "View", kViews.size());
  if (view_choice == 0 && !sheet_marks_of(call.mesh())) v = default_view(view.mesh);  // a rollout: the default, from +Z
  if (view_choice == 0 && sheet_marks_of(call.mesh())) v.name = "facing the rollout";
  if (view_choice == 1) v.name = "from +Z";
  if (view_choice == 2) v.name = "along the direction given";
  if (view_choice == 2) {
    const vcg::Point3f d = call.params.getPoint3m("direction");
    v.direction = Vec3(d[0], d[1], d[2]);
  }
  return v;
}

// The folder a relative plate name goes to: the mesh's file's, or — for a layer a filter made (a
// rollout) — the file's of the first layer of the document that has one (the scan it came from).
QString plate_folder(FilterCall& call) {
  if (!call.mesh().fullName().isEmpty()) return call.mesh().pathName();
  for (MeshModel* m : document_layers(call.doc))
    if (!m->fullName().isEmpty()) return m->pathName();
  throw InputError(qUtf8Printable("The layer \"" + call.mesh().label() + "\" has no file (a filter made it) and no layer "
                                  "has one, so there is no folder for the plate: give the plate file a full path."));
}

// The default name: <mesh file's name>-plate.svg, or the layer's label made a file name.
QString plate_name(const MeshModel& m) {
  QString base = m.fullName().isEmpty() ? m.label() : QFileInfo(m.fullName()).completeBaseName();
  if (m.fullName().isEmpty()) base.replace(QString::fromUtf8(" \u2013 "), "-").replace(' ', '_');
  return base + "-plate.svg";
}

// The SVG file asked for (a relative name or none: beside the mesh's file), written.
QString write_svg(FilterCall& call, const Plate& plate) {
  QString svg = call.params.getSaveFileName("file").trimmed();
  if (svg.isEmpty() || QFileInfo(svg).isRelative()) svg = plate_folder(call) + "/" + (svg.isEmpty() ? plate_name(call.mesh()) : svg);
  QFile out(svg);
  if (!out.open(QIODevice::WriteOnly) || out.write(QByteArray::fromStdString(plate_svg(plate))) < 0)
    throw InputError(qUtf8Printable("The plate could not be written to " + svg + " (check the folder exists and is writable)."));
  return svg;
}

// The object's size at the unit given: a scan whose unit is not the millimetre gives itself away.
QString size_text(const Plate& plate, double unit_mm) {
  const Vec2 s = plate.real_size_mm;
  return QString("the object %1 x %2 mm at %3 mm per unit").arg(s.x(), 0, 'g', 4).arg(s.y(), 0, 'g', 4).arg(unit_mm);
}

// The curve layers drawn on `m`: those derived from it (<mesh> – …), or all when none is.
std::vector<PlateCurves> curves_of_mesh(const MeshModel& m, const std::vector<PlateCurves>& layers) {
  const std::string prefix = derived_label(m, "").toStdString();
  std::vector<PlateCurves> own;
  for (const PlateCurves& l : layers)
    if (l.name.rfind(prefix, 0) == 0) own.push_back(l);
  return own.empty() ? layers : own;
}

// A layout's plate: the views of this mesh, or for Two faces with a reverse layer, each face's.
Plate layout_plate(FilterCall& call, View& view, const Surface& surface, const std::vector<double>& grey, const std::vector<PlateCurves>& layers,
                   PlateLayout layout, const PlateParams& p, const std::optional<PlateShadingParams>& core, PlateView& main_view) {
  const ObjectFrame frame = object_frame(view.mesh, layout, read_bool(call, "turn_over", "Turn over (layouts)"),
                                         read_bool(call, "upside_down", "Upside down (layouts)"));
  const QString reverse_name = call.params.getString("reverse_layer").trimmed();
  if (layout != PlateLayout::two_faces || reverse_name.isEmpty()) {
    QStringList names;
    for (const LayoutView& v : layout_views(layout, frame)) names << QString::fromStdString(v.name);
    call.log(QString::fromStdString("Plate layout: " + frame.how + "; views: ") + names.join(", ") + ".");
    if (!frame.warning.empty()) call.log(QString::fromStdString(frame.warning));
    main_view = layout_views(layout, frame).front().view;  // the obverse, dorsal face or front
    return make_layout_plate(view.mesh, grey, layers, layout, frame, p, core ? &*core : nullptr);
  }
  MeshModel* reverse = nullptr;
  for (MeshModel* m : document_layers(call.doc))
    if (m->label() == reverse_name) reverse = m;
  if (!reverse || reverse == &call.mesh())
    throw InputError(qUtf8Printable("Two faces: no other layer is called \"" + reverse_name + "\" (the reverse's layer; "
                                    "leave it empty to draw the back of this mesh)."));
  View back = view_of(*reverse, call.log);
  std::vector<double> back_grey = shading_of(*reverse, back, read_enum(call, "shading", "Shading", kShadings.size()));
  const std::vector<PlateCurves> front_curves = curves_of_mesh(call.mesh(), layers), back_curves = curves_of_mesh(*reverse, layers);
  LayoutView obverse{"obverse", default_view(view.mesh), 0, 0}, other{"reverse", default_view(back.mesh), 1, 0};
  main_view = obverse.view;
  std::vector<double> front_grey = grey;
  if (core) front_grey = plate_shading(surface, obverse.view, *core), back_grey = plate_shading(surface_of(back), other.view, *core);
  call.log("Plate layout: two faces from two layers, \"" + call.mesh().label() + "\" (obverse) and \"" + reverse_name +
           "\" (reverse), each " + QString::fromStdString(obverse.view.name) + ".");
  return make_panels_plate({PlatePanel{&view.mesh, &front_grey, &front_curves, obverse}, PlatePanel{&back.mesh, &back_grey, &back_curves, other}}, p);
}

// The light stack asked for: its images and .lp file beside the plate (<plate>-light-01.png ...).
void write_light_stack(FilterCall& call, const Surface& surface, const PlateView& main_view, const PlateParams& p, double ratio, const QString& svg) {
  const int count = read_int(call, "light_stack", "Light stack (images)", 0, 360);
  if (count == 0) return;
  const LightStack stack = light_stack(surface, main_view, p, ratio, count,
                                       read_float(call, "light_elevation", "Light elevation (degrees)", 0.01, 90));
  const QString base = QFileInfo(svg).path() + "/" + QFileInfo(svg).completeBaseName();
  std::vector<std::string> names;
  for (size_t k = 0; k < stack.images.size(); ++k) {
    const QString name = QFileInfo(base).fileName() + QString("-light-%1.png").arg(k + 1, 2, 10, QChar('0'));
    if (!cv::imwrite((QFileInfo(svg).path() + "/" + name).toStdString(), stack.images[k]))
      throw InputError(qUtf8Printable("The light stack's image " + name + " could not be written."));
    names.push_back(name.toStdString());
  }
  QFile lp(base + ".lp");
  if (!lp.open(QIODevice::WriteOnly) || lp.write(QByteArray::fromStdString(lp_file(names, stack.directions))) < 0)
    throw InputError(qUtf8Printable("The light stack's file " + base + ".lp could not be written."));
  call.log(QString("Light stack: %1 images lit from %2 directions round at %3 degrees, and %4.lp, beside the plate.")
               .arg(count).arg(count).arg(read_float(call, "light_elevation", "Light elevation (degrees)", 0.01, 90)).arg(base));
}

void apply_plate(FilterCall& call) {
  QElapsedTimer timer;
  timer.start();
  View view = view_of(call.mesh(), call.log);
  PlateParams p = plate_params(call);
  p.progress = call.progress;
  const double width = read_float(call, "width", "Line width (mm)", 0.01, 10);
  p.section.width_mm = width * 0.5 / 0.35;  // the profile in the heavy pen
  std::vector<PlateCurves> layers = curve_layers(call, call.params.getString("layers"), width);
  std::vector<double> grey = shading_of(call.mesh(), view, read_enum(call, "shading", "Shading", kShadings.size()));
  const std::optional<PlateShadingParams> core = core_shading(call);
  p.curves_required = !core;  // a rendered shading alone is a plate (a tablet under raking light); white paper is not
  const Surface surface = surface_of(view);  // the run's geometry, once: the record, the shadings, the light stack
  Plate plate;
  PlateView main_view;  // the view the light stack is taken from
  const auto layout = PlateLayout(read_enum(call, "layout", "Layout", kLayouts.size()));
  if (read_enum(call, "view", "View", kViews.size()) == kPotteryView) {
    main_view = pottery_front_view();
    if (core) grey = plate_shading(surface, main_view, *core);
    plate = pottery_plate(call, surface, grey, layers, p);
  } else if (layout != PlateLayout::one_view) {
    plate = layout_plate(call, view, surface, grey, layers, layout, p, core, main_view);
  } else {
    mark_rollout(call, p);
    main_view = plate_view(call, view);
    call.log(QString::fromStdString("Plate view: " + main_view.name + "."));
    if (core) grey = plate_shading(surface, main_view, *core);
    plate = make_plate(view.mesh, grey, layers, main_view, p);
  }
  const QString svg = write_svg(call, plate);
  write_light_stack(call, surface, main_view, p, plate.ratio, svg);
  QString pdf;
  if (read_bool(call, "pdf", "Also as PDF")) write_pdf(plate, pdf = QFileInfo(svg).path() + "/" + QFileInfo(svg).completeBaseName() + ".pdf");
  call.log(QString("Illustration plate: %1 x %2 mm at %3%4, %5 curve layer(s), %6 paths (%7 segments visible, %8)%9; "
                   "%10; scale bar %11; written to %12%13; %14 s.")
               .arg(plate.width_mm, 0, 'f', 1).arg(plate.height_mm, 0, 'f', 1).arg(QString::fromStdString(plate.scale_label))
               .arg(p.ratio > 0 ? "" : " (automatic)").arg(layers.size()).arg(plate.paths.size())
               .arg(thousands(plate.visible_segments))
               .arg(thousands(plate.hidden_segments) + " hidden" +
                    (plate.outside_segments > 0 ? QString(", %1 off the mesh's drawing").arg(thousands(plate.outside_segments)) : QString()))
               .arg(plate.section_segments > 0 ? QString(", a section of %1 segments").arg(plate.section_segments) : QString())
               .arg(size_text(plate, p.unit_mm)).arg(QString::fromStdString(plate.bar_label)).arg(svg)
               .arg(pdf.isEmpty() ? QString() : " and " + pdf).arg(timer.elapsed() / 1000.0, 0, 'f', 2));
  for (const std::string& warning : plate_warnings(plate, p.unit_mm)) call.log(QString::fromStdString(warning));
}

// The page description (the same the SVG is written from) through QPainter, in millimetres.
void draw_mark(QPainter& painter, const Plate& plate, const PageMark& m) {
  if (m.kind == PageMark::Kind::shading) {
    const QImage shading(plate.shading.data, plate.shading.cols, plate.shading.rows, int(plate.shading.step), QImage::Format_Grayscale8);
    painter.drawImage(QRectF(QPointF(m.points[0].x(), m.points[0].y()), QPointF(m.points[1].x(), m.points[1].y())), shading);
  } else if (m.kind == PageMark::Kind::path) {
    QPainterPath line(QPointF(m.points[0].x(), m.points[0].y()));
    for (size_t i = 1; i < m.points.size(); ++i) line.lineTo(m.points[i].x(), m.points[i].y());
    if (m.filled) line.closeSubpath(), painter.fillPath(line, Qt::black);
    QPen pen(Qt::black, m.width_mm, Qt::SolidLine, m.round_caps ? Qt::RoundCap : Qt::FlatCap, Qt::RoundJoin);
    if (!m.dashes.empty()) {  // Qt's dashes are in pen widths
      QVector<qreal> dashes;
      for (double d : m.dashes) dashes << d / m.width_mm;
      pen.setDashPattern(dashes);
    }
    painter.setPen(pen);
    painter.drawPath(line);
  } else {
    QFont font("DejaVu Sans");
    font.setPixelSize(std::max(1, int(std::lround(m.size_mm))));
    painter.setFont(font);
    painter.setPen(QPen(Qt::black));
    const QString text = QString::fromStdString(m.text);
    const double shift = m.centred ? 0.5 * QFontMetricsF(font).horizontalAdvance(text) : 0;
    painter.drawText(QPointF(m.points[0].x() - shift, m.points[0].y()), text);
  }
}

// The plate as a PDF: the page description drawn with millimetres mapped to the PDF's points.
void write_pdf(const Plate& plate, const QString& path) {
  QPdfWriter pdf(path);
  pdf.setPageSize(QPageSize(QSizeF(plate.width_mm, plate.height_mm), QPageSize::Millimeter));
  pdf.setPageMargins(QMarginsF(0, 0, 0, 0));
  pdf.setResolution(1200);
  QPainter painter;
  if (!painter.begin(&pdf)) throw InputError(qUtf8Printable("The PDF could not be written to " + path + "."));
  painter.scale(1200 / 25.4, 1200 / 25.4);  // device pixels per millimetre
  for (const PageMark& m : page_marks(plate)) draw_mark(painter, plate, m);
  painter.end();
}
}  // namespace

FilterSpec illustration_plate_filter(int id) {
  FilterSpec s{id, "Export Illustration Plate", QString(kPlateInfo), FilterInterface::MeshCreation, MeshModel::MM_NONE,
               MeshModel::MM_NONE, plate_parameters, apply_plate, false};
  return s;
}

}  // namespace reliefkit::ml
