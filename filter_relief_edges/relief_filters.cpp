#include "relief_filters.h"

#include <chrono>
#include <cmath>
#include <tuple>

#include "reliefkit/base/angles.h"
#include "reliefkit/relief_edges/base_normals.h"
#include "curve_report.h"
#include "mesh_bridge.h"
#include "params.h"
#include "reliefkit/relief_edges/relief_edges.h"
#include "reliefkit/relief_edges/ridges.h"

namespace reliefkit::ml {
namespace {


const char* kReliefInfo =
    "Draws <b>relief edges</b>: the edges of a relief as if it were an image printed on the smooth "
    "surface underneath — outlines of stamped letters, figures and ornaments on handles, vases, lamps "
    "and figurines, also where the relief is worn and the scan is noisy, and on curved objects.<br><br>"
    "<b>Output</b>: a new layer <i>&lt;mesh&gt; – relief edges</i> (edges; vertex quality = edge strength, "
    "the angle in degrees between the surface and the base surface; save it as OBJ). On the scanned mesh, "
    "optionally, attributes <code>relief_G</code>, <code>relief_direction</code>, <code>relief_alpha</code>, "
    "<code>relief_fit_error</code> and <code>base_normal</code>.<br><br>"
    "Method: at every vertex a smoothed step edge is fitted to the local surface (its direction "
    "maximises the correlation with the curvature-derivative tensor); the normal of the smooth base "
    "surface limits the possible directions; the curvature across the edge is smoothed, and its zero "
    "crossings are the edge points, kept by a two-dimensional hysteresis on how well the surface fits the "
    "step model and how steep it is. M. Kolomenkin, I. Shimshoni, A. Tal, <b>\"On edge detection on "
    "surfaces\"</b>, CVPR 2009; thesis chapter 4.";

const char* kBaseInfo =
    "Estimates the normals of the <b>smooth base surface</b> under a relief — the shape a coin, vase or "
    "handle would have without its decoration — by smoothing the surface normals over a wide "
    "neighbourhood (about three times the size of the relief's features) along the surface.<br><br>"
    "<b>Output</b>: per-vertex attribute <code>base_normal</code> (Point3); optionally vertex quality = "
    "angle in degrees between the surface normal and the base normal (large on the flanks of the relief).<br><br>"
    "Method: one implicit heat-diffusion step of the normals (Gaussian scale = the parameter), solved by "
    "Eigen's conjugate gradients, or CHOLMOD's Cholesky factorization for wide scales; thesis section 4.4 (M. Kolomenkin, I. Shimshoni, A. Tal, CVPR 2009).";

const char* kRidgeInfo =
    "Draws <b>ridges</b> (where the surface is most sharply convex across a crest) and <b>valleys</b> "
    "(most sharply concave across a groove): the classic feature lines, for comparison with demarcating "
    "curves and relief edges.<br><br>"
    "<b>Output</b>: two new layers, <i>&lt;mesh&gt; – ridges</i> and <i>&lt;mesh&gt; – valleys</i> (edges; "
    "vertex quality = |curvature|; save them as OBJ).<br><br>"
    "Method: zero crossings of the derivative of the maximal (minimal) curvature along its own direction, "
    "from the curvature-derivative tensor; Y. Ohtake, A. Belyaev, H.-P. Seidel, <b>\"Ridge-valley lines on "
    "meshes via implicit surface fitting\"</b>, SIGGRAPH 2004; thesis sections 3.4 and 5.5.1.";

// Solves that do not reach their tolerance say so, with the solver, the residual and what to change.
void log_unconverged(FilterCall& call, const BaseNormals& b, double scale, double edge) {
  call.log(QString("Warning: the base-normal solve did not reach its tolerance (%1; asked: residual 0.001)%2. The "
                   "base surface is then less smooth than the base scale (%3 edge lengths) asks for. The result is "
                   "kept; a smaller \"Base surface scale\" converges faster.")
               .arg(QString::fromStdString(b.solve.summary()))
               .arg(b.solve.note.empty() ? QString() : QString(": ") + QString::fromStdString(b.solve.note))
               .arg(edge > 0 ? scale / edge : 0.0, 0, 'f', 1));
}

void relief_parameters(const MeshModel&, RichParameterList& par) {
  add_presmoothing(par);
  add_base_scale(par);
  add_length(par, "edge_smoothing", Length::automatic(), "Edge smoothing",
             "Smooths jagged edges (a Gaussian scale). auto: 0.8 edge lengths (as in the thesis); 0 turns it off.");
  par.addParam(RichBool("restrict", true, "Use the base surface for directions",
                        "Limits the edge directions to those the base surface allows; helps on noisy scans."));
  par.addParam(RichFloat("strong_error", 0.5f, "Model error, strong edges",
                         "Edges seed where the surface fits a step edge at least this well (0 perfect, 1 not at all)."));
  par.addParam(RichFloat("weak_error", 0.8f, "Model error, weak edges",
                         "Edges continue from the seeds where the fit is at least this good."));
  par.addParam(RichFloat("strong_angle", 0.f, "Steepness, strong edges (degrees)",
                         "Edges seed where the surface is tilted at least this much against the base surface. 0: "
                         "automatic (above the tilt the scan's measured noise gives and above most crossings' tilt; "
                         "the log says which)."));
  par.addParam(RichFloat("weak_angle", 0.f, "Steepness, weak edges (degrees)",
                         "Edges continue from the seeds where the tilt is at least this. 0: half the strong one."));
  add_min_length(par, ReliefEdgeParams::kDefaultMinLengthEdges);
  par.addParam(RichFloat("gap", float(ReliefEdgeParams::kDefaultLinkGapEdges), "Bridge gaps up to",
                         "Joins the ends of edge pieces that face each other across a gap of at most this many edge "
                         "lengths, so that outlines come out continuous. 0 leaves the pieces as found."));
  par.addParam(RichBool("per_vertex", true, "Write per-vertex results",
                        "Also store the per-vertex quantities on this mesh (relief_G, relief_direction, "
                        "relief_alpha, relief_fit_error, base_normal)."));
  par.addParam(RichBool("quality", false, "Vertex quality = curvature across the edge",
                        "Also put G (zero on the edges) into vertex quality."));
  add_lift(par);
}

ReliefEdgeParams read_relief_parameters(FilterCall& call) {
  ReliefEdgeParams p;
  p.presmoothing = read_presmoothing(call);
  p.base_scale = read_base_scale(call);
  p.edge_smoothing = read_length(call, "edge_smoothing", "Edge smoothing", 0, 100);
  p.restrict_orientation = read_bool(call, "restrict", "Use the base surface for directions");
  p.strong_error = read_float(call, "strong_error", "Model error, strong edges", 0, 1);
  p.weak_error = std::max(read_float(call, "weak_error", "Model error, weak edges", 0, 1), p.strong_error);
  p.strong_angle = read_float(call, "strong_angle", "Steepness, strong edges (degrees)", 0, 90) * kRadiansPerDegree;
  p.weak_angle = read_float(call, "weak_angle", "Steepness, weak edges (degrees)", 0, 90) * kRadiansPerDegree;
  p.min_length_edges = read_min_length(call);
  p.link_gap_edges = read_float(call, "gap", "Bridge gaps up to", 0, 20);
  p.progress = call.progress;
  return p;
}

// The run's thresholds and scales, and what to change when nothing passed.
void log_relief(FilterCall& call, const ReliefEdgeResult& r, const ReliefEdgeParams& p) {
  call.log(scale_summary(r.scale, r.noise, r.presmoothing, p.presmoothing));
  call.log(QString("Direction window %1 deg; hysteresis: strong = error <= %2 and tilt >= %3 deg, weak = error <= "
                   "%4 and tilt >= %5 deg (automatic: %9 deg from the crossings, %10 deg from the noise); base scale "
                   "%6 (solved by %7), edge smoothing %8.")
               .arg(r.window / kRadiansPerDegree, 0, 'f', 1)
               .arg(p.strong_error, 0, 'g', 3)
               .arg(r.strong_angle / kRadiansPerDegree, 0, 'f', 1)
               .arg(p.weak_error, 0, 'g', 3)
               .arg(r.weak_angle / kRadiansPerDegree, 0, 'f', 1)
               .arg(r.base_scale, 0, 'g', 4)
               .arg(QString::fromStdString(r.base.solve.summary()))
               .arg(r.edge_smoothing, 0, 'g', 4)
               .arg(r.automatic_angle / kRadiansPerDegree, 0, 'f', 1)
               .arg(r.noise_angle / kRadiansPerDegree, 0, 'f', 1));
  if (r.edges.segments.empty())
    call.log(QString("No relief edge passed the thresholds: the layer is empty (meshlabserver then reports \"Failed "
                     "saving\" for it). The steepest edge crossing seen tilts by %1 deg (strong threshold %2 deg): set "
                     "\"Steepness, strong edges\" below it, or raise \"Model error, strong edges\".")
                 .arg(r.steepest_crossing / kRadiansPerDegree, 0, 'f', 1)
                 .arg(r.strong_angle / kRadiansPerDegree, 0, 'f', 1));
  if (!r.base.solve.converged) log_unconverged(call, r.base, r.base_scale, r.scale.edge);
}

void apply_relief(FilterCall& call) {
  auto t0 = std::chrono::steady_clock::now();
  const ReliefEdgeParams p = read_relief_parameters(call);
  const bool per_vertex = read_bool(call, "per_vertex", "Write per-vertex results");
  const bool quality = read_bool(call, "quality", "Vertex quality = curvature across the edge");
  const double lift = read_lift(call);
  View view = view_of(call.mesh(), call.log);
  ReliefEdgeResult r = compute_relief_edges(surface_of(view), p);
  Polylines edges = r.edges;
  for (auto& s : edges.strength) s /= kRadiansPerDegree;  // layer quality in degrees
  const QString label = derived_label(call.mesh(), "relief edges");
  add_curve_layer(call.doc, label, edges, vcg::Color4b(0, 0, 0, 255), &r.curvature->normal, lift * r.scale.edge);
  if (per_vertex) {
    write_vertex_attribute(call.mesh().cm, view, "relief_G", r.G);
    write_vertex_vectors(call.mesh().cm, view, "relief_direction", r.direction);
    write_vertex_attribute(call.mesh().cm, view, "relief_alpha", r.alpha);
    write_vertex_attribute(call.mesh().cm, view, "relief_fit_error", r.fit_error);
    write_vertex_vectors(call.mesh().cm, view, "base_normal", r.base.normal);
  }
  if (quality) {
    call.mesh().updateDataMask(MeshModel::MM_VERTQUALITY);
    for_each_vertex(view, [&](int i, CVertexO* v) { v->Q() = float(r.G[i]); });
  }
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  call.log(QString("Relief edges: %1 segments in %2 curves (%6 gaps bridged), length %3, layer \"%4\"; %5 s.")
               .arg(thousands(static_cast<long long>(r.edges.segments.size())))
               .arg(thousands(static_cast<long long>(r.edges.chains().size())))
               .arg(r.edges.total_length(), 0, 'g', 5)
               .arg(label)
               .arg(secs, 0, 'f', 3)
               .arg(r.links));
  log_relief(call, r, p);
  log_curve_statistics(call, "relief edges", "relief_edges", r.edges, r.scale.edge, view.mesh.n_faces());
}

void base_parameters(const MeshModel&, RichParameterList& par) {
  add_base_scale(par);
  par.addParam(RichBool("quality", true, "Vertex quality = tilt against the base",
                        "Put the angle (degrees) between the surface normal and the base normal into vertex quality."));
}

void apply_base(FilterCall& call) {
  auto t0 = std::chrono::steady_clock::now();
  const Length scale = read_base_scale(call);
  const bool quality = read_bool(call, "quality", "Vertex quality = tilt against the base");
  View view = view_of(call.mesh(), call.log);
  const Surface surface = surface_of(view);
  const MeshScale& ms = surface.scale();
  scale.check("Base surface scale", 0.5, 10000, ms.edge);
  BaseNormalOptions o;
  o.scale = scale.resolve(ms.edge, automatic_base_scale(ms));
  o.progress = call.progress;
  const std::vector<Vec3>& n = surface.normals();
  BaseNormals b = estimate_base_normals(surface, n, o);
  write_vertex_vectors(call.mesh().cm, view, "base_normal", b.normal);
  if (quality) {
    call.mesh().updateDataMask(MeshModel::MM_VERTQUALITY);
    for_each_vertex(view, [&](int i, CVertexO* v) {
      v->Q() = float(std::acos(std::clamp(n[i].dot(b.normal[i]), -1.0, 1.0)) / kRadiansPerDegree);
    });
  }
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!b.solve.converged) log_unconverged(call, b, o.scale, ms.edge);
  call.log(QString("Base normals of %1 vertices at scale %2 (%5 edge lengths), solved by %3; %4 s.")
               .arg(thousands(view.mesh.n_vertices()))
               .arg(o.scale, 0, 'g', 4)
               .arg(QString::fromStdString(b.solve.summary()))
               .arg(secs, 0, 'f', 3)
               .arg(ms.edge > 0 ? o.scale / ms.edge : 0.0, 0, 'f', 1));
}

void ridge_parameters(const MeshModel&, RichParameterList& par) {
  par.addParam(RichFloat("threshold", 1.f, "Strength threshold",
                         "Keeps lines at least this curved, relative to the automatic threshold (1). Smaller values "
                         "show fainter lines, larger only the sharpest."));
  add_presmoothing(par);
  add_min_length(par, RidgeValleyParams::kDefaultMinLengthEdges);
  add_lift(par);
}

void apply_ridges(FilterCall& call) {
  auto t0 = std::chrono::steady_clock::now();
  RidgeValleyParams p;
  p.relative_threshold = read_float(call, "threshold", "Strength threshold", 0, 1000);
  p.presmoothing = read_presmoothing(call);
  p.min_length_edges = read_min_length(call);
  const double lift = read_lift(call);
  p.progress = call.progress;
  View view = view_of(call.mesh(), call.log);
  RidgeValleyResult r = compute_ridges_valleys(surface_of(view), p);
  const QString lr = derived_label(call.mesh(), "ridges"), lv = derived_label(call.mesh(), "valleys");
  add_curve_layer(call.doc, lr, r.ridges, vcg::Color4b(200, 30, 30, 255), &r.curvature->normal, lift * r.scale.edge);
  add_curve_layer(call.doc, lv, r.valleys, vcg::Color4b(30, 30, 200, 255), &r.curvature->normal, lift * r.scale.edge);
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  call.log(QString("Ridges: %1 segments (threshold %2); valleys: %3 segments (threshold %4); layers \"%5\", \"%6\"; "
                   "%7 s.")
               .arg(thousands(static_cast<long long>(r.ridges.segments.size())))
               .arg(r.ridge_threshold, 0, 'g', 4)
               .arg(thousands(static_cast<long long>(r.valleys.segments.size())))
               .arg(r.valley_threshold, 0, 'g', 4)
               .arg(lr)
               .arg(lv)
               .arg(secs, 0, 'f', 3));
  call.log(scale_summary(r.scale, r.noise, r.presmoothing, p.presmoothing));
  log_curve_statistics(call, "ridges", "ridges", r.ridges, r.scale.edge, view.mesh.n_faces());
  log_curve_statistics(call, "valleys", "valleys", r.valleys, r.scale.edge, view.mesh.n_faces());
  for (const auto& [name, layer, strongest, threshold] :
       {std::tuple{"ridge", &r.ridges, r.strongest_ridge, r.ridge_threshold},
        std::tuple{"valley", &r.valleys, r.strongest_valley, r.valley_threshold}})
    if (layer->segments.empty())
      call.log(QString("No %1 line is above the threshold: its layer is empty (meshlabserver then reports \"Failed "
                       "saving\" for it). The strongest %1 seen has |curvature| %2, %3 x the threshold %4: lower "
                       "\"Strength threshold\" below %3, or the minimum length.")
                   .arg(name)
                   .arg(strongest, 0, 'g', 3)
                   .arg(threshold > 0 ? p.relative_threshold * strongest / threshold : 0.0, 0, 'g', 3)
                   .arg(threshold, 0, 'g', 3));
}

}  // namespace

FilterSpec relief_edges_filter(int id) {
  return FilterSpec{id, "Relief Edges", kReliefInfo,
                    ml::FilterInterface::FilterClass(ml::FilterInterface::Normal | ml::FilterInterface::Layer),
                    MeshModel::MM_NONE, MeshModel::MM_VERTQUALITY, relief_parameters, apply_relief, true};
}

FilterSpec base_normals_filter(int id) {
  return FilterSpec{id, "Estimate Base Normals", kBaseInfo, ml::FilterInterface::Normal, MeshModel::MM_NONE,
                    MeshModel::MM_VERTQUALITY, base_parameters, apply_base};
}

FilterSpec ridges_valleys_filter(int id) {
  return FilterSpec{id, "Ridges and Valleys", kRidgeInfo,
                    ml::FilterInterface::FilterClass(ml::FilterInterface::Normal | ml::FilterInterface::Layer),
                    MeshModel::MM_NONE, MeshModel::MM_NONE, ridge_parameters, apply_ridges, true};
}

}  // namespace reliefkit::ml
