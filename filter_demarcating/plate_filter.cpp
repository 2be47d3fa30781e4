// ReliefKit — "Export Illustration Plate" (see plate_filter.h): the layers gathered, the plate laid
// out by the core, written as SVG (the core) and PDF (Qt's QPdfWriter, the same page drawn).
#include "plate_filter.h"
#include <algorithm>
#include <cmath>

#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QPainter>
#include <QPainterPath>
#include <QPdfWriter>

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

const QStringList kViews{"Facing the relief (its least extent)", "From +Z (MeshLab's default view)", "Given direction",
                         "Pottery (a vessel or sherd on its axis: Vessel Axis and Profile first)"};
constexpr int kPotteryView = 3;
const QStringList kShadings{"Automatic (vertex colours if any, else light)", "Vertex colours", "Light from the top left",
                            "None (white paper)"};
const QStringList kPages{"Fit the drawing", "A4 portrait", "A4 landscape"};
const QStringList kWeights{"By curve strength (three weights)", "By layer (the first heaviest)", "One weight"};
const QStringList kSections{"None", "Vertical (profile to the right)", "Horizontal (profile below)"};

void plate_parameters(const MeshModel&, RichParameterList& par) {
  par.addParam(ml::RichSaveFile("file", "", "*.svg", "Plate file (SVG)",
                            "Where the plate goes (a relative name: beside the mesh's file). Empty: <mesh>-plate.svg "
                            "beside the mesh's file."));
  par.addParam(RichBool("pdf", true, "Also as PDF", "Writes the same page as a PDF beside the SVG."));
  par.addParam(RichString("layers", "all", "Curve layers",
                          "\"all\": every layer of curves; or the names of the layers to draw, separated by ';'."));
  par.addParam(RichEnum("view", 0, kViews, "View", "Facing the relief: along its least extent, from the side its "
                                                   "normals face (a coin, a plaque, a sherd's exterior). Pottery: a "
                                                   "vessel or sherd turned onto its axis by Vessel Axis and Profile, "
                                                   "drawn in half-section (axis dash-dot, the section filled on the "
                                                   "left, the exterior on the right, the rim line, the rim diameter "
                                                   "and its preserved share; at 1:1 or reduced)."));
  par.addParam(RichDirection("direction", vcg::Point3f(0, 0, -1), "View direction (given)", "Looking along this direction."));
  par.addParam(RichFloat("unit_mm", 1.0f, "Mesh unit (mm)", "Millimetres per unit of the mesh: 1 for a scan in mm, 10 for cm, 25.4 for inches."));
  par.addParam(RichFloat("ratio", 0.0f, "Scale (drawn / real, 0: auto)",
                         "1 for 1:1, 2 for 2:1, 0.5 for 1:2. 0: automatic, the largest standard scale (5:1, 2:1, 1:1, "
                         "1:2...) at which the plate fits the page (A4 when the page fits the drawing)."));
  par.addParam(RichEnum("shading", 0, kShadings, "Shading", "The grey under the lines."));
  par.addParam(RichInt("dpi", 300, "Shading resolution (dpi)", "Of the shading raster on the page (the lines are vectors)."));
  par.addParam(RichFloat("width", 0.35f, "Line width (mm)", "Of the curves (a technical pen's 0.35 mm by default)."));
  par.addParam(RichEnum("weights", 0, kWeights, "Line weights",
                        "By strength: the strongest third of the curves 0.5 mm, the weakest third 0.25 mm (for the "
                        "0.35 mm width). By layer: the first layer 0.5 mm, the second 0.35, the others 0.25."));
  par.addParam(RichEnum("section", 0, kSections, "Cross-section",
                        "The profile of the object cut along a line of the drawing, drawn beside it at the same scale; "
                        "the line marked dash-dot."));
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
std::vector<PlateCurves> curve_layers(FilterCall& call, const QString& wanted, double width_mm) {
  QStringList names;
  for (const QString& n : wanted.split(';')) if (!n.trimmed().isEmpty()) names << n.trimmed();
  const bool all = names.isEmpty() || (names.size() == 1 && names[0].toLower() == "all");
  std::vector<PlateCurves> layers;
  for (MeshModel* m : document_layers(call.doc)) {
    const bool curves = m->cm.fn == 0 && m->cm.en > 0;
    if (all ? curves : names.removeAll(m->label()) > 0) {
      if (!curves)
        throw InputError(qUtf8Printable("The layer \"" + m->label() + "\" holds " + (m->cm.fn > 0 ? "a surface" : "no edges") +
                                        ", not curves: name a layer of curves (Demarcating Curves, Relief Edges...)."));
      layers.push_back(curves_of(*m, width_mm));
    }
  }
  if (!all && !names.isEmpty()) throw InputError(qUtf8Printable("No layer is called " + names.join(" or ") + "."));
  return layers;
}

// Grey per view vertex from the vertex colours (luminance), or empty (the core's Lambertian light).
std::vector<double> shading_of(MeshModel& m, const View& view, int choice) {
  const bool colours = m.hasDataMask(MeshModel::MM_VERTCOLOR);
  if (choice == 1 && !colours) throw InputError("The mesh has no vertex colours: run Prominent Coloring or Curvature Shading first, or choose the light.");
  if (choice == 3) return std::vector<double>(view.mesh.vertices.size(), 1.0);
  if (choice == 2 || !colours) return {};
  std::vector<double> grey(view.mesh.vertices.size());
  for_each_vertex(view, [&](int i, const CVertexO* v) {
    const auto& c = v->cC();
    grey[size_t(i)] = (0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]) / 255.0;
  });
  return grey;
}

void write_pdf(const Plate& plate, const QString& path);

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
Plate pottery_plate(FilterCall& call, View& view, const std::vector<double>& grey, std::vector<PlateCurves>& layers,
                    const PlateParams& p) {
  VesselRecordParams rp;
  rp.as_oriented = true;
  const VesselRecord record = record_vessel(surface_of(view), rp);
  const std::string own_profile = derived_label(call.mesh(), "profile").toStdString();
  layers.erase(std::remove_if(layers.begin(), layers.end(), [&](const PlateCurves& l) { return l.name == own_profile; }), layers.end());
  for (const std::string& line : record_log_lines(record))
    if (line.rfind("Rim", 0) == 0 || line.rfind("No rim", 0) == 0) call.log(QString::fromStdString("Pottery plate: " + line));
  return make_pottery_plate(view.mesh, grey, layers, pottery_sheet(record), p);
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
  if (view_choice == 0 && !sheet_marks_of(call.mesh())) v = facing_view(view.mesh);  // a rollout: the default, from +Z
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

// A size no object drawn for a report has (over 1 m, under 5 mm) is most likely a wrong unit.
void warn_of_unit(FilterCall& call, const Plate& plate, double unit_mm) {
  const double size = std::max(plate.real_size_mm.x(), plate.real_size_mm.y());
  if (size <= 1000 && size >= 5) return;
  call.log("Warning: " + size_text(plate, unit_mm) + ": if that is not its size, the scan is not in that unit — set Mesh "
           "unit (mm) to the scan's unit (the plate's scale and scale bar assume it).");
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
  const std::vector<double> grey = shading_of(call.mesh(), view, read_enum(call, "shading", "Shading", kShadings.size()));
  Plate plate;
  if (read_enum(call, "view", "View", kViews.size()) == kPotteryView) {
    plate = pottery_plate(call, view, grey, layers, p);
  } else {
    mark_rollout(call, p);
    plate = make_plate(view.mesh, grey, layers, plate_view(call, view), p);
  }
  const QString svg = write_svg(call, plate);
  QString pdf;
  if (read_bool(call, "pdf", "Also as PDF")) write_pdf(plate, pdf = QFileInfo(svg).path() + "/" + QFileInfo(svg).completeBaseName() + ".pdf");
  call.log(QString("Illustration plate: %1 x %2 mm at %3%4, %5 curve layer(s), %6 paths (%7 segments visible, %8 hidden)%9; "
                   "%10; scale bar %11; written to %12%13; %14 s.")
               .arg(plate.width_mm, 0, 'f', 1).arg(plate.height_mm, 0, 'f', 1).arg(QString::fromStdString(plate.scale_label))
               .arg(p.ratio > 0 ? "" : " (automatic)").arg(layers.size()).arg(plate.paths.size())
               .arg(thousands(plate.visible_segments))
               .arg(thousands(plate.hidden_segments) +
                    (plate.outside_segments > 0 ? QString(", %1 off the mesh's drawing").arg(thousands(plate.outside_segments)) : QString()))
               .arg(plate.section_segments > 0 ? QString(", a section of %1 segments").arg(plate.section_segments) : QString())
               .arg(size_text(plate, p.unit_mm)).arg(QString::fromStdString(plate.bar_label)).arg(svg)
               .arg(pdf.isEmpty() ? QString() : " and " + pdf).arg(timer.elapsed() / 1000.0, 0, 'f', 2));
  warn_of_unit(call, plate, p.unit_mm);
}

// The same page through QPainter: millimetres mapped to the PDF's points.
void write_pdf(const Plate& plate, const QString& path) {
  QPdfWriter pdf(path);
  pdf.setPageSize(QPageSize(QSizeF(plate.width_mm, plate.height_mm), QPageSize::Millimeter));
  pdf.setPageMargins(QMarginsF(0, 0, 0, 0));
  pdf.setResolution(1200);
  QPainter painter;
  if (!painter.begin(&pdf)) throw InputError(qUtf8Printable("The PDF could not be written to " + path + "."));
  const double k = 1200 / 25.4;  // device pixels per millimetre
  painter.scale(k, k);
  const QImage shading(plate.shading.data, plate.shading.cols, plate.shading.rows, int(plate.shading.step), QImage::Format_Grayscale8);
  painter.drawImage(QRectF(plate.drawing_origin_mm.x(), plate.drawing_origin_mm.y(), plate.drawing_size_mm.x(), plate.drawing_size_mm.y()), shading);
  for (const auto& path_ : plate.paths) {
    QPainterPath line(QPointF(path_.points[0].x(), path_.points[0].y()));
    for (size_t i = 1; i < path_.points.size(); ++i) line.lineTo(path_.points[i].x(), path_.points[i].y());
    if (path_.filled) line.closeSubpath(), painter.fillPath(line, Qt::black);
    QPen pen(Qt::black, path_.width_mm, Qt::SolidLine, path_.dash_dot ? Qt::FlatCap : Qt::RoundCap, Qt::RoundJoin);
    if (path_.dash_dot) pen.setDashPattern({3 / path_.width_mm, 1 / path_.width_mm, 0.5 / path_.width_mm, 1 / path_.width_mm});
    painter.setPen(pen);
    painter.drawPath(line);
  }
  const double x = plate.bar_start_mm.x(), y = plate.bar_start_mm.y(), len = plate.bar_length_mm;
  painter.setPen(QPen(Qt::black, 0.3));
  painter.drawLine(QPointF(x, y), QPointF(x + len, y));
  painter.drawLine(QPointF(x, y - 1), QPointF(x, y + 1));
  painter.drawLine(QPointF(x + len, y - 1), QPointF(x + len, y + 1));
  QFont font("DejaVu Sans");
  font.setPixelSize(3);  // 3 mm: the painter's unit is the millimetre
  painter.setFont(font);
  painter.drawText(QRectF(x - 10, y + 1, len + 20, 5), Qt::AlignHCenter | Qt::AlignTop, QString::fromStdString(plate.bar_label));
  painter.drawText(QRectF(x + len + 4, y - 2.5, 40, 5), Qt::AlignLeft | Qt::AlignVCenter, QString::fromStdString(plate.scale_label));
  for (const PlateText& t : plate.texts) {
    QFont text_font("DejaVu Sans");
    text_font.setPixelSize(int(std::lround(t.size_mm)));
    painter.setFont(text_font);
    painter.drawText(QRectF(t.at.x() - 60, t.at.y() - 1.3 * t.size_mm, 120, 1.3 * t.size_mm), Qt::AlignHCenter | Qt::AlignBottom,
                     QString::fromStdString(t.text));
  }
  painter.end();
}
}  // namespace

FilterSpec illustration_plate_filter(int id) {
  FilterSpec s{id, "Export Illustration Plate", QString(kPlateInfo), FilterInterface::MeshCreation, MeshModel::MM_NONE,
               MeshModel::MM_NONE, plate_parameters, apply_plate, false};
  return s;
}

}  // namespace reliefkit::ml
