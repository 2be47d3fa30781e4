// "Base from Drawing Silhouette": MeshLab adapter of reliefkit/drawing/base_library.h (thesis sect. 7.5).
#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>

#include "drawing_filters.h"
#include "drawing_image.h"
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
    "the fit improves (1 pass: the thesis); a model of more than 40,000 faces makes its passes on a coarse "
    "copy of at most 20,000 and moves as the copy does (the fit is still measured on the model). ";

const char* kBaseCitation =
    "M. Kolomenkin, G. Leifman, I. Shimshoni, A. Tal, <b>\"Reconstruction of relief objects from line "
    "drawings\"</b>, CVPR 2011; thesis chapter 7, section 7.5.";

// The folder this plugin's library was loaded from (MeshLab's plugin folder, or a user's
// MeshLabExtraPlugins/<version>), empty if unknown.
QString plugin_folder() {
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&plugin_folder), &info) || !info.dli_fname) return {};
  return QFileInfo(QString::fromLocal8Bit(info.dli_fname)).absolutePath();
}

// The library the build made: installed beside the plugins (cmake --install, the user's plugin
// folder: reliefkit-bases/), or in the private prefix (<bin>/../share/reliefkit/bases).
QString shipped_library() {
  for (const QString& dir : {plugin_folder() + "/reliefkit-bases",
                             QCoreApplication::applicationDirPath() + "/../share/reliefkit/bases"})
    if (QFileInfo(QDir::cleanPath(dir)).isDir()) return QDir::cleanPath(dir);
  return {};
}

void base_parameters(const MeshModel&, RichParameterList& par) {
  add_drawing_image_parameter(par, "The drawing of the object: dark lines on light paper (PNG, JPEG, TIFF, BMP).");
  par.addParam(RichString("views", "front", "Views",
                          "Which views the image shows: \"front\" (the largest outline is the front view); \"front; "
                          "top\" (the two largest outlines in reading order: top to bottom, then left to right); "
                          "\"front = x y w h; side = x y w h\" (regions in pixels); \"top = other_image.png\" (a view "
                          "in its own image, beside the drawing). Views: front (x right, y up), side (seen from the "
                          "right), top (seen from above, front at the bottom)."));
  add_dpi_and_scale_parameters(par);
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

// What "Base from Drawing Silhouette" reads.
struct BaseSettings {
  QString path, views_text, library_dir, user_dir, wanted;
  double pixel_mm = 25.4 / 300;  // of the images as drawn (DPI and scale)
  DeformParams deform;
  OutlineParams outline;
  int listed = 5;
  bool round = false;
};

BaseSettings read_base_settings(FilterCall& call) {
  BaseSettings s;
  s.path = call.params.getOpenFileName("drawing");
  s.pixel_mm = read_pixel_mm(call);
  s.deform.alpha = read_float(call, "alpha", "Shape weight (alpha)", 1e-4, 1e4);
  s.deform.passes = read_int(call, "passes", "Passes", 1, 20);
  s.deform.progress = call.progress;
  s.outline.gap = read_float(call, "gap", "Outline gap (px, 0: auto)", 0, 10000);
  s.listed = read_int(call, "matches", "Matches listed", 1, 100);
  s.round = read_bool(call, "round", "One view: a round object");
  s.library_dir = call.params.getString("library").trimmed();
  if (s.library_dir.isEmpty()) {
    s.library_dir = shipped_library();
    if (s.library_dir.isEmpty())
      throw InputError("ReliefKit's library of base models is not beside this plugin (reliefkit-bases in its folder) nor "
                       "this MeshLab (share/reliefkit/bases next to its bin folder): give its folder in \"Model library folder\" (build/bases in a build tree).");
  } else if (s.library_dir.compare("none", Qt::CaseInsensitive) == 0) {
    s.library_dir.clear();
  }
  s.user_dir = call.params.getString("user_models").trimmed();
  s.wanted = call.params.getString("model").trimmed();
  s.views_text = call.params.getString("views");
  if (s.path.trimmed().isEmpty()) throw InputError("No drawing image was given: choose the image file in \"Drawing image\".");
  return s;
}

// The drawing's images, each read once, with their pixel size (mm): a view's own image by its name
// (relative to the drawing's folder), "" the drawing.
class DrawingImages {
 public:
  explicit DrawingImages(const BaseSettings& s) : s_(s), dir_(QFileInfo(s.path).absoluteDir()) {}
  const ViewImage& of(const std::string& name) {
    QString p = s_.path;
    if (!name.empty()) {
      p = QString::fromStdString(name);
      if (QFileInfo(p).isRelative()) p = dir_.filePath(p);
    }
    for (size_t k = 0; k < paths_.size(); ++k)
      if (paths_[k] == p) return images_[k];
    double reduction = 1;
    const cv::Mat img = read_drawing_image(p.toStdString(), &reduction);
    paths_.push_back(p);
    images_.push_back({drawing_grey(img), s_.pixel_mm / reduction});
    return images_.back();
  }

 private:
  const BaseSettings& s_;
  QDir dir_;
  std::vector<QString> paths_;
  std::deque<ViewImage> images_;  // references stay valid as images are added
};

void log_view(FilterCall& call, ViewKind kind, const FoundViewOutline& f) {
  QString name = view_name(kind);
  name[0] = name[0].toUpper();
  const DrawingOutline& o = f.outline;
  call.log(QString("%1 view: outline of %2 x %3 px at (%4, %5), %6 mm x %7 mm; gaps up to %8 px bridged, %9 other marks "
                   "left out.")
               .arg(name)
               .arg(o.box.width)
               .arg(o.box.height)
               .arg(o.box.x)
               .arg(o.box.y)
               .arg(o.box.width * f.pixel_size, 0, 'f', 1)
               .arg(o.box.height * f.pixel_size, 0, 'f', 1)
               .arg(o.gap, 0, 'f', 0)
               .arg(o.dropped));
  if (touches_frame(o.box, f.frame))
    call.log(QString("Warning: the %1 view's outline touches the border of its image: the drawing may be cut there, "
                     "or its lines run into the border (check the outline; give the view's region).")
                 .arg(view_name(kind)));
}

BaseLibrary read_library(FilterCall& call, const BaseSettings& s) {
  BaseLibrary library;
  if (!s.library_dir.isEmpty()) add_library_folder(library, s.library_dir.toStdString());
  if (!s.user_dir.isEmpty()) add_library_folder(library, s.user_dir.toStdString());
  for (const auto& n : library.notes) call.log(QString::fromStdString(n));
  if (!s.library_dir.isEmpty())
    call.log("Model library: " + s.library_dir + (s.user_dir.isEmpty() ? QString() : " and " + s.user_dir));
  if (library.models.empty())
    throw InputError("The model library is empty: \"Model library folder\"" +
                     (s.library_dir.isEmpty() ? std::string(" is \"none\"") : " (" + s.library_dir.toStdString() + ")") +
                     " and \"Your models folder\"" +
                     (s.user_dir.isEmpty() ? std::string(" is not set") : " (" + s.user_dir.toStdString() + ")") +
                     " hold no readable PLY, OBJ, STL or OFF model.");
  return library;
}

// The best match (or the model the user named), with the best matches logged.
BaseMatch choose_model(FilterCall& call, const BaseSettings& s, const BaseLibrary& library,
                       const std::vector<ViewFeature>& features) {
  const auto t_search = std::chrono::steady_clock::now();
  const auto ranked = retrieve_bases(library, features, int(library.models.size()));
  const double search_s = seconds_since(t_search);
  QString list;
  for (int k = 0; k < std::min<int>(s.listed, int(ranked.size())); ++k) {
    const LibraryModel& m = library.models[size_t(ranked[size_t(k)].model)];
    list += QString("%1%2. %3 (%4) %5")
                .arg(k ? "; " : "")
                .arg(k + 1)
                .arg(QString::fromStdString(m.name))
                .arg(QString::fromStdString(m.kind))
                .arg(ranked[size_t(k)].score, 0, 'f', 4);
  }
  call.log(QString("Best matches of %1 models (feature distance, 0 = same silhouette; %2 s): %3.")
               .arg(library.models.size())
               .arg(search_s, 0, 'f', 3)
               .arg(list));
  return s.wanted.isEmpty() ? ranked.front() : named_match(library, ranked, s.wanted.toStdString());
}

void log_base(FilterCall& call, const LibraryModel& lm, const BaseMatch& chosen, size_t views, const DeformReport& rep,
              const TriMesh& base, double seconds) {
  const std::string warning = base_fit_warning(rep);
  if (!warning.empty()) call.log(QString::fromStdString(warning));
  call.log(QString("Base from Drawing Silhouette: %1 (%2, score %3) deformed to %4 view(s): %5 silhouette vertices pulled, "
                   "silhouette off the outline by %6 % of its size before, %7 % after (Hausdorff); Laplacian coordinates "
                   "changed by %8 %; %9 vertices, %10 faces; %11; %12 s.")
               .arg(QString::fromStdString(lm.name))
               .arg(QString::fromStdString(lm.kind))
               .arg(chosen.score, 0, 'f', 4)
               .arg(views)
               .arg(rep.silhouette_vertices)
               .arg(100 * rep.hausdorff_before, 0, 'f', 2)
               .arg(100 * rep.hausdorff_after, 0, 'f', 2)
               .arg(100 * rep.laplacian_change, 0, 'f', 1)
               .arg(thousands(base.n_vertices()))
               .arg(thousands(base.n_faces()))
               .arg(QString::fromStdString(rep.solver))
               .arg(seconds, 0, 'f', 2));
}

void apply_base(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const BaseSettings s = read_base_settings(call);
  const auto views = parse_drawing_views(s.views_text.toStdString());
  if (call.progress) call.progress(2, "Reading the drawing");
  DrawingImages images(s);
  const std::vector<FoundViewOutline> found =
      find_view_outlines(views, [&](const std::string& name) -> const ViewImage& { return images.of(name); }, s.outline);
  std::vector<ViewOutline> outlines;
  std::vector<ViewFeature> features;
  for (size_t i = 0; i < views.size(); ++i) {
    outlines.push_back({views[i].kind, outline_in_units(found[i].outline.outline, found[i].pixel_size)});
    features.push_back({views[i].kind, circle_feature(outlines.back().outline)});
    log_view(call, views[i].kind, found[i]);
  }
  if (call.progress) call.progress(10, "Reading the model library");
  const BaseLibrary library = read_library(call, s);
  const BaseMatch chosen = choose_model(call, s, library, features);
  const LibraryModel& lm = library.models[size_t(chosen.model)];
  if (call.progress) call.progress(20, "Placing the model");
  const std::vector<ViewOutline> fit = s.round ? round_object_views(outlines) : outlines;
  if (fit.size() > outlines.size())
    call.log(QString("One %1 view: the object is taken as round (the same outline as its %2 view; \"One view: a round "
                     "object\" off keeps the model's depth).")
                 .arg(view_name(views[0].kind))
                 .arg(view_name(fit.back().kind)));
  const TriMesh model = place_on_outlines(oriented(normalize_to_principal_axes(read_model_file(lm.path)), chosen.orientation), fit);
  DeformReport rep;
  const TriMesh base = deform_to_outlines(model, fit, s.deform, &rep);
  std::vector<double> moved(size_t(base.n_vertices()));
  for (int i = 0; i < base.n_vertices(); ++i) moved[size_t(i)] = (base.vertices[size_t(i)] - model.vertices[size_t(i)]).norm();
  const QString name = QString::fromStdString(lm.name);
  add_mesh_layer(call.doc, name + QString::fromUtf8(" – retrieved"), model, std::vector<double>(size_t(model.n_vertices()), 0), {},
                 false);
  add_mesh_layer(call.doc, QFileInfo(s.path).completeBaseName() + QString::fromUtf8(" – base (") + name + ")", base, moved, {},
                 true);
  log_base(call, lm, chosen, fit.size(), rep, base, seconds_since(t0));
}

}  // namespace

FilterSpec base_from_silhouette_filter(int id) {
  FilterSpec s{id,
               "Base from Drawing Silhouette",
               QString(kBaseInfo) + kBaseCitation,
               ml::FilterInterface::MeshCreation,
               MeshModel::MM_NONE,
               MeshModel::MM_NONE,
               base_parameters,
               apply_base,
               true};
  s.needs_mesh = false;
  return s;
}

}  // namespace reliefkit::ml
