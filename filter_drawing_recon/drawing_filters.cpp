#include "drawing_filters.h"
#include "drawing_image.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <chrono>
#include <cmath>

#include "mesh_bridge.h"
#include "params.h"
#include "reliefkit/drawing/drawing_file.h"
#include "reliefkit/drawing/drawing_relief.h"

namespace reliefkit::ml {
namespace {

const char* kCitation =
    "M. Kolomenkin, G. Leifman, I. Shimshoni, A. Tal, <b>\"Reconstruction of relief objects from line "
    "drawings\"</b>, CVPR 2011; thesis chapter 7. Line detection: C. Steger, PAMI 1998.";

const char* kCurvesInfo =
    "Finds the <b>lines of a scanned drawing</b> (an excavation report's figure of a lamp, a seal, a stone tool) "
    "and adds them as a new layer of curves, so that the extraction can be inspected before a relief is built "
    "from it.<br><br>"
    "<b>Input</b>: an image file (PNG, JPEG, TIFF...; grey, colour or with a transparent background) of dark "
    "lines on light paper. <b>Output</b>: a new layer <i>&lt;image&gt; – curves</i>: the curves as edges in the "
    "plane z = 0, image x to the right and y up, one pixel = 25.4 / DPI &times; scale millimetres; vertex "
    "quality = the curve's id, as the interpretation file of <i>Relief from Line Drawing</i> names it.<br><br>"
    "Method: the image is smoothed (Gaussian, <i>Line scale</i>); a pixel is on a line where the second "
    "derivative across the line is strong, the first vanishes (the line's centre, to a sub-pixel) and the "
    "image is dark; points are linked along the lines, pieces that face each other across a junction or a "
    "corner are joined, strokes shorter than <i>Shortest stroke</i> (stippling) are dropped. Hatching and "
    "cross-hatching (families of near-parallel strokes) go to a layer <i>&lt;image&gt; – shading</i>; each "
    "object's outline is completed from its ink where no line was found along it. ";

const char* kReliefInfo =
    "Builds a <b>3-D relief from a line drawing</b>: which side of each line is higher is decided "
    "automatically (the paper around the object is the ground, and shapes drawn inside others rise from them, "
    "one step per line), then a smooth surface is made that steps up or down across every line and is smooth "
    "between them.<br><br>"
    "<b>Output</b>: a new layer <i>&lt;image&gt; – relief</i> (made current) on a plane, on a cylinder whose "
    "circumference is the drawing's width (a roll-out drawing of a cup or a lamp), or on the current layer (the "
    "drawing projected onto it), with vertex quality = the height over the base and the per-vertex attribute <code>drawing_level</code> (the level "
    "each part was given); a layer <i>&lt;image&gt; – curves</i> with the lines on the relief, and <i>&lt;image&gt; – "
    "shading</i> with the hatching's strokes (shading is no step; <i>Shading engraved</i> cuts it in as a "
    "texture); and, beside the "
    "image, the <b>interpretation file</b> <i>&lt;image&gt;.interpretation.json</i>: every curve with its id, ends, "
    "sides and step. To change the result, edit a curve's <code>direction</code> (auto, left-lower, "
    "right-lower), <code>weight</code> (levels of its step, or a ridge's height) or <code>profile</code> (step, "
    "ridge, valley) in a copy of that file and give it as <i>Interpretation file</i>.<br><br>"
    "Method: thesis sect. 7.3 (the regions between the lines form a graph; it is directed from the ground "
    "up and levelled by topological order) and 7.4 (a smoothed step of width <i>Step width</i> across each "
    "line; the Laplacian of the relief is interpolated smoothly between the lines, eq. 7.4, then the relief, "
    "eq. 7.6, kept within half a step of each part's level and above the ground). ";

const QStringList kBases = {"Plane", "Cylinder (the drawing's width goes round it)",
                             "Current layer (the drawing projected onto it)"};
enum BaseChoice { kPlane, kCylinder, kCurrent };
const QStringList kPlacements = {"Fitted to the layer (along the view direction)",
                                 "As drawn (the drawing's frame: DPI and scale)"};
const QStringList kGrounds = {"The paper around the drawing", "The most connected region (the thesis' heuristic)"};

// ---- Shared: the drawing and its curves ----

void drawing_parameters(RichParameterList& par) {
  add_drawing_image_parameter(par, "The scanned line drawing: dark lines on light paper (PNG, JPEG, TIFF, BMP; grey, "
                                   "colour or RGBA with a transparent background).");
  par.addParam(RichFloat("sigma", 0.f, "Line scale (px, 0: auto)",
                         "Standard deviation of the Gaussian that smooths the image before lines are found, about the "
                         "lines' half-width. 0 (automatic): each line at the scale of its own width (1, 2, 4 or 8 px), "
                         "so a heavy outline and thin scar lines or hatching in one drawing are each found at their "
                         "centres; each curve's width is recorded and sets how far its ends reach to close a region. "
                         "A number: that one scale for every line (the thesis: 2 px)."));
  par.addParam(RichFloat("min_length", 12.f, "Shortest stroke (px)",
                         "Strokes shorter than this are taken for shading (stippling, hatching) and dropped."));
  par.addParam(RichBool("shading", true, "Recognise shading",
                        "Hatching and cross-hatching (families of near-parallel strokes, at least four, a few line "
                        "widths apart) are shading, not the object's lines: they go to their own layer "
                        "\"<image> – shading\" and take no part in the relief's regions, while the lines they end on "
                        "still do. Untick when close parallel lines are the object's (fluting, a row of grooves)."));
  par.addParam(RichFloat("outline_gap", 6.f, "Outline gaps closed (px, 0: none)",
                         "Each drawn object (its ink, dots and hatching included, closed over gaps of up to twice "
                         "this, holes filled) gets its outline where no line was found along it — an engraving draws "
                         "an edge with the ends of its hatching, with dots or with a broken line — so that every "
                         "object rises as one body from the paper. Objects drawn closer than twice this become one: "
                         "lower it for views drawn close together."));
  add_dpi_and_scale_parameters(par);
}

struct Drawing {
  QString path;
  cv::Mat image;
  LineDetectionParams detection;
  DrawingCurves curves;
  double pixel_mm = 1;  // mesh units (mm) per pixel of the image as read
};

Drawing read_drawing(FilterCall& call) {
  Drawing d;
  d.detection.sigma = read_float(call, "sigma", "Line scale (px, 0: auto)", 0, 50);
  if (d.detection.sigma > 0 && d.detection.sigma < 0.5)
    throw InputError("Line scale (px, 0: auto): 0 for automatic, or at least 0.5 px.");
  d.detection.min_length = read_float(call, "min_length", "Shortest stroke (px)", 0, 1e6);
  d.detection.recognise_shading = call.params.getBool("shading");
  d.detection.object_gap = read_float(call, "outline_gap", "Outline gaps closed (px, 0: none)", 0, 1000);
  d.pixel_mm = read_pixel_mm(call);
  if (call.progress) call.progress(2, "Reading the drawing");
  d.image = read_drawing_parameter(call, d.pixel_mm, &d.path);
  if (call.progress) call.progress(10, "Finding the lines");
  d.curves = extract_drawing_curves(d.image, d.detection);
  if (d.curves.curves.empty())
    throw InputError(QString("No lines were found in \"%1\" (%2 x %3 px): the image is blank, or its lines are lighter or "
                             "shorter than the line detection takes (Line scale %4, Shortest stroke %5 px).")
                         .arg(QFileInfo(d.path).fileName())
                         .arg(d.image.cols)
                         .arg(d.image.rows)
                         .arg(d.detection.sigma > 0 ? QString::number(d.detection.sigma) + " px" : QString("automatic"))
                         .arg(d.detection.min_length)
                         .toStdString());
  return d;
}

const vcg::Color4b kShadingColour(150, 150, 150, 255);

// What the log says of the shading strokes and the outline pieces added.
QString shading_and_outlines(const DrawingCurves& c, long shading) {
  return QString("%1 of the curves recognised as shading (hatching; layer \"– shading\"), %2 outline pieces added "
                 "where an object's edge had no line.")
      .arg(shading)
      .arg(c.outline_pieces);
}

QString image_label(const Drawing& d, const char* what) { return QFileInfo(d.path).completeBaseName() + QString::fromUtf8(" – ") + what; }

// ---- Line Drawing to Curves ----

void curves_parameters(const MeshModel&, RichParameterList& par) {
  drawing_parameters(par);
  par.addParam(RichFloat("margins", 0.f, "Margins (px, 0: none)",
                         "When positive, a second layer \"<image> – margins\" shows each curve's margins: the curve "
                         "offset by this many pixels to either side (the Step width of Relief from Line Drawing is "
                         "4 px), so that closely drawn curves whose steps will meet can be seen."));
}

void apply_curves(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const Drawing d = read_drawing(call);
  const double margins = read_float(call, "margins", "Margins (px, 0: none)", 0, 1000);
  const QString label = image_label(d, "curves");
  const DrawingCurves shading = curves_where(d.curves, d.curves.shading, true);
  add_curve_layer(call.doc, label, drawing_polylines(curves_where(d.curves, d.curves.shading, false), d.pixel_mm),
                  vcg::Color4b(20, 20, 20, 255));
  if (!shading.curves.empty())
    add_curve_layer(call.doc, image_label(d, "shading"), drawing_polylines(shading, d.pixel_mm), kShadingColour);
  if (margins > 0) {
    DrawingCurves m;
    m.curves = margin_lines(d.curves, margins);
    add_curve_layer(call.doc, image_label(d, "margins"), drawing_polylines(m, d.pixel_mm), vcg::Color4b(40, 90, 220, 255));
  }
  call.log(QString("Line Drawing to Curves: \"%1\" %2 x %3 px; %4 curves (%5 px of lines, %6 junctions), %7 short strokes "
                   "dropped; layer \"%8\", pixel %9 mm; %10 s. %11")
               .arg(QFileInfo(d.path).fileName())
               .arg(d.image.cols)
               .arg(d.image.rows)
               .arg(d.curves.curves.size())
               .arg(thousands((long long)std::lround(d.curves.total_length())))
               .arg(d.curves.junctions.size())
               .arg(d.curves.dropped_short)
               .arg(label)
               .arg(d.pixel_mm, 0, 'g', 4)
               .arg(seconds_since(t0), 0, 'f', 2)
               .arg(shading_and_outlines(d.curves, std::count(d.curves.shading.begin(), d.curves.shading.end(), char(1)))));
}

// ---- Relief from Line Drawing ----

void relief_parameters(const MeshModel&, RichParameterList& par) {
  drawing_parameters(par);
  par.addParam(ml::RichOpenFile("interpretation", "", QStringList{"*.json"}, "Interpretation file",
                            "Empty: automatic. Otherwise a JSON interpretation file (as this filter writes beside the "
                            "image, edited): its curves' directions, weights and profiles are kept."));
  par.addParam(RichEnum("ground", 0, kGrounds, "Ground level",
                        "Which region is the ground the relief rises from (level 0). The paper around the drawing "
                        "(regions touching the image's border); or, as in the thesis, the region bordered by most "
                        "curves — for a drawing of a relief's surface without paper around it."));
  par.addParam(RichEnum("base", 0, kBases, "Base",
                        "The surface the relief stands on: a plane; a cylinder round which the drawing is rolled (its "
                        "width is the circumference); or the current layer (any mesh: a scan of the object, or its "
                        "smooth base), onto which the drawing is projected along the view direction, scaled to fit "
                        "the part of it that faces the view."));
  par.addParam(ml::RichDirection("view", vcg::Point3f(0, 0, 0), "View direction (current layer)",
                           "Direction in which the drawing is projected onto the current layer (towards it). 0 0 0: "
                           "automatic, along the layer's axis of least extent (the normal of a plaque)."));
  par.addParam(RichEnum("placement", 0, kPlacements, "Placement (current layer)",
                        "How the drawing lies on the current layer. Fitted: projected along the view direction and "
                        "scaled to the part of the layer facing it. As drawn: in the drawing's own frame (x right, y "
                        "up, millimetres from DPI and scale, seen from +z) — for the decoration of a vessel's exterior, "
                        "raised on the layer \"Vessel from Profile Drawing\" made from the same drawing."));
  par.addParam(RichFloat("margin", 4.f, "Step width (px)",
                         "Half-width of the smoothed step across each line, in pixels of the drawing. Closely drawn "
                         "lines need a small width; wide ones give softer steps."));
  par.addParam(RichFloat("step_height", 0.5f, "Step height (% of the drawing's width)",
                         "Height of one level, as a percentage of the width of the drawn part of the image, so the "
                         "same script suits any DPI and scale."));
  par.addParam(RichFloat("shading_depth", 0.f, "Shading engraved (steps, 0: none)",
                         "With Recognise shading: the hatching's strokes cut into the relief as fine grooves this many "
                         "steps deep (0.2: a texture that reads in raking light), so that the shaded parts show as "
                         "they were drawn. 0: the shading is only in its own layer."));
  par.addParam(RichFloat("cell", 0.f, "Base resolution (px)",
                         "Spacing of the base's vertices in pixels of the drawing. 0: automatic: half the step width "
                         "(each step over four vertices) or a quarter of the narrowest region between curves, if "
                         "finer; coarser only when the base would exceed 4 million vertices."));
}

constexpr long kMaxAutoVertices = 4000000;

// What "Relief from Line Drawing" reads besides the drawing.
struct ReliefSettings {
  QString interpretation;  // the user's file ("" automatic)
  int ground = 0;
  int base = kPlane;
  bool as_drawn = false;   // placement on the current layer: the drawing's frame, not fitted
  DrawingReliefParams relief;
  double step_percent = 0.5;
  double cell = 0;  // px; 0 automatic
};

ReliefSettings read_relief_settings(FilterCall& call) {
  ReliefSettings s;
  s.interpretation = call.params.getOpenFileName("interpretation").trimmed();
  s.ground = read_enum(call, "ground", "Ground level", kGrounds.size());
  s.base = read_enum(call, "base", "Base", kBases.size());
  s.as_drawn = read_enum(call, "placement", "Placement (current layer)", kPlacements.size()) == 1;
  s.relief.margin = read_float(call, "margin", "Step width (px)", 0.5, 1000);
  s.step_percent = read_float(call, "step_height", "Step height (% of the drawing's width)", 1e-6, 1000);
  s.cell = read_float(call, "cell", "Base resolution (px)", 0, 1000);
  s.relief.shading_depth = read_float(call, "shading_depth", "Shading engraved (steps, 0: none)", 0, 100);
  return s;
}

// The interpretation parameters: automatic, with the user's overrides when a file is given.
InterpretationParams interpretation_params(const ReliefSettings& s, const DrawingCurves& curves) {
  InterpretationParams ip;
  ip.margin = std::max(3.0, 0.75 * s.relief.margin);
  ip.paper_is_base = s.ground == 0;
  if (!s.interpretation.isEmpty()) {
    QFile f(s.interpretation);
    if (!f.open(QIODevice::ReadOnly))
      throw InputError(("The interpretation file \"" + s.interpretation + "\" does not exist or cannot be read.").toStdString());
    ip.overrides = overrides_from_json(f.readAll().toStdString(), curves);
  }
  return ip;
}

// The relief with the layers shown beside it.
struct ReliefLayers {
  TriMesh surface;
  DrawingRelief relief;
  std::vector<double> level;  // per vertex: its region's level (-1 on a curve, uncovered)
  Polylines curves;           // the drawing's curves on the relief (structure)
  Polylines shading;          // its shading strokes on the relief
  int base_vertices = 0;
  double spacing_px = 0;      // the base's vertex spacing in the drawing
};

// On the current layer: the drawing projected onto it, the relief along its normals.
ReliefLayers relief_on_layer(FilterCall& call, const Drawing& d, const DrawingInterpretation& di, ReliefSettings& s,
                             const cv::Rect& area) {
  if (call.current == nullptr)
    throw InputError("Base \"Current layer\" needs a mesh layer: open the base mesh first, or choose the Plane or "
                     "Cylinder base.");
  const vcg::Point3f vd = call.params.getPoint3m("view");
  const Vec3 view(vd[0], vd[1], vd[2]);
  if (!std::isfinite(view.norm())) throw InputError("View direction: the numbers must be finite (0 0 0 for automatic).");
  View bv = view_of(call.mesh(), call.log);
  const Surface base = surface_of(bv);
  const DrawingProjection proj = s.as_drawn ? project_drawing_as_drawn(base, area, d.pixel_mm) : project_drawing(base, area, view);
  s.relief.pixel_size = proj.pixel_size;
  s.relief.step_height = relief_step_height(s.step_percent, area, proj.pixel_size);
  if (proj.edge_px > s.relief.margin / 2)
    call.log(QString("The base's edges are %1 px of the drawing, but steps %2 px wide need edges of at most %3 px: the "
                     "relief will be coarse. Subdivide the base first (Filters > Remeshing, Simplification and "
                     "Reconstruction > Subdivision Surfaces: Midpoint) or raise Step width.")
                 .arg(proj.edge_px, 0, 'g', 3)
                 .arg(s.relief.margin, 0, 'g', 3)
                 .arg(s.relief.margin / 2, 0, 'g', 3));
  if (call.progress) call.progress(40, "Reconstructing the relief");
  ReliefLayers out;
  out.relief = reconstruct_drawing_relief(base, d.curves, di, s.relief, &proj.pixel);
  out.surface = displace_along_normals(base, out.relief.height);
  out.level = region_levels(di, proj.pixel);
  out.curves = curves_on_projected_relief(curves_where(d.curves, di.shading, false), proj, out.surface);
  out.shading = curves_on_projected_relief(curves_where(d.curves, di.shading, true), proj, out.surface);
  out.base_vertices = base.n_vertices();
  out.spacing_px = proj.edge_px;
  call.log(QString("Drawing projected along (%1, %2, %3) onto %4 of the layer's %5 vertices, %6 mesh units per pixel.")
               .arg(proj.view.x(), 0, 'f', 3)
               .arg(proj.view.y(), 0, 'f', 3)
               .arg(proj.view.z(), 0, 'f', 3)
               .arg(thousands(proj.covered))
               .arg(thousands(base.n_vertices()))
               .arg(proj.pixel_size, 0, 'g', 4));
  return out;
}

// On a plane or a cylinder: a grid over the drawn part of the image.
ReliefLayers relief_on_grid(FilterCall& call, const Drawing& d, const DrawingInterpretation& di, ReliefSettings& s) {
  ReliefGridParams gp;
  gp.margin = s.relief.margin, gp.cell = s.cell, gp.max_vertices = kMaxAutoVertices, gp.pixel_size = d.pixel_mm;
  const ReliefGrid g = relief_grid(d.curves, di, gp);
  if (g.coarsened())
    call.log(QString("Base resolution: %1 px per vertex would make %2 vertices; %3 px taken (steps less finely "
                     "resolved; set Base resolution to override).")
                 .arg(g.wanted_cell, 0, 'g', 3)
                 .arg(thousands((long long)g.wanted_vertices))
                 .arg(g.cell, 0, 'g', 3));
  s.relief.pixel_size = d.pixel_mm;
  s.relief.step_height = relief_step_height(s.step_percent, g.area, d.pixel_mm);
  if (call.progress) call.progress(40, "Reconstructing the relief");
  const DrawingBase shape = s.base == kCylinder ? DrawingBase::Cylinder : DrawingBase::Plane;
  const double circumference = d.image.cols * d.pixel_mm, front = (g.area.x + 0.5 * g.area.width) * d.pixel_mm;
  ReliefLayers out;
  out.relief = reconstruct_drawing_relief(g.grid, d.curves, di, s.relief);
  out.surface = relief_surface(g.grid, out.relief.height, shape, circumference, front);
  out.level = region_levels(di, g.pixel);
  for (bool shading : {false, true})
    (shading ? out.shading : out.curves) = curves_on_grid_relief(curves_where(d.curves, di.shading, shading), d.pixel_mm,
                                                                 g.area, g.cell, out.relief.height, shape, circumference, front);
  out.base_vertices = g.grid.n_vertices();
  out.spacing_px = g.cell;
  return out;
}

// The interpretation file beside the image (in reliefkit-batch: in the outputs folder), only when
// none was given: the user's file stays as written. Returns its path, "" when it was not written.
QString write_interpretation_file(FilterCall& call, const Drawing& d, const DrawingInterpretation& di) {
  const QFileInfo fi(d.path);
  const QString path = QDir(derived_file_folder(d.path)).filePath(fi.completeBaseName() + ".interpretation.json");
  QFile f(path);
  const std::string text = interpretation_to_json(fi.fileName().toStdString(), d.curves, d.detection, di);
  if (f.open(QIODevice::WriteOnly | QIODevice::Truncate) && f.write(text.data(), qint64(text.size())) == qint64(text.size()))
    return path;
  call.log("The interpretation file could not be written (" + path + "): the folder is not writable.");
  return QString();
}

void apply_relief(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const Drawing d = read_drawing(call);
  ReliefSettings s = read_relief_settings(call);
  const InterpretationParams ip = interpretation_params(s, d.curves);
  if (call.progress) call.progress(30, "Interpreting the drawing");
  const DrawingInterpretation di = interpret_drawing(d.curves, ip);
  require_rising_regions(d.curves, di, d.detection.sigma);
  const ReliefLayers r = s.base == kCurrent ? relief_on_layer(call, d, di, s, relief_area(d.curves, s.relief.margin))
                                             : relief_on_grid(call, d, di, s);
  const QString written = s.interpretation.isEmpty() ? write_interpretation_file(call, d, di) : QString();
  if (call.progress) call.progress(95, "Adding the layers");
  add_mesh_layer(call.doc, image_label(d, "relief"), r.surface, r.relief.height, {{"drawing_level", &r.level}}, true);
  add_curve_layer(call.doc, image_label(d, "curves"), r.curves, vcg::Color4b(200, 30, 30, 255));
  if (di.shading_curves > 0) add_curve_layer(call.doc, image_label(d, "shading"), r.shading, kShadingColour);
  const int top = di.region_height.empty() ? 0 : std::max(0, *std::max_element(di.region_height.begin(), di.region_height.end()));
  call.log(QString("Relief from Line Drawing: %1 curves, %2 regions (%3 curves not between two regions), levels 0 to %4, "
                   "%14 regions rise; %5 curves fixed by the interpretation file; base %6, %7 vertices (%8 px apart), "
                   "step %9 mesh units; solves: %10 | %11; %12 s.%13")
               .arg(d.curves.curves.size())
               .arg(di.region_count)
               .arg(di.ignored_curves)
               .arg(top)
               .arg(ip.overrides.size())
               .arg(kBases[s.base].section(' ', 0, s.base == kCurrent ? 1 : 0))
               .arg(thousands(r.base_vertices))
               .arg(r.spacing_px, 0, 'g', 3)
               .arg(s.relief.step_height, 0, 'g', 3)
               .arg(QString::fromStdString(r.relief.laplacian_solve.summary()))
               .arg(QString::fromStdString(r.relief.relief_solve.summary()))
               .arg(seconds_since(t0), 0, 'f', 2)
               .arg(written.isEmpty() ? QString() : " Interpretation written to " + written + ".")
               .arg(rising_regions(di)));
  call.log(shading_and_outlines(d.curves, di.shading_curves) +
           QString(" Free surface held within half a step of its region's level at %1 vertices.")
               .arg(thousands(r.relief.bounded_vertices)));
  for (const FlatObject& o : flat_objects(d.curves, di))
    call.log(QString("Warning: the drawn object at x %1-%2, y %3-%4 px stays at the paper's level over %5 % of its inside: "
                     "its outline is open to the paper where no line was found (or it has an opening). Look at the "
                     "curves layer; raise Outline gaps closed, or give the gap's curves a direction in the "
                     "interpretation file.")
                 .arg(o.box.x)
                 .arg(o.box.x + o.box.width)
                 .arg(o.box.y)
                 .arg(o.box.y + o.box.height)
                 .arg(std::lround(100 * o.flat_share)));
}

}  // namespace

FilterSpec drawing_curves_filter(int id) {
  FilterSpec s{id,
               "Line Drawing to Curves",
               QString(kCurvesInfo) + kCitation,
               ml::FilterInterface::MeshCreation,
               MeshModel::MM_NONE,
               MeshModel::MM_NONE,
               curves_parameters,
               apply_curves,
               true};
  s.needs_mesh = false;
  return s;
}

FilterSpec drawing_relief_filter(int id) {
  FilterSpec s{id,
               "Relief from Line Drawing",
               QString(kReliefInfo) + kCitation,
               ml::FilterInterface::MeshCreation,
               MeshModel::MM_NONE,
               MeshModel::MM_NONE,
               relief_parameters,
               apply_relief,
               true};
  s.needs_mesh = false;
  return s;
}

}  // namespace reliefkit::ml
