#include "multiscale_filters.h"

#include <chrono>
#include <cmath>
#include <tuple>

#include "curve_report.h"
#include "mesh_bridge.h"
#include "params.h"
#include "reliefkit/base/angles.h"
#include "reliefkit/multiscale/multiscale.h"

namespace reliefkit::ml {
namespace {

constexpr double kAutoMinScale = 1.0, kAutoMaxScale = 16.0, kAutoFinalSmoothing = 0.5;  // edge lengths

const char* kMethod =
    "Method (thesis chapter 5; M. Kolomenkin, I. Shimshoni, A. Tal): the surface is smoothed to a series "
    "of scales; at every point the scale where the curve's own strength, normalised by the scale, peaks "
    "is its optimal scale (Lindeberg's scale selection on surfaces) — the curvature over the smooth base "
    "surface for ridges and valleys, the derivative of the curvature across the edge for relief edges. "
    "Each feature's scale covers its footprint; featureless areas take a smooth fill (a sparse linear "
    "system, eq. 5.3). Scales are in edge lengths, so one script serves a coin in millimetres and a "
    "statue in metres.";

const QStringList kCurveTypes = {"Ridges and valleys", "Relief edges"};

QString with_method(const char* what) { return QString(what) + "<br><br>" + kMethod; }

const char* kOptimalInfo =
    "Finds, at every vertex, the <b>scale of the feature that passes there</b>: a worn coin's date is fine, "
    "its portrait coarse, and one smoothing for both loses one of them. Run it to see what the multi-scale "
    "filters will use: <i>Filters › Color Creation › Colorize by vertex Quality</i> then shows fine features "
    "in one colour and coarse ones in another.<br><br>"
    "<b>Output</b>: per-vertex attributes <code>optimal_scale</code> (the Gaussian scale, mesh units) and "
    "<code>optimal_scale_strength</code> (the feature's normalised strength; 0 where no feature anchors the "
    "scale); vertex quality = the scale in edge lengths; the log shows how the scales are distributed.";

const char* kSmoothedInfo =
    "Makes a copy of the mesh in which <b>every point is smoothed by its own optimal scale</b>: noise and "
    "small bumps vanish from smooth areas while fine features (letters, incised lines) stay sharp. The "
    "input layer is left untouched.<br><br>"
    "<b>Output</b>: a new layer <i>&lt;mesh&gt; – optimally smoothed</i> with the input's per-vertex data.";

const char* kRidgesInfo =
    "Draws <b>ridges and valleys</b> (crests and grooves) with <b>no smoothing scale to choose</b>: every "
    "part of the surface is read at the scale of its own features, so fine grooves and wide ones come out "
    "in one run, on noisy scans too. What <i>Ridges and Valleys</i> draws at its automatic smoothing is "
    "kept, joined into longer lines, and the wider features are added. A groove's banks are reported as the "
    "groove, not as ridges of their own.<br><br>"
    "<b>Output</b>: two new layers <i>&lt;mesh&gt; – multi-scale ridges</i> and <i>– multi-scale valleys</i> "
    "(edges on the input surface; vertex quality = normalised strength; save them as OBJ); per-vertex "
    "attribute <code>optimal_scale</code> on the mesh.";

const char* kReliefInfo =
    "Draws <b>relief edges</b> (outlines of stamped or carved relief) with <b>no smoothing scale to "
    "choose</b>: each outline is found on the surface smoothed by its own optimal scale, and the fine "
    "outlines <i>Relief Edges</i> draws at its automatic smoothing (lettering) are kept where the chosen "
    "scale is fine.<br><br>"
    "<b>Output</b>: a new layer <i>&lt;mesh&gt; – multi-scale relief edges</i> (edges on the input surface; "
    "vertex quality = edge strength in degrees; save it as OBJ); per-vertex attribute "
    "<code>optimal_scale</code> on the mesh.";

void add_curve_type(RichParameterList& par) {
  par.addParam(RichEnum("curve", 0, kCurveTypes, "Curves the scale is for",
                        "Ridges and valleys: the scale of crests and grooves (curvature). Relief edges: the scale "
                        "of step edges (the derivative of the curvature across them)."));
}

void add_scale_range(RichParameterList& par) {
  add_length(par, "min_scale", Length::automatic(), "Smallest scale",
             "The finest smoothing considered (a Gaussian, in edge lengths). auto: 1 edge length.");
  add_length(par, "max_scale", Length::automatic(), "Largest scale",
             "The widest smoothing considered (edge lengths). auto: 16 edge lengths, at most 1/32 of the "
             "object's size (a small curved object's own shape would read as a feature); a set value is "
             "lowered on objects smaller than 8 times it (the log says so).");
  par.addParam(RichInt("levels", 2, "Scales per doubling",
                       "How many scales are computed per doubling of the scale (1-8); more is slower and "
                       "only slightly more precise (the peak between scales is interpolated)."));
}

struct ScaleRange {
  Length lo, hi;
  int levels = 2;
};

ScaleRange read_scale_range(FilterCall& call) {
  ScaleRange r;
  r.lo = read_length(call, "min_scale", "Smallest scale", 0.25, 1000);
  r.hi = read_length(call, "max_scale", "Largest scale", 0.25, 1000);
  r.levels = read_int(call, "levels", "Scales per doubling", 1, 8);
  return r;
}

// The options in edge lengths, once the mesh's edge length is known (lengths from old scripts
// are in mesh units).
OptimalScaleOptions resolve(FilterCall& call, const ScaleRange& r, const MeshScale& scale) {
  OptimalScaleOptions o;
  auto edges = [&](const Length& l, double automatic) {
    return l.is_auto() ? automatic : l.kind == Length::Kind::Edges ? l.value : l.value / scale.edge;
  };
  o.min_scale_edges = edges(r.lo, kAutoMinScale);
  o.max_scale_edges = edges(r.hi, kAutoMaxScale);
  o.max_scale_auto = r.hi.is_auto();
  o.levels_per_octave = r.levels;
  o.progress = call.progress;
  if (!(o.max_scale_edges >= o.min_scale_edges))
    throw InputError(qUtf8Printable(QString("\"Largest scale\" (%1 edge lengths) must not be below \"Smallest scale\" "
                                            "(%2 edge lengths).")
                                        .arg(o.max_scale_edges)
                                        .arg(o.min_scale_edges)));
  o.validate();
  return o;
}

// "Optimal scale (edge lengths): 1.0 12 % · 1.4 3 % · …; 41 % featureless (filled)".
QString histogram(const OptimalScale& s) {
  const double h = s.scale.edge;
  std::vector<long long> count(s.levels.size(), 0);
  long long featureless = 0;
  for (size_t v = 0; v < s.sigma.size(); ++v) {
    if (!(s.sigma[v] > 0)) continue;
    size_t best = 0;
    for (size_t k = 1; k < s.levels.size(); ++k)
      if (std::abs(std::log(s.sigma[v] / s.levels[k])) < std::abs(std::log(s.sigma[v] / s.levels[best]))) best = k;
    ++count[best];
    if (!(s.selected[v] > 0)) ++featureless;
  }
  const double n = std::max<size_t>(1, s.sigma.size());
  QString line = QString("Edge length %1 (the unit of the scales). Optimal scale (edge lengths, share of vertices):")
                     .arg(h, 0, 'g', 4);
  for (size_t k = 0; k < count.size(); ++k)
    line += QString(" %1: %2 %").arg(s.levels[k] / h, 0, 'f', 1).arg(100.0 * count[k] / n, 0, 'f', 1);
  line += QString("; %1 % of the vertices carry no feature (their scale is filled in, eq. 5.3, solved by %2).")
              .arg(100.0 * featureless / n, 0, 'f', 1)
              .arg(QString::fromStdString(s.fill_solve.summary()));
  if (s.max_scale_lowered)
    line += QString(" The largest scale was lowered to %1 edge lengths for an object %2 edge lengths across "
                    "(auto: at most 1/32 of it; a set value: 1/8).")
                .arg(s.levels.back() / h, 0, 'f', 1)
                .arg(s.scale.object_size / h, 0, 'f', 0);
  return line;
}

void write_scale(FilterCall& call, const View& view, const OptimalScale& s) {
  write_vertex_attribute(call.mesh().cm, view, "optimal_scale", s.sigma);
}

void optimal_parameters(const MeshModel&, RichParameterList& par) {
  add_curve_type(par);
  add_scale_range(par);
  par.addParam(RichBool("quality", true, "Vertex quality = scale",
                        "Put the optimal scale (edge lengths) into vertex quality, for Colorize by vertex Quality."));
}

void apply_optimal(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const ScaleRange range = read_scale_range(call);
  const bool relief = read_enum(call, "curve", "Curves the scale is for", 2) == 1;
  const bool quality = read_bool(call, "quality", "Vertex quality = scale");
  View view = view_of(call.mesh(), call.log);
  const Surface surface = surface_of(view);
  OptimalScaleOptions o = resolve(call, range, surface.scale());
  o.curve = relief ? ScaleStrength::ReliefEdges : ScaleStrength::RidgesValleys;
  const OptimalScale s = optimal_scale(surface, o);
  write_scale(call, view, s);
  write_vertex_attribute(call.mesh().cm, view, "optimal_scale_strength", s.strength);
  if (quality) {
    call.mesh().updateDataMask(MeshModel::MM_VERTQUALITY);
    for_each_vertex(view, [&](int i, CVertexO* v) { v->Q() = float(s.sigma[i] / s.scale.edge); });
  }
  call.log(QString("Optimal scale of %1 vertices for %2, %3 scales from %4 to %5 edge lengths (edge length %6); %7 s.")
               .arg(thousands(view.mesh.n_vertices()))
               .arg(kCurveTypes[relief ? 1 : 0].toLower())
               .arg(s.levels.size())
               .arg(s.levels.front() / s.scale.edge, 0, 'f', 1)
               .arg(s.levels.back() / s.scale.edge, 0, 'f', 1)
               .arg(s.scale.edge, 0, 'g', 4)
               .arg(seconds_since(t0), 0, 'f', 2));
  call.log(histogram(s));
}

void smoothed_parameters(const MeshModel&, RichParameterList& par) {
  add_curve_type(par);
  add_scale_range(par);
  add_length(par, "final_smoothing", Length::automatic(), "Final smoothing",
             "A light smoothing of the assembled surface that removes seams between scales (thesis 5.4). "
             "auto: 0.5 edge lengths; 0 turns it off.");
}

void apply_smoothed(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const ScaleRange range = read_scale_range(call);
  const bool relief = read_enum(call, "curve", "Curves the scale is for", 2) == 1;
  const Length fs = read_length(call, "final_smoothing", "Final smoothing", 0, 100);
  View view = view_of(call.mesh(), call.log);
  const Surface surface = surface_of(view);
  const MeshScale& ms = surface.scale();
  OptimalScaleOptions o = resolve(call, range, ms);
  o.curve = relief ? ScaleStrength::ReliefEdges : ScaleStrength::RidgesValleys;
  o.final_smoothing_edges = fs.is_auto() ? kAutoFinalSmoothing : fs.kind == Length::Kind::Edges ? fs.value : fs.value / ms.edge;
  o.smoothed_surface = true;
  const OptimalScale s = optimal_scale(surface, o);
  const QString label = derived_label(call.mesh(), "optimally smoothed");
  add_surface_layer(call.doc, label, call.mesh(), view, s.smoothed);
  write_scale(call, view, s);
  call.log(QString("Optimally smoothed surface in layer \"%1\" (%2 vertices); %3 s.")
               .arg(label)
               .arg(thousands(view.mesh.n_vertices()))
               .arg(seconds_since(t0), 0, 'f', 2));
  call.log(histogram(s));
}

void ridges_parameters(const MeshModel&, RichParameterList& par) {
  par.addParam(RichFloat("threshold", 1.f, "Strength threshold",
                         "Keeps lines at least this strong, relative to the automatic threshold (1). Smaller values "
                         "show fainter lines, larger only the clearest."));
  add_min_length(par, kMultiscaleMinLengthEdges);
  add_scale_range(par);
  add_lift(par);
}

void apply_ridges(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  RidgeValleyParams p;
  p.relative_threshold = read_float(call, "threshold", "Strength threshold", 0, 1000);
  p.min_length_edges = read_min_length(call);
  const ScaleRange range = read_scale_range(call);
  const double lift = read_lift(call);
  p.progress = call.progress;
  View view = view_of(call.mesh(), call.log);
  const Surface surface = surface_of(view);
  const OptimalScaleOptions o = resolve(call, range, surface.scale());
  const MultiscaleRidgeValleys r = multiscale_ridges_valleys(surface, o, p);
  const std::vector<Vec3>& normals = surface.normals();
  const QString lr = derived_label(call.mesh(), "multi-scale ridges"), lv = derived_label(call.mesh(), "multi-scale valleys");
  const double h = r.scale.scale.edge;
  add_curve_layer(call.doc, lr, r.curves.ridges, vcg::Color4b(200, 30, 30, 255), &normals, lift * h);
  add_curve_layer(call.doc, lv, r.curves.valleys, vcg::Color4b(30, 30, 200, 255), &normals, lift * h);
  write_scale(call, view, r.scale);
  call.log(QString("Multi-scale ridges: %1 segments; valleys: %2 segments (normalised thresholds %3, %4); layers "
                   "\"%5\", \"%6\"; %7 s.")
               .arg(thousands(static_cast<long long>(r.curves.ridges.segments.size())))
               .arg(thousands(static_cast<long long>(r.curves.valleys.segments.size())))
               .arg(r.curves.ridge_threshold, 0, 'g', 3)
               .arg(r.curves.valley_threshold, 0, 'g', 3)
               .arg(lr)
               .arg(lv)
               .arg(seconds_since(t0), 0, 'f', 2));
  call.log(histogram(r.scale));
  log_curve_statistics(call, "multi-scale ridges", "ridges", r.curves.ridges, h, view.mesh.n_faces());
  log_curve_statistics(call, "multi-scale valleys", "valleys", r.curves.valleys, h, view.mesh.n_faces());
  for (const auto& [name, layer, strongest, threshold] :
       {std::tuple{"ridge", &r.curves.ridges, r.curves.strongest_ridge, r.curves.ridge_threshold},
        std::tuple{"valley", &r.curves.valleys, r.curves.strongest_valley, r.curves.valley_threshold}})
    if (layer->segments.empty())
      call.log(QString("No %1 line is above the threshold: its layer is empty (meshlabserver then reports \"Failed "
                       "saving\" for it). The strongest %1 seen has %2 x the threshold: lower \"Strength "
                       "threshold\" below it.")
                   .arg(name)
                   .arg(threshold > 0 ? p.relative_threshold * strongest / threshold : 0.0, 0, 'g', 3));
}

void relief_parameters(const MeshModel&, RichParameterList& par) {
  add_min_length(par, ReliefEdgeParams::kDefaultMinLengthEdges);
  par.addParam(RichFloat("gap", float(ReliefEdgeParams::kDefaultLinkGapEdges), "Bridge gaps up to",
                         "Joins the ends of edge pieces that face each other across a gap of at most this many edge "
                         "lengths. 0 leaves the pieces as found."));
  add_scale_range(par);
  add_lift(par);
}

void apply_relief(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  ReliefEdgeParams p;
  p.min_length_edges = read_min_length(call);
  p.link_gap_edges = read_float(call, "gap", "Bridge gaps up to", 0, 20);
  const ScaleRange range = read_scale_range(call);
  const double lift = read_lift(call);
  p.progress = call.progress;
  View view = view_of(call.mesh(), call.log);
  const Surface surface = surface_of(view);
  const OptimalScaleOptions o = resolve(call, range, surface.scale());
  const MultiscaleReliefEdges r = multiscale_relief_edges(surface, o, p);
  Polylines edges = r.curves.edges;
  for (auto& s : edges.strength) s /= kRadiansPerDegree;
  const std::vector<Vec3>& normals = surface.normals();
  const QString label = derived_label(call.mesh(), "multi-scale relief edges");
  add_curve_layer(call.doc, label, edges, vcg::Color4b(0, 0, 0, 255), &normals, lift * r.scale.scale.edge);
  write_scale(call, view, r.scale);
  call.log(QString("Multi-scale relief edges: %1 segments in %2 curves, layer \"%3\"; strong tilt %4 deg; %5 s.")
               .arg(thousands(static_cast<long long>(r.curves.edges.segments.size())))
               .arg(thousands(static_cast<long long>(r.curves.edges.chains().size())))
               .arg(label)
               .arg(r.curves.strong_angle / kRadiansPerDegree, 0, 'f', 1)
               .arg(seconds_since(t0), 0, 'f', 2));
  call.log(histogram(r.scale));
  log_curve_statistics(call, "multi-scale relief edges", "relief_edges", r.curves.edges, r.scale.scale.edge,
                       view.mesh.n_faces());
  if (r.curves.edges.segments.empty())
    call.log(QString("No relief edge passed the thresholds: the layer is empty (meshlabserver then reports \"Failed "
                     "saving\" for it). The steepest edge crossing seen tilts by %1 deg.")
                 .arg(r.curves.steepest_crossing / kRadiansPerDegree, 0, 'f', 1));
}

constexpr auto kLayers = ml::FilterInterface::FilterClass(ml::FilterInterface::Normal | ml::FilterInterface::Layer);

}  // namespace

FilterSpec optimal_scale_filter(int id) {
  return FilterSpec{id, "Compute Optimal Scale", with_method(kOptimalInfo), ml::FilterInterface::Normal,
                    MeshModel::MM_NONE, MeshModel::MM_VERTQUALITY, optimal_parameters, apply_optimal};
}

FilterSpec smoothed_surface_filter(int id) {
  return FilterSpec{id, "Optimally Smoothed Surface", with_method(kSmoothedInfo), kLayers, MeshModel::MM_NONE,
                    MeshModel::MM_NONE, smoothed_parameters, apply_smoothed, true};
}

FilterSpec multiscale_ridges_filter(int id) {
  return FilterSpec{id, "Multi-scale Ridges and Valleys", with_method(kRidgesInfo), kLayers, MeshModel::MM_NONE,
                    MeshModel::MM_NONE, ridges_parameters, apply_ridges, true};
}

FilterSpec multiscale_relief_edges_filter(int id) {
  return FilterSpec{id, "Multi-scale Relief Edges", with_method(kReliefInfo), kLayers, MeshModel::MM_NONE,
                    MeshModel::MM_NONE, relief_parameters, apply_relief, true};
}

}  // namespace reliefkit::ml
