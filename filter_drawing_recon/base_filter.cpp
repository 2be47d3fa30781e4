// "Base from Drawing Silhouette": MeshLab adapter of reliefkit/drawing/base_library.h (thesis sect. 7.5).
#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "drawing_filters.h"
#include "mesh_bridge.h"
#include "params.h"
#include "reliefkit/drawing/base_library.h"
#include "reliefkit/drawing/line_drawing.h"

namespace reliefkit::ml {
namespace {

const char* kBaseInfo =
    "Makes the <b>base</b> of a drawn object — the smooth body of a lamp, a bowl, a jug that its relief sits "
    "on — from the <b>outlines of its drawing</b>: the most similar model of a library is found and deformed "
    "until its silhouettes match the drawing's. Use the new layer as the base of <i>Relief from Line Drawing</i> "
    "(<i>Base</i>: current layer).<br><br>"
    "<b>Input</b>: the drawing image and which views it shows, in <i>Views</i>: <code>front</code> (the "
    "default: the largest outline of the image is the front view), <code>front; top</code> (the two largest "
    "outlines, in reading order), or regions in pixels <code>front = x y w h; top = x y w h</code>; a view can "
    "also be its own image: <code>side = lamp_side.png</code>. The library: ReliefKit's own models (lamps, "
    "bowls, cups, kraters, jugs, amphorae, plates, cylinders, spheres) and any folder of your models (PLY, OBJ, "
    "STL, OFF; sub-folder names are their classes).<br><br>"
    "<b>Output</b>: a new layer <i>&lt;image&gt; – base (&lt;model&gt;)</i> (made current), in millimetres "
    "(<i>DPI</i>, <i>scale</i>), vertex quality = how far each vertex moved; and the retrieved model as it was "
    "before the deformation, <i>&lt;model&gt; – retrieved</i>, for comparison. The log lists the best matches with "
    "their scores and how close the silhouettes came.<br><br>"
    "Method (thesis sect. 7.5): the outline of each view (gaps in the line bridged, text beside it ignored); "
    "its circle-distance feature (distances from the outline to its enclosing circle in 64 directions) "
    "compared with the library's (models normalised to their principal axes, every way of facing the views "
    "tried); the best model's silhouette vertices pulled onto the drawing's outlines, depth kept, while its "
    "Laplacian coordinates are preserved (eq. 7.8) — one sparse Cholesky solve per pass, passes repeated while "
    "the fit improves (1 pass: the thesis). ";

const char* kBaseCitation =
    "M. Kolomenkin, G. Leifman, I. Shimshoni, A. Tal, <b>\"Reconstruction of relief objects from line "
    "drawings\"</b>, CVPR 2011; thesis chapter 7, section 7.5.";

const QStringList kImageExts = {"*.png", "*.jpg", "*.jpeg", "*.tif", "*.tiff", "*.bmp"};

// The library the build made, in the private prefix (or an installed tree): <bin>/../share/reliefkit/bases.
QString shipped_library() {
  const QString dir = QDir::cleanPath(QCoreApplication::applicationDirPath() + "/../share/reliefkit/bases");
  return QFileInfo(dir).isDir() ? dir : QString();
}

void base_parameters(MeshModel&, RichParameterList& par) {
  par.addParam(RichOpenFile("drawing", "", kImageExts, "Drawing image",
                            "The drawing of the object: dark lines on light paper (PNG, JPEG, TIFF, BMP)."));
  par.addParam(RichString("views", "front", "Views",
                          "Which views the image shows: \"front\" (the largest outline is the front view); \"front; "
                          "top\" (the two largest outlines in reading order: top to bottom, then left to right); "
                          "\"front = x y w h; side = x y w h\" (regions in pixels); \"top = other_image.png\" (a view "
                          "in its own image, beside the drawing). Views: front (x right, y up), side (seen from the "
                          "right), top (seen from above, front at the bottom)."));
  par.addParam(RichFloat("dpi", 300.f, "Drawing resolution (DPI)",
                         "Dots per inch of the scan: with the scale it sets the base's size, 25.4 / DPI x scale "
                         "millimetres per pixel."));
  par.addParam(RichFloat("scale", 1.f, "Drawing scale (object : drawing)",
                         "How many times larger the object is than its drawing (2 for a figure drawn at 1:2)."));
  const QString shipped = shipped_library();
  par.addParam(RichString("library", "", "Model library folder",
                          "Empty: ReliefKit's own library of base models (" +
                              (shipped.isEmpty() ? QString("not found beside this MeshLab") : shipped) +
                              "), so that scripts work on any machine. A folder: that library instead. \"none\": no "
                              "library, only your models."));
  par.addParam(RichString("user_models", "", "Your models folder",
                          "A folder of your own models (PLY, OBJ, STL, OFF; sub-folders are classes), searched with the "
                          "library. Their silhouette features are cached in the folder on the first search."));
  par.addParam(RichString("model", "", "Use model",
                          "The name of a library model to deform instead of the best match (e.g. cylinder_05, as the "
                          "log lists them); empty: the best match."));
  par.addParam(RichBool("round", false, "One view: a round object",
                        "With a front (or side) view alone, take the object as round: its outline is used as the "
                        "side (front) view too, so that a stem drawn narrow is narrow all round. Good when the model "
                        "is close to the drawing; a drastic change (a cylinder made a goblet) folds the mesh. Off: the "
                        "depth stays the model's (the thesis). Not used with two or more views."));
  par.addParam(RichFloat("alpha", 1.f, "Shape weight (alpha)",
                         "How strongly the model keeps its shape (its Laplacian coordinates) against fitting the "
                         "outlines (thesis eq. 7.8: 1). Smaller fits the outlines more closely, larger keeps more of "
                         "the model's detail."));
  par.addParam(RichInt("passes", 10, "Passes (most)",
                       "Times the model's silhouette is found, matched to the drawing and solved (the thesis: 1). "
                       "After a large change the silhouette moves onto other vertices; more passes follow it."));
  par.addParam(RichFloat("gap", 0.f, "Outline gap (px, 0: auto)",
                         "Widest gap in the drawing's outer line that is bridged (automatic: 1.5 % of the view's "
                         "diagonal). Raise it when the outline is not found because its line is broken."));
  par.addParam(RichInt("matches", 5, "Matches listed", "How many of the best library models the log lists."));
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Reading order of outlines: top to bottom, and left to right for outlines side by side.
bool reads_before(const DrawingOutline& a, const DrawingOutline& b) {
  const int overlap = std::min(a.box.y + a.box.height, b.box.y + b.box.height) - std::max(a.box.y, b.box.y);
  if (overlap > 0.5 * std::min(a.box.height, b.box.height)) return a.box.x < b.box.x;
  return a.box.y < b.box.y;
}

void apply_base(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const QString path = call.params.getOpenFileName("drawing");
  const double dpi = read_float(call, "dpi", "Drawing resolution (DPI)", 1, 100000);
  const double scale = read_float(call, "scale", "Drawing scale (object : drawing)", 1e-6, 1e6);
  const double alpha = read_float(call, "alpha", "Shape weight (alpha)", 1e-4, 1e4);
  const int passes = read_int(call, "passes", "Passes", 1, 20);
  const double gap = read_float(call, "gap", "Outline gap (px, 0: auto)", 0, 10000);
  const int listed = read_int(call, "matches", "Matches listed", 1, 100);
  const bool round = read_bool(call, "round", "One view: a round object");
  QString library_dir = call.params.getString("library").trimmed();
  if (library_dir.isEmpty()) {
    library_dir = shipped_library();
    if (library_dir.isEmpty())
      throw InputError("ReliefKit's library of base models is not beside this MeshLab (share/reliefkit/bases next to its "
                       "bin folder): give its folder in \"Model library folder\" (build/bases in a build tree).");
  } else if (library_dir.compare("none", Qt::CaseInsensitive) == 0) {
    library_dir.clear();
  }
  const QString user_dir = call.params.getString("user_models").trimmed();
  const QString wanted = call.params.getString("model").trimmed();
  if (path.trimmed().isEmpty()) throw InputError("No drawing image was given: choose the image file in \"Drawing image\".");
  const auto views = parse_drawing_views(call.params.getString("views").toStdString());
  if (call.progress) call.progress(2, "Reading the drawing");

  // ---- outlines of the views, in millimetres (view coordinates: x right, y up) ----
  OutlineParams op;
  op.gap = gap;
  struct Image { QString path; cv::Mat grey; double pixel_mm; };
  std::vector<Image> images;
  auto image_of = [&](const QString& p) -> const Image& {
    for (const auto& im : images)
      if (im.path == p) return im;
    double reduction = 1;
    const cv::Mat img = read_drawing_image(p.toStdString(), &reduction);
    images.push_back({p, drawing_grey(img), 25.4 / dpi * scale / reduction});
    return images.back();
  };
  image_of(path);
  const QDir drawing_dir = QFileInfo(path).absoluteDir();
  std::vector<ViewOutline> outlines(views.size());
  std::vector<DrawingOutline> found(views.size());
  std::vector<double> pixel(views.size());
  std::vector<cv::Rect> frame(views.size());  // the image (or region) each view's outline was found in
  // Views without a region that share the drawing's image take its largest outlines in reading order.
  std::vector<size_t> shared;
  for (size_t i = 0; i < views.size(); ++i)
    if (views[i].image.empty() && views[i].region.area() == 0) shared.push_back(i);
  if (!shared.empty()) {
    const Image& im = image_of(path);
    auto all = drawing_outlines(im.grey, cv::Rect(), int(shared.size()), op);
    if (all.size() < shared.size())
      throw InputError("The views \"" + call.params.getString("views").toStdString() + "\" need " +
                       std::to_string(shared.size()) + " separate outlines, but the drawing has " +
                       std::to_string(all.size()) + ": give each view's region (front = x y w h; ...).");
    std::sort(all.begin(), all.end(), reads_before);
    for (size_t k = 0; k < shared.size(); ++k) {
      found[shared[k]] = all[k];
      pixel[shared[k]] = im.pixel_mm;
      frame[shared[k]] = cv::Rect(0, 0, im.grey.cols, im.grey.rows);
    }
  }
  for (size_t i = 0; i < views.size(); ++i) {
    if (views[i].image.empty() && views[i].region.area() == 0) continue;
    QString p = path;
    if (!views[i].image.empty()) {
      p = QString::fromStdString(views[i].image);
      if (QFileInfo(p).isRelative()) p = drawing_dir.filePath(p);
    }
    const Image& im = image_of(p);
    found[i] = drawing_outlines(im.grey, views[i].region, 1, op).front();
    pixel[i] = im.pixel_mm;
    const cv::Rect whole(0, 0, im.grey.cols, im.grey.rows);
    frame[i] = views[i].region.area() > 0 ? (views[i].region & whole) : whole;
  }
  std::vector<ViewFeature> features;
  for (size_t i = 0; i < views.size(); ++i) {
    outlines[i].kind = views[i].kind;
    for (const auto& q : found[i].outline) outlines[i].outline.push_back(Vec2(q.x() * pixel[i], -q.y() * pixel[i]));
    features.push_back({views[i].kind, circle_feature(outlines[i].outline)});
    call.log(QString("%1 view: outline of %2 x %3 px at (%4, %5), %6 mm x %7 mm; gaps up to %8 px bridged, %9 other marks "
                     "left out.")
                 .arg(QString(view_name(views[i].kind)).replace(0, 1, QString(view_name(views[i].kind)).at(0).toUpper()))
                 .arg(found[i].box.width)
                 .arg(found[i].box.height)
                 .arg(found[i].box.x)
                 .arg(found[i].box.y)
                 .arg(found[i].box.width * pixel[i], 0, 'f', 1)
                 .arg(found[i].box.height * pixel[i], 0, 'f', 1)
                 .arg(found[i].gap, 0, 'f', 0)
                 .arg(found[i].dropped));
    // Within 1 % of the image's size (at least 3 px) of its border: the outline may be cut there.
    const cv::Rect& b = found[i].box;
    const int near = std::max(3, int(0.01 * std::max(frame[i].width, frame[i].height)));
    if (b.x - frame[i].x <= near || b.y - frame[i].y <= near || frame[i].x + frame[i].width - (b.x + b.width) <= near ||
        frame[i].y + frame[i].height - (b.y + b.height) <= near)
      call.log(QString("Warning: the %1 view's outline touches the border of its image: the drawing may be cut there, "
                       "or its lines run into the border (check the outline; give the view's region).")
                   .arg(view_name(views[i].kind)));
  }

  // ---- the library and the search ----
  if (call.progress) call.progress(10, "Reading the model library");
  BaseLibrary library;
  if (!library_dir.isEmpty()) add_library_folder(library, library_dir.toStdString());
  if (!user_dir.isEmpty()) add_library_folder(library, user_dir.toStdString());
  for (const auto& n : library.notes) call.log(QString::fromStdString(n));
  if (!library_dir.isEmpty()) call.log("Model library: " + library_dir + (user_dir.isEmpty() ? QString() : " and " + user_dir));
  if (library.models.empty())
    throw InputError("The model library is empty: \"Model library folder\"" +
                     (library_dir.isEmpty() ? std::string(" is \"none\"") : " (" + library_dir.toStdString() + ")") +
                     " and \"Your models folder\"" +
                     (user_dir.isEmpty() ? std::string(" is not set") : " (" + user_dir.toStdString() + ")") +
                     " hold no readable PLY, OBJ, STL or OFF model.");
  const auto t_search = std::chrono::steady_clock::now();
  const auto ranked = retrieve_bases(library, features, int(library.models.size()));
  const double search_s = seconds_since(t_search);
  QString list;
  for (int k = 0; k < std::min<int>(listed, int(ranked.size())); ++k)
    list += QString("%1%2. %3 (%4) %5").arg(k ? "; " : "").arg(k + 1)
                .arg(QString::fromStdString(library.models[size_t(ranked[size_t(k)].model)].name))
                .arg(QString::fromStdString(library.models[size_t(ranked[size_t(k)].model)].kind))
                .arg(ranked[size_t(k)].score, 0, 'f', 4);
  call.log(QString("Best matches of %1 models (feature distance, 0 = same silhouette; %2 s): %3.")
               .arg(library.models.size())
               .arg(search_s, 0, 'f', 3)
               .arg(list));
  BaseMatch chosen = ranked.front();
  if (!wanted.isEmpty()) {
    auto it = std::find_if(ranked.begin(), ranked.end(), [&](const BaseMatch& m) {
      return QString::fromStdString(library.models[size_t(m.model)].name).compare(wanted, Qt::CaseInsensitive) == 0;
    });
    if (it == ranked.end())
      throw InputError("\"Use model\": no model named \"" + wanted.toStdString() + "\" in the library (names as the log lists them, e.g. " +
                       library.models[size_t(ranked.front().model)].name + ").");
    chosen = *it;
  }
  const LibraryModel& lm = library.models[size_t(chosen.model)];

  // ---- the model, placed on the outlines and deformed ----
  if (call.progress) call.progress(20, "Placing the model");
  std::vector<ViewOutline> fit = outlines;
  if (round && views.size() == 1 && views[0].kind != ViewKind::Top) {
    fit.push_back({views[0].kind == ViewKind::Front ? ViewKind::Side : ViewKind::Front, outlines[0].outline});
    call.log(QString("One %1 view: the object is taken as round (the same outline as its %2 view; \"One view: a round "
                     "object\" off keeps the model's depth).")
                 .arg(view_name(views[0].kind))
                 .arg(view_name(fit.back().kind)));
  }
  TriMesh model = place_on_outlines(oriented(normalize_to_principal_axes(read_model_file(lm.path)), chosen.orientation), fit);
  DeformParams dp;
  dp.alpha = alpha;
  dp.passes = passes;
  dp.progress = call.progress;
  DeformReport rep;
  const TriMesh base = deform_to_outlines(model, fit, dp, &rep);
  constexpr double kPoorFit = 0.05;  // the tests' worst deliberate case (a cylinder made a goblet) stays under it
  if (rep.hausdorff_after > kPoorFit)
    call.log(QString("Warning: the base stays %1 % of the outline's size off the drawing (more than %2 %): the model "
                     "could not be bent to this outline. Try another match (Use model), a second view, or check the "
                     "outline (a drawing cut by the image's border, text run into it).")
                 .arg(100 * rep.hausdorff_after, 0, 'f', 1)
                 .arg(100 * kPoorFit, 0, 'f', 0));
  std::vector<double> moved(size_t(base.n_vertices()));
  for (int i = 0; i < base.n_vertices(); ++i) moved[size_t(i)] = (base.vertices[size_t(i)] - model.vertices[size_t(i)]).norm();

  const QString name = QString::fromStdString(lm.name);
  add_mesh_layer(call.doc, name + QString::fromUtf8(" – retrieved"), model, std::vector<double>(size_t(model.n_vertices()), 0), {},
                 false);
  add_mesh_layer(call.doc, QFileInfo(path).completeBaseName() + QString::fromUtf8(" – base (") + name + ")", base, moved, {}, true);
  call.log(QString("Base from Drawing Silhouette: %1 (%2, score %3) deformed to %4 view(s): %5 silhouette vertices pulled, "
                   "silhouette off the outline by %6 % of its size before, %7 % after (Hausdorff); Laplacian coordinates "
                   "changed by %8 %; %9 vertices, %10 faces; %11; %12 s.")
               .arg(name)
               .arg(QString::fromStdString(lm.kind))
               .arg(chosen.score, 0, 'f', 4)
               .arg(fit.size())
               .arg(rep.silhouette_vertices)
               .arg(100 * rep.hausdorff_before, 0, 'f', 2)
               .arg(100 * rep.hausdorff_after, 0, 'f', 2)
               .arg(100 * rep.laplacian_change, 0, 'f', 1)
               .arg(thousands(base.n_vertices()))
               .arg(thousands(base.n_faces()))
               .arg(QString::fromStdString(rep.solver))
               .arg(seconds_since(t0), 0, 'f', 2));
}

}  // namespace

FilterSpec base_from_silhouette_filter(int id) {
  FilterSpec s{id,
               "Base from Drawing Silhouette",
               QString(kBaseInfo) + kBaseCitation,
               MeshFilterInterface::MeshCreation,
               MeshModel::MM_NONE,
               MeshModel::MM_NONE,
               base_parameters,
               apply_base,
               true};
  s.needs_mesh = false;
  return s;
}

}  // namespace reliefkit::ml
