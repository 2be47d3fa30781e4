#include "demarcating_filters.h"

#include <chrono>
#include <cmath>

#include "reliefkit/demarcating/demarcating.h"
#include "curve_report.h"
#include "mesh_bridge.h"
#include "params.h"

namespace reliefkit::ml {
namespace {

const char* kCitation =
    "M. Kolomenkin, I. Shimshoni, A. Tal, <b>\"Demarcating curves for shape illustration\"</b>, "
    "ACM Transactions on Graphics 27(5) (SIGGRAPH Asia 2008); thesis chapter 3.";

const char* kDemarcatingInfo =
    "Draws <b>demarcating curves</b>: the lines where a relief turns from concave to convex most "
    "steeply — the outlines of raised letters, figures and decorations on coins, seals, lamps and "
    "inscriptions, the way an archaeological illustrator would draw them. They do not depend on the "
    "viewpoint.<br><br>"
    "<b>Output</b>: a new layer <i>&lt;mesh&gt; – demarcating curves</i> holding the curves as "
    "edges (vertex quality = curve strength; save it as OBJ to keep the edges). On the scanned mesh, "
    "optionally, per-vertex attributes <code>demarcating_kappa</code> (the curvature across the "
    "curve direction), <code>demarcating_strength</code> and <code>demarcating_direction</code>.<br><br>"
    "<b>Strength threshold</b>: curves weaker than this are dropped. 1 is automatic: above the "
    "strength scanner noise gives and at least a quarter of the strongest features; it works the "
    "same whatever the size or unit of the scan. Use 0.5 for more, fainter lines; 2 for only the "
    "boldest.<br><br>"
    "Method: at every vertex the direction g in which curvature changes fastest (curvature "
    "gradient) is found in closed form from the curvature-derivative tensor; curves are the zero "
    "crossings of the curvature in that direction. ";

const char* kShadingInfo =
    "Grey-level <b>mean-curvature shading</b> for illustration: convex parts light, concave parts "
    "dark, as in archaeological drawings (thesis section 3.6). For the curves on top, run "
    "<i>Demarcating Curves</i> too: they come in their own layer, drawn crisply over the shading "
    "(<i>Darken along demarcating curves</i> paints them into the colours instead).<br><br>"
    "<b>Output</b>: vertex colours (grey = 0.5 + atan(contrast &middot; H / H<sub>90</sub>) / "
    "&pi;, where H is the mean curvature and H<sub>90</sub> the 90th percentile of its magnitude on this mesh), "
    "and vertex quality = the grey level (0..1).<br><br>";

void common_parameters(RichParameterList& par) {
  par.addParam(RichFloat("threshold", float(DemarcatingParams::kDefaultRelativeThreshold), "Strength threshold",
                         "Keeps curves at least this strong, relative to the automatic threshold (1). Smaller "
                         "values show fainter lines (and more noise), larger values only the boldest outlines."));
  add_presmoothing(par);
}

DemarcatingParams read_params(FilterCall& call) {
  DemarcatingParams p;
  p.relative_threshold = read_float(call, "threshold", "Strength threshold", 0, 1000);
  p.presmoothing = read_presmoothing(call);
  p.progress = call.progress;
  return p;
}

void demarcating_parameters(const MeshModel&, RichParameterList& par) {
  common_parameters(par);
  add_min_length(par, DemarcatingParams::kDefaultMinLengthEdges);
  par.addParam(RichBool("per_vertex", true, "Write per-vertex results",
                        "Also store, on this mesh, the curvature across the curve direction, the strength and "
                        "the direction at every vertex (attributes demarcating_kappa, demarcating_strength, "
                        "demarcating_direction)."));
  par.addParam(RichBool("quality", false, "Vertex quality = curvature across",
                        "Also put the curvature in the curve-crossing direction into vertex quality (it is zero "
                        "on the curves; Colorize by vertex quality shows where the relief is convex or concave)."));
  add_lift(par);
}

void log_curves(FilterCall& call, const DemarcatingParams& p, const DemarcatingResult& r, const QString& label,
                int faces, double secs) {
  const double h = r.scale.edge, len = r.curves.total_length();
  call.log(QString("Demarcating curves: %1 segments in %2 curves, length %3 (%4 edge lengths per 1,000 faces), "
                   "layer \"%5\"; %6 s.")
               .arg(thousands(static_cast<long long>(r.curves.segments.size())))
               .arg(thousands(static_cast<long long>(r.curves.chains().size())))
               .arg(len, 0, 'g', 5)
               .arg(h > 0 ? 1000.0 * len / h / faces : 0.0, 0, 'f', 1)
               .arg(label)
               .arg(secs, 0, 'f', 3));
  call.log(scale_summary(r.scale, r.noise, r.presmoothing, p.presmoothing));
  call.log(QString("Strength threshold %1 x automatic = %2 (median vertex strength %3; units 1/length^2); "
                   "minimum length %4; %5 vertices resolved among three competing maxima.")
               .arg(p.relative_threshold, 0, 'g', 3)
               .arg(r.threshold, 0, 'g', 4)
               .arg(r.median_strength, 0, 'g', 4)
               .arg(r.min_length, 0, 'g', 4)
               .arg(thousands(r.gradient.competing)));
  if (r.curves.segments.empty())
    call.log(QString("No demarcating curve is above the threshold: the layer is empty (meshlabserver then reports "
                     "\"Failed saving\" for it). The strongest crossing seen has strength %1, %2 x the threshold %3: "
                     "lower \"Strength threshold\" below %2, or the minimum length.")
                 .arg(r.strongest_crossing, 0, 'g', 3)
                 .arg(r.threshold > 0 ? p.relative_threshold * r.strongest_crossing / r.threshold : 0.0, 0, 'g', 3)
                 .arg(r.threshold, 0, 'g', 3));
}

void apply_demarcating(FilterCall& call) {
  auto t0 = std::chrono::steady_clock::now();
  DemarcatingParams p = read_params(call);
  p.min_length_edges = read_min_length(call);
  const bool per_vertex = read_bool(call, "per_vertex", "Write per-vertex results");
  const bool quality = read_bool(call, "quality", "Vertex quality = curvature across");
  const double lift = read_lift(call);
  View view = view_of(call.mesh(), call.log);
  const Surface surface = surface_of(view);
  DemarcatingResult r = compute_demarcating(surface, p);

  const QString label = derived_label(call.mesh(), "demarcating curves");
  add_curve_layer(call.doc, label, r.curves, vcg::Color4b(0, 0, 0, 255), &r.curvature->normal, lift * r.scale.edge);
  if (per_vertex) {
    write_vertex_attribute(call.mesh().cm, view, "demarcating_kappa", r.gradient.kappa);
    write_vertex_attribute(call.mesh().cm, view, "demarcating_strength", r.gradient.strength);
    write_vertex_vectors(call.mesh().cm, view, "demarcating_direction", r.gradient.direction);
  }
  if (quality) {
    call.mesh().updateDataMask(MeshModel::MM_VERTQUALITY);
    for_each_vertex(view, [&](int i, CVertexO* v) { v->Q() = float(r.gradient.kappa[i]); });
  }
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  log_curves(call, p, r, label, view.mesh.n_faces(), secs);
  log_curve_statistics(call, "demarcating curves", "demarcating", r.curves, r.scale.edge, view.mesh.n_faces());
}

void shading_parameters(const MeshModel&, RichParameterList& par) {
  par.addParam(RichFloat("contrast", 1.0f, "Contrast",
                         "How strongly curvature is turned into light and dark. At 1 the curvature of the "
                         "mesh's most curved tenth (its relief) gives three-quarter light or dark; larger "
                         "values exaggerate faint details."));
  par.addParam(RichBool("darken", false, "Darken along demarcating curves",
                        "Also paints the demarcating curves into the shading (the vertices next to them are darkened). "
                        "Off by default: on scans the painted lines are two or three triangles wide; run "
                        "<i>Demarcating Curves</i> for crisp curves in their own layer."));
  par.addParam(RichFloat("darkness", 0.6f, "Curve darkness",
                         "How much the curves darken the shading: 0 not at all, 1 black."));
  common_parameters(par);
}

void apply_shading(FilterCall& call) {
  DemarcatingParams p = read_params(call);
  const double contrast = read_float(call, "contrast", "Contrast", 0, 1000);
  const bool darken = read_bool(call, "darken", "Darken along demarcating curves");
  const double darkness = read_float(call, "darkness", "Curve darkness", 0, 1);
  View view = view_of(call.mesh(), call.log);
  const Surface surface = surface_of(view);
  std::vector<double> grey;
  long long segments = 0;
  if (darken) {
    DemarcatingResult r = compute_demarcating(surface, p);
    grey = mean_curvature_shading(*r.curvature, contrast);
    darken_along_curves(view.mesh, r.curves, darkness, grey);
    segments = static_cast<long long>(r.curves.segments.size());
    call.log(scale_summary(r.scale, r.noise, r.presmoothing, p.presmoothing));
  } else {
    ScaledCurvature sc = curvature_at_scale(surface, p.presmoothing, p.estimator, p.progress);
    grey = mean_curvature_shading(*sc.curvature, contrast);
    call.log(scale_summary(sc.scale, sc.noise, sc.presmoothing, p.presmoothing));
  }
  write_grey(call.mesh(), view, grey, grey);
  call.log(QString("Curvature shading of %1 vertices (contrast %2)%3.")
               .arg(thousands(view.mesh.n_vertices()))
               .arg(contrast, 0, 'g', 3)
               .arg(darken ? QString(", darkened along %1 demarcating-curve segments").arg(thousands(segments)) : QString()));
}

}  // namespace

FilterSpec demarcating_curves_filter(int id) {
  return FilterSpec{id,
                    "Demarcating Curves",
                    QString(kDemarcatingInfo) + kCitation,
                    ml::FilterInterface::FilterClass(ml::FilterInterface::Normal | ml::FilterInterface::Layer),
                    MeshModel::MM_NONE,
                    MeshModel::MM_VERTQUALITY,
                    demarcating_parameters,
                    apply_demarcating,
                    true};
}

FilterSpec curvature_shading_filter(int id) {
  return FilterSpec{id,
                    "Curvature Shading",
                    QString(kShadingInfo) + "Method: " + kCitation,
                    ml::FilterInterface::VertexColoring,
                    MeshModel::MM_NONE,
                    MeshModel::MM_VERTCOLOR | MeshModel::MM_VERTQUALITY,
                    shading_parameters,
                    apply_shading};
}

}  // namespace reliefkit::ml
