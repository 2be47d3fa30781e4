#include "drawing_filters.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <chrono>
#include <cmath>
#include <unordered_map>

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
    "corner are joined, strokes shorter than <i>Shortest stroke</i> (stippling, hatching, shading) are "
    "dropped. ";

const char* kReliefInfo =
    "Builds a <b>3-D relief from a line drawing</b>: which side of each line is higher is decided "
    "automatically (the paper around the object is the ground, and shapes drawn inside others rise from them, "
    "one step per line), then a smooth surface is made that steps up or down across every line and is smooth "
    "between them.<br><br>"
    "<b>Output</b>: a new layer <i>&lt;image&gt; – relief</i> (made current) on a plane, on a cylinder whose "
    "circumference is the drawing's width (a roll-out drawing of a cup or a lamp), or on the current layer (the "
    "drawing projected onto it), with vertex quality = the height over the base and the per-vertex attribute <code>drawing_level</code> (the level "
    "each part was given); a layer <i>&lt;image&gt; – curves</i> with the lines on the relief; and, beside the "
    "image, the <b>interpretation file</b> <i>&lt;image&gt;.interpretation.json</i>: every curve with its id, ends, "
    "sides and step. To change the result, edit a curve's <code>direction</code> (auto, left-lower, "
    "right-lower), <code>weight</code> (levels of its step, or a ridge's height) or <code>profile</code> (step, "
    "ridge, valley) in a copy of that file and give it as <i>Interpretation file</i>.<br><br>"
    "Method: thesis sect. 7.3 (the regions between the lines form a graph; it is directed from the ground "
    "up and levelled by topological order) and 7.4 (a smoothed step of width <i>Step width</i> across each "
    "line; the Laplacian of the relief is interpolated smoothly between the lines, eq. 7.4, then the relief, "
    "eq. 7.6). ";

const QStringList kImageExts = {"*.png", "*.jpg", "*.jpeg", "*.tif", "*.tiff", "*.bmp"};
const QStringList kBases = {"Plane", "Cylinder (the drawing's width goes round it)",
                             "Current layer (the drawing projected onto it)"};
enum BaseChoice { kPlane, kCylinder, kCurrent };
const QStringList kGrounds = {"The paper around the drawing", "The most connected region (the thesis' heuristic)"};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ---- Shared: the drawing and its curves ----

void drawing_parameters(RichParameterList& par) {
  par.addParam(RichOpenFile("drawing", "", kImageExts, "Drawing image",
                            "The scanned line drawing: dark lines on light paper (PNG, JPEG, TIFF, BMP; grey, colour "
                            "or RGBA with a transparent background)."));
  par.addParam(RichFloat("sigma", 2.f, "Line scale (px)",
                         "Standard deviation of the Gaussian that smooths the image before lines are found (thesis: "
                         "2 px). About the lines' half-width: 2 suits drawings scanned at 300 dpi; take 1 for thin "
                         "lines in small images, more for thick pen lines."));
  par.addParam(RichFloat("min_length", 12.f, "Shortest stroke (px)",
                         "Strokes shorter than this are taken for shading (stippling, hatching) and dropped."));
  par.addParam(RichFloat("dpi", 300.f, "Drawing resolution (DPI)",
                         "Dots per inch of the scan: with the scale it sets the size of a pixel on the object, "
                         "25.4 / DPI x scale millimetres."));
  par.addParam(RichFloat("scale", 1.f, "Drawing scale (object : drawing)",
                         "How many times larger the object is than its drawing (2 for a figure drawn at 1:2)."));
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
  d.path = call.params.getOpenFileName("drawing");
  d.detection.sigma = read_float(call, "sigma", "Line scale (px)", 0.5, 50);
  d.detection.min_length = read_float(call, "min_length", "Shortest stroke (px)", 0, 1e6);
  const double dpi = read_float(call, "dpi", "Drawing resolution (DPI)", 1, 100000);
  const double scale = read_float(call, "scale", "Drawing scale (object : drawing)", 1e-6, 1e6);
  if (d.path.trimmed().isEmpty()) throw InputError("No drawing image was given: choose the image file in \"Drawing image\".");
  double reduction = 1;
  if (call.progress) call.progress(2, "Reading the drawing");
  d.image = read_drawing_image(d.path.toStdString(), &reduction);
  d.pixel_mm = 25.4 / dpi * scale / reduction;
  if (reduction < 1)
    call.log(QString("The drawing has more than %1 million pixels: read reduced by %2 (pixel size %3 mm).")
                 .arg(kMaxDrawingPixels / 1e6, 0, 'f', 0)
                 .arg(reduction, 0, 'f', 3)
                 .arg(d.pixel_mm, 0, 'g', 4));
  if (call.progress) call.progress(10, "Finding the lines");
  d.curves = extract_drawing_curves(d.image, d.detection);
  if (d.curves.curves.empty())
    throw InputError(QString("No lines were found in \"%1\" (%2 x %3 px): the image is blank, or its lines are lighter or "
                             "shorter than the line detection takes (Line scale %4 px, Shortest stroke %5 px).")
                         .arg(QFileInfo(d.path).fileName())
                         .arg(d.image.cols)
                         .arg(d.image.rows)
                         .arg(d.detection.sigma)
                         .arg(d.detection.min_length)
                         .toStdString());
  return d;
}

// The curves as an edge layer in the plane of the drawing (or on `surface`), quality = curve id.
Polylines curves_in_mesh_units(const DrawingCurves& dc, double pixel_mm) {
  Polylines pl;
  for (size_t k = 0; k < dc.curves.size(); ++k) {
    const int first = int(pl.points.size());
    for (const auto& q : dc.curves[k]) {
      pl.points.push_back(Vec3(q.x() * pixel_mm, -q.y() * pixel_mm, 0));
      pl.strength.push_back(double(k));
    }
    for (int i = first; i + 1 < int(pl.points.size()); ++i) pl.segments.push_back({i, i + 1});
  }
  return pl;
}

QString image_label(const Drawing& d, const char* what) { return QFileInfo(d.path).completeBaseName() + QString::fromUtf8(" – ") + what; }

// ---- Line Drawing to Curves ----

void curves_parameters(MeshModel&, RichParameterList& par) {
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
  add_curve_layer(call.doc, label, curves_in_mesh_units(d.curves, d.pixel_mm), vcg::Color4b(20, 20, 20, 255));
  if (margins > 0) {
    DrawingCurves m;
    m.curves = margin_lines(d.curves, margins);
    add_curve_layer(call.doc, image_label(d, "margins"), curves_in_mesh_units(m, d.pixel_mm), vcg::Color4b(40, 90, 220, 255));
  }
  call.log(QString("Line Drawing to Curves: \"%1\" %2 x %3 px; %4 curves (%5 px of lines, %6 junctions), %7 short strokes "
                   "dropped; layer \"%8\", pixel %9 mm; %10 s.")
               .arg(QFileInfo(d.path).fileName())
               .arg(d.image.cols)
               .arg(d.image.rows)
               .arg(d.curves.curves.size())
               .arg(thousands((long long)std::lround(d.curves.total_length())))
               .arg(d.curves.junctions.size())
               .arg(d.curves.dropped_short)
               .arg(label)
               .arg(d.pixel_mm, 0, 'g', 4)
               .arg(seconds_since(t0), 0, 'f', 2));
}

// ---- Relief from Line Drawing ----

void relief_parameters(MeshModel&, RichParameterList& par) {
  drawing_parameters(par);
  par.addParam(RichOpenFile("interpretation", "", QStringList{"*.json"}, "Interpretation file",
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
  par.addParam(RichPoint3f("view", vcg::Point3f(0, 0, 0), "View direction (current layer)",
                           "Direction in which the drawing is projected onto the current layer (towards it). 0 0 0: "
                           "automatic, along the layer's axis of least extent (the normal of a plaque)."));
  par.addParam(RichFloat("margin", 4.f, "Step width (px)",
                         "Half-width of the smoothed step across each line, in pixels of the drawing. Closely drawn "
                         "lines need a small width; wide ones give softer steps."));
  par.addParam(RichFloat("step_height", 0.5f, "Step height (% of the drawing's width)",
                         "Height of one level, as a percentage of the width of the drawn part of the image, so the "
                         "same script suits any DPI and scale."));
  par.addParam(RichFloat("cell", 0.f, "Base resolution (px)",
                         "Spacing of the base's vertices in pixels of the drawing. 0: automatic: half the step width "
                         "(each step over four vertices) or a quarter of the narrowest region between curves, if "
                         "finer; coarser only when the base would exceed 4 million vertices."));
}

constexpr long kMaxAutoVertices = 4000000;

void apply_relief(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  Drawing d = read_drawing(call);
  const QString interp_path = call.params.getOpenFileName("interpretation").trimmed();
  const int ground = read_enum(call, "ground", "Ground level", kGrounds.size());
  const int base = read_enum(call, "base", "Base", kBases.size());
  DrawingReliefParams rp;
  rp.margin = read_float(call, "margin", "Step width (px)", 0.5, 1000);
  const double step_pct = read_float(call, "step_height", "Step height (% of the drawing's width)", 1e-6, 1000);
  double cell = read_float(call, "cell", "Base resolution (px)", 0, 1000);

  // Interpretation: automatic, with the user's overrides when a file is given.
  InterpretationParams ip;
  ip.margin = std::max(3.0, 0.75 * rp.margin);
  ip.paper_is_base = ground == 0;
  if (!interp_path.isEmpty()) {
    QFile f(interp_path);
    if (!f.open(QIODevice::ReadOnly))
      throw InputError(("The interpretation file \"" + interp_path + "\" does not exist or cannot be read.").toStdString());
    const QByteArray text = f.readAll();
    ip.overrides = overrides_from_json(text.toStdString(), d.curves);
  }
  if (call.progress) call.progress(30, "Interpreting the drawing");
  const DrawingInterpretation di = interpret_drawing(d.curves, ip);
  int top = 0;
  for (int h : di.region_height) top = std::max(top, h);

  // The base: a grid over the drawn part of the image (plane, cylinder), or the current layer.
  const cv::Rect area = drawing_extent(d.curves, 4 * rp.margin + 4);
  const int base_choice = int(base);
  TriMesh grid, surface;
  DrawingRelief r;
  std::vector<double> level;
  DrawingProjection proj;
  // The level of the region at a drawing pixel (-1 on a curve or outside the image).
  auto level_at = [&](const Vec2& q) {
    const int x = int(std::lround(q.x())), y = int(std::lround(q.y()));
    const int reg = (x >= 0 && y >= 0 && x < di.regions.cols && y < di.regions.rows) ? di.regions.at<int>(y, x) : -1;
    return reg >= 0 ? double(di.region_height[size_t(reg)]) : -1.0;
  };
  const double circumference = d.image.cols * d.pixel_mm, front = (area.x + 0.5 * area.width) * d.pixel_mm;
  if (base_choice == kCurrent) {
    if (call.current == nullptr)
      throw InputError("Base \"Current layer\" needs a mesh layer: open the base mesh first, or choose the Plane or "
                       "Cylinder base.");
    const vcg::Point3f vd = call.params.getPoint3m("view");
    const Vec3 view(vd[0], vd[1], vd[2]);
    if (!std::isfinite(view.norm())) throw InputError("View direction: the numbers must be finite (0 0 0 for automatic).");
    View bv = view_of(call.mesh(), call.log);
    proj = project_drawing(bv.mesh, area, view);
    rp.pixel_size = proj.pixel_size;
    rp.step_height = step_pct / 100 * area.width * proj.pixel_size;
    if (proj.edge_px > rp.margin / 2)
      call.log(QString("The base's edges are %1 px of the drawing, but steps %2 px wide need edges of at most %3 px: the "
                       "relief will be coarse. Subdivide the base first (Filters > Remeshing, Simplification and "
                       "Reconstruction > Subdivision Surfaces: Midpoint) or raise Step width.")
                   .arg(proj.edge_px, 0, 'g', 3)
                   .arg(rp.margin, 0, 'g', 3)
                   .arg(rp.margin / 2, 0, 'g', 3));
    if (call.progress) call.progress(40, "Reconstructing the relief");
    r = reconstruct_drawing_relief(bv.mesh, d.curves, di, rp, &proj.pixel);
    surface = displace_along_normals(bv.mesh, r.height);
    grid = bv.mesh;
    level.assign(size_t(grid.n_vertices()), -1);
    for (int v = 0; v < grid.n_vertices(); ++v)
      if (std::isfinite(proj.pixel[size_t(v)].x())) level[size_t(v)] = level_at(proj.pixel[size_t(v)]);
    call.log(QString("Drawing projected along (%1, %2, %3) onto %4 of the layer's %5 vertices, %6 mesh units per pixel.")
                 .arg(proj.view.x(), 0, 'f', 3)
                 .arg(proj.view.y(), 0, 'f', 3)
                 .arg(proj.view.z(), 0, 'f', 3)
                 .arg(thousands(proj.covered))
                 .arg(thousands(grid.n_vertices()))
                 .arg(proj.pixel_size, 0, 'g', 4));
  } else {
    if (cell <= 0) {
      cell = drawing_cell(di, rp.margin);
      const double verts = (area.width / cell + 1) * (area.height / cell + 1);
      if (verts > kMaxAutoVertices) {
        const double c2 = std::sqrt(double(area.width) * area.height / kMaxAutoVertices);
        call.log(QString("Base resolution: %1 px per vertex would make %2 vertices; %3 px taken (steps less finely "
                         "resolved; set Base resolution to override).")
                     .arg(cell, 0, 'g', 3)
                     .arg(thousands((long long)verts))
                     .arg(c2, 0, 'g', 3));
        cell = c2;
      }
    }
    rp.pixel_size = d.pixel_mm;
    rp.step_height = step_pct / 100 * area.width * d.pixel_mm;
    if (call.progress) call.progress(40, "Reconstructing the relief");
    grid = drawing_grid(area.width, area.height, cell, d.pixel_mm, area.x, area.y);
    r = reconstruct_drawing_relief(grid, d.curves, di, rp);
    surface = relief_surface(grid, r.height, base_choice == kCylinder ? DrawingBase::Cylinder : DrawingBase::Plane, circumference, front);
    level.assign(size_t(grid.n_vertices()), 0);
    for (int v = 0; v < grid.n_vertices(); ++v)
      level[size_t(v)] = level_at(Vec2(grid.vertices[v].x() / d.pixel_mm, -grid.vertices[v].y() / d.pixel_mm));
  }

  // The interpretation file beside the image (only when none was given: the user's file stays as written).
  QString written;
  if (interp_path.isEmpty()) {
    const QFileInfo fi(d.path);
    written = fi.absoluteDir().filePath(fi.completeBaseName() + ".interpretation.json");
    QFile f(written);
    const std::string text = interpretation_to_json(fi.fileName().toStdString(), d.curves, d.detection, di);
    if (f.open(QIODevice::WriteOnly | QIODevice::Truncate) && f.write(text.data(), qint64(text.size())) == qint64(text.size())) {
      f.close();
    } else {
      call.log("The interpretation file could not be written beside the drawing (" + written + "): the folder is not writable.");
      written.clear();
    }
  }

  if (call.progress) call.progress(95, "Adding the layers");
  // The curves on the relief.
  Polylines pl = curves_in_mesh_units(d.curves, d.pixel_mm);
  if (base_choice == kCurrent) {
    // Each curve point at the covered vertex nearest to it in the drawing, moved within the image
    // plane by the remaining offset (a grid of the covered vertices' pixel positions).
    const double cellpx = std::max(1.0, 2 * proj.edge_px);
    std::unordered_map<long long, std::vector<int>> bins;
    auto key = [&](double x, double y) { return (long long)std::floor(x / cellpx) * 1000003LL + (long long)std::floor(y / cellpx); };
    for (int v = 0; v < grid.n_vertices(); ++v)
      if (std::isfinite(proj.pixel[size_t(v)].x())) bins[key(proj.pixel[size_t(v)].x(), proj.pixel[size_t(v)].y())].push_back(v);
    std::vector<char> keep(pl.points.size(), 1);
    size_t i = 0;
    for (const auto& c : d.curves.curves)
      for (const auto& q : c) {
        int best = -1;
        double bd = 1e300;
        for (int ox = -1; ox <= 1; ++ox)
          for (int oy = -1; oy <= 1; ++oy) {
            auto it = bins.find(key(q.x() + ox * cellpx, q.y() + oy * cellpx));
            if (it == bins.end()) continue;
            for (int v : it->second) {
              const double dd = (proj.pixel[size_t(v)] - q).squaredNorm();
              if (dd < bd) bd = dd, best = v;
            }
          }
        if (best < 0) {
          keep[i] = 0;
          pl.points[i++] = Vec3::Zero();
          continue;
        }
        const Vec2 off = q - proj.pixel[size_t(best)];
        pl.points[i++] = surface.vertices[best] + proj.pixel_size * (off.x() * proj.right - off.y() * proj.up);
      }
    std::vector<std::array<int, 2>> segs;
    for (const auto& sgm : pl.segments)
      if (keep[size_t(sgm[0])] && keep[size_t(sgm[1])]) segs.push_back(sgm);
    pl.segments = segs;
  } else {
    // Each curve point at the height of the surface below it (bilinear in the grid).
    const int nx = int(std::ceil((area.width - 1) / cell)) + 1, ny = int(std::ceil((area.height - 1) / cell)) + 1;
    std::vector<double> hgt(pl.points.size(), 0);
    for (size_t i = 0; i < pl.points.size(); ++i) {
      const double gx = std::clamp((pl.points[i].x() / d.pixel_mm - area.x) / cell, 0.0, nx - 1.0);
      const double gy = std::clamp((-pl.points[i].y() / d.pixel_mm - area.y) / cell, 0.0, ny - 1.0);
      const int i0 = std::min(nx - 2, int(gx)), j0 = std::min(ny - 2, int(gy));
      const double fx = gx - i0, fy = gy - j0;
      auto H = [&](int a, int b) { return r.height[size_t(b * nx + a)]; };
      hgt[i] = (1 - fy) * ((1 - fx) * H(i0, j0) + fx * H(i0 + 1, j0)) + fy * ((1 - fx) * H(i0, j0 + 1) + fx * H(i0 + 1, j0 + 1));
    }
    TriMesh pts;
    pts.vertices = pl.points;
    pl.points = relief_surface(pts, hgt, base_choice == kCylinder ? DrawingBase::Cylinder : DrawingBase::Plane, circumference, front).vertices;
  }
  const QString relief_label = image_label(d, "relief");
  add_mesh_layer(call.doc, relief_label, surface, r.height, {{"drawing_level", &level}}, true);
  add_curve_layer(call.doc, image_label(d, "curves"), pl, vcg::Color4b(200, 30, 30, 255));
  call.log(QString("Relief from Line Drawing: %1 curves, %2 regions (%3 curves not between two regions), levels 0 to %4, "
                   "%5 curves fixed by the interpretation file; base %6, %7 vertices (%8 px apart), step %9 mesh units; "
                   "solves: %10 | %11; %12 s.%13")
               .arg(d.curves.curves.size())
               .arg(di.region_count)
               .arg(di.ignored_curves)
               .arg(top)
               .arg(ip.overrides.size())
               .arg(kBases[base_choice].section(' ', 0, base_choice == kCurrent ? 1 : 0))
               .arg(thousands(grid.n_vertices()))
               .arg(base_choice == kCurrent ? proj.edge_px : cell, 0, 'g', 3)
               .arg(rp.step_height, 0, 'g', 3)
               .arg(QString::fromStdString(r.laplacian_solve.summary()))
               .arg(QString::fromStdString(r.relief_solve.summary()))
               .arg(seconds_since(t0), 0, 'f', 2)
               .arg(written.isEmpty() ? QString() : " Interpretation written to " + written + "."));
}

}  // namespace

FilterSpec drawing_curves_filter(int id) {
  FilterSpec s{id,
               "Line Drawing to Curves",
               QString(kCurvesInfo) + kCitation,
               MeshFilterInterface::MeshCreation,
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
               MeshFilterInterface::MeshCreation,
               MeshModel::MM_NONE,
               MeshModel::MM_NONE,
               relief_parameters,
               apply_relief,
               true};
  s.needs_mesh = false;
  return s;
}

}  // namespace reliefkit::ml
