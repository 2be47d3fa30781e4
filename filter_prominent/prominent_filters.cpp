#include "prominent_filters.h"

#include <chrono>
#include <cmath>

#include "mesh_bridge.h"
#include "params.h"
#include "reliefkit/base/angles.h"
#include "reliefkit/prominent/prominent.h"

namespace reliefkit::ml {
namespace {


const char* kCitation =
    "M. Kolomenkin, I. Shimshoni, A. Tal, <b>\"Prominent field for shape processing and analysis of archaeological "
    "artifacts\"</b>, IJCV 2011; thesis chapter 6.";

const char* kFieldInfo =
    "Computes the <b>prominent field</b>: at every vertex the direction across the relief's features — across "
    "the outline of a stamped letter, across an engraved line, up the step of a figure — and, between the "
    "features, the smoothest field that joins them. It is what <i>Prominent Enhancement</i> and <i>Prominent "
    "Coloring</i> work along.<br><br>"
    "<b>Output</b> (on this layer): per-vertex attributes <code>prominent_direction</code> (unit vector), "
    "<code>prominent_confidence</code> (1 at the feature points that fix the field, 0 elsewhere), "
    "<code>prominent_strength</code> (how consistent the field is there, 0–1) and "
    "<code>prominent_curvature</code> (the curvature along the field); the field also replaces the curvature "
    "directions, so <i>Render &gt; Show Curvature</i> draws it: each vertex gets a short line across the "
    "features (half green, half red: the field has no sign).<br><br>"
    "Method: the prominent direction blends the relief direction (near relief edges) and the direction of "
    "largest curvature (near ridges and valleys) by how curved and how elongated the surface is there; feature "
    "points are those that fit a step edge and tilt against the smooth base surface, or are strongly and "
    "elongatedly curved. The field is one sparse solve for a <i>line field</i> (directions without sign, as "
    "curvature directions are), smooth between the feature points. ";

const char* kEnhanceInfo =
    "Makes a worn or noisy relief <b>easier to read</b>: the bumpy background is smoothed, the outlines of "
    "letters and figures are kept and steepened. The scan is not changed: the result is a new layer "
    "<i>&lt;mesh&gt; – enhanced</i> (vertex quality = how far each vertex moved up or down over the base "
    "surface, in mesh units).<br><br>"
    "Method: (1) a bilateral filter that averages the surface along the features but not across them (the "
    "prominent field says which way is across), then (2) an inverse-curvature flow along the prominent field, "
    "which steepens steps, moving every vertex along the base surface's normal; a vertex stops when it reaches "
    "the highest (lowest) point of its neighbourhood, so nothing rises above the relief's own top or sinks "
    "below its ground, or when it has moved as far as the scan's noise could hide (at strength 1: the steps "
    "come out no steeper than the scan supports) or restored what its curvature says wear took. Raise "
    "<i>Enhancement strength</i> to restore worn steps beyond what the scan shows (about 12 for a step eroded "
    "to five times its width). Set <i>Flow iterations</i> to 0 to denoise only; -1 stops automatically. ";

const char* kColoringInfo =
    "Colours the surface in grey by its <b>curvature across the features</b> (the prominent field): convex "
    "edges light, concave ones dark, the rest mid-grey — an artificial light that shows faint carvings, as "
    "archaeological drawings do. For comparison the same mapping can colour by mean or by maximal "
    "curvature.<br><br>"
    "<b>Output</b>: vertex colour (grey = 0.5 + arctan(&lambda; &kappa;) / &pi;) and vertex quality = "
    "&kappa; (1/length). &lambda; is automatic (1 / the 90th percentile of |&kappa;|), times <i>Contrast</i>: the "
    "same script gives the same picture for a coin in millimetres and a statue in metres. ";

const QStringList kFieldQuality = {"Prominent curvature (along the field)", "Confidence (feature points)",
                                   "Field strength", "None (keep vertex quality)"};
const QStringList kColoringCurvature = {"Prominent curvature (along the field)", "Mean curvature",
                                        "Maximal curvature (largest |curvature|)"};

// ---- Parameters every filter of the plugin shares (the field's) ----

void field_parameters(RichParameterList& par) {
  add_presmoothing(par);
  add_base_scale(par);
  par.addParam(RichFloat("theta", float(ProminentFieldParams::kDefaultTheta), "Feature threshold (theta)",
                         "Which points count as features that fix the field (the thesis' theta, default 2). Larger "
                         "values take fainter features (each threshold is scaled by 2 / theta), smaller values only "
                         "the clearest."));
}

ProminentFieldParams read_field_parameters(FilterCall& call) {
  ProminentFieldParams p;
  p.presmoothing = read_presmoothing(call);
  p.base_scale = read_base_scale(call);
  p.theta = read_float(call, "theta", "Feature threshold (theta)", 0.01, 100);
  p.progress = call.progress;
  return p;
}

void log_field(FilterCall& call, const ProminentFieldResult& f, const ProminentFieldParams& p) {
  const long long nv = static_cast<long long>(f.field.size());
  call.log(QString("Prominent field of %1 vertices: %2 feature points (%3 ridge/valley-like, %4 relief-edge-like) fix "
                   "it; solved by %5; field stage %6 s.")
               .arg(thousands(nv))
               .arg(thousands(f.ridge_points + f.edge_points))
               .arg(thousands(f.ridge_points))
               .arg(thousands(f.edge_points))
               .arg(QString::fromStdString(f.solve.summary()))
               .arg(f.field_seconds, 0, 'f', 2));
  call.log(scale_summary(f.scale, f.noise, f.presmoothing, p.presmoothing));
  call.log(QString("Feature thresholds (theta %1): curvature %2 (%3 per edge length) for ridges/valleys; tilt %4 deg "
                   "against the base surface (scale %5 edge lengths) for relief edges.")
               .arg(p.theta, 0, 'g', 3)
               .arg(f.curvature_threshold * 2 / p.theta, 0, 'g', 3)
               .arg(f.curvature_threshold * 2 / p.theta * f.scale.edge, 0, 'g', 3)
               .arg(f.tilt_threshold * 2 / p.theta / kRadiansPerDegree, 0, 'f', 1)
               .arg(f.scale.edge > 0 ? f.base_scale / f.scale.edge : 0.0, 0, 'f', 1));
  if (f.ridge_points + f.edge_points == 0)
    call.log("Warning: no vertex passed the feature thresholds, so nothing fixes the field: it follows the local "
             "directions. Raise \"Feature threshold (theta)\" to take fainter features.");
  if (f.unreached > 0)
    call.log(QString("%1 vertices lie in parts no feature reaches: the field there is the local prominent direction.")
                 .arg(thousands(f.unreached)));
  if (!f.solve.converged)
    call.log(QString("Warning: the field's solve did not reach its tolerance (%1): the field is kept, a little less "
                     "smooth than asked.")
                 .arg(QString::fromStdString(f.solve.summary())));
}

// ---- Prominent Field ----

void field_filter_parameters(const MeshModel&, RichParameterList& par) {
  field_parameters(par);
  par.addParam(RichEnum("quality", 0, kFieldQuality, "Vertex quality",
                        "What to store in vertex quality (for Colorize by vertex quality)."));
  par.addParam(RichBool("curvature_dir", true, "Show in Show Curvature",
                        "Replace the per-vertex curvature directions by the field, so that Render > Show Curvature "
                        "draws it (the curvature values become the curvature along and across the field)."));
}

void apply_field(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const ProminentFieldParams p = read_field_parameters(call);
  const int quality = read_enum(call, "quality", "Vertex quality", kFieldQuality.size());
  const bool curvature_dir = read_bool(call, "curvature_dir", "Show in Show Curvature");
  View view = view_of(call.mesh(), call.log);
  const ProminentFieldResult f = compute_prominent_field(surface_of(view), p);
  const Curvature& c = *f.curvature;
  const int nv = view.mesh.n_vertices();
  std::vector<double> kp(nv), kq(nv);
  std::vector<Vec3> across(nv);
  for (int v = 0; v < nv; ++v) {
    across[v] = c.normal[v].cross(f.field[v]);
    kp[v] = c.normal_curvature(v, f.field[v]);
    kq[v] = c.normal_curvature(v, across[v]);
  }
  write_vertex_vectors(call.mesh().cm, view, "prominent_direction", f.field);
  write_vertex_attribute(call.mesh().cm, view, "prominent_confidence", f.beta);
  write_vertex_attribute(call.mesh().cm, view, "prominent_strength", f.strength);
  write_vertex_attribute(call.mesh().cm, view, "prominent_curvature", kp);
  if (curvature_dir) {
    call.mesh().updateDataMask(MeshModel::MM_VERTCURVDIR);
    for_each_vertex(view, [&](int i, CVertexO* v) {
      const Vec3& s = f.field[i];
      // Show Curvature draws PD1 green and PD2 red from the vertex: a line field is drawn as one
      // segment through the vertex, half each colour.
      v->PD1() = Point3m(Scalarm(s.x()), Scalarm(s.y()), Scalarm(s.z()));
      v->PD2() = Point3m(Scalarm(-s.x()), Scalarm(-s.y()), Scalarm(-s.z()));
      v->K1() = Scalarm(kp[i]);
      v->K2() = Scalarm(kq[i]);
    });
  }
  if (quality != 3) {
    call.mesh().updateDataMask(MeshModel::MM_VERTQUALITY);
    const std::vector<double>& q = quality == 0 ? kp : quality == 1 ? f.beta : f.strength;
    for_each_vertex(view, [&](int i, CVertexO* v) { v->Q() = Scalarm(q[i]); });
  }
  log_field(call, f, p);
  call.log(QString("Wrote prominent_direction, prominent_confidence, prominent_strength, prominent_curvature%1%2; "
                   "%3 s in all.")
               .arg(curvature_dir ? ", the curvature directions (Render > Show Curvature)" : "")
               .arg(quality != 3 ? QString(", vertex quality = ") + kFieldQuality[quality].toLower() : QString())
               .arg(seconds_since(t0), 0, 'f', 2));
}

// ---- Prominent Enhancement ----

void enhance_parameters(const MeshModel&, RichParameterList& par) {
  add_length(par, "sigma_c", Length::automatic(), "Smoothing scale (sigma_c)",
             "How far the bilateral filter averages (Gaussian scale; neighbours within twice it count), in edge "
             "lengths. auto: 1.5 edge lengths. Larger removes coarser bumps but may round small letters.");
  par.addParam(RichInt("bilateral_iterations", EnhanceParams::kDefaultBilateralIterations, "Bilateral iterations",
                       "How many times step 1 (smoothing along the features) is applied. 0 skips it."));
  par.addParam(RichInt("flow_iterations", -1, "Flow iterations",
                       "Step 2 (steepening the features): -1 runs until every vertex has stopped (automatic; at most "
                       "100 iterations), 0 skips it (denoise only), a positive number stops after that many."));
  par.addParam(RichFloat("flow_step", 0.2f, "Flow step",
                         "The largest move of a vertex per flow iteration, in edge lengths."));
  par.addParam(RichFloat("strength", 1.f, "Enhancement strength",
                         "How far step 2 may move a vertex. 1: as far as the scan's noise could hide (a third of its "
                         "standard deviation) — sharper than the smoothed scan, no steeper than the scan supports. "
                         "Larger values trade faithfulness for legibility: about 12 restores a worn step (steeper "
                         "than the scan shows, an illustration rather than a measurement). No vertex ever passes "
                         "the highest or lowest point of its neighbourhood."));
  field_parameters(par);
}

void apply_enhance(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  EnhanceParams p;
  p.spatial_scale = read_length(call, "sigma_c", "Smoothing scale (sigma_c)", 0.1, 100);
  p.bilateral_iterations = read_int(call, "bilateral_iterations", "Bilateral iterations", 0, 100);
  p.flow_iterations = read_int(call, "flow_iterations", "Flow iterations", -1, 10000);
  p.flow_step = read_float(call, "flow_step", "Flow step", 0.001, 1);
  p.strength = read_float(call, "strength", "Enhancement strength", 0.01, 100);
  p.field = read_field_parameters(call);
  p.progress = call.progress;
  View view = view_of(call.mesh(), call.log);
  const EnhanceResult r = enhance_relief(surface_of(view), p);
  const QString label = derived_label(call.mesh(), "enhanced");
  add_surface_layer(call.doc, label, call.mesh(), view, r.positions, &r.height_change);
  log_field(call, r.field, p.field);
  const double h = r.field.scale.edge;
  double largest = 0;
  for (double u : r.height_change) largest = std::max(largest, std::abs(u));
  call.log(QString("Enhanced surface in layer \"%1\": bilateral filter %2 x at sigma_c %3 (%4 edge lengths; %5 s); "
                   "inverse-curvature flow %6 iterations (%7; %8 s), %9 vertices stopped at their local height "
                   "extremum (within %10 edge lengths), %13 at the height their curvature explains (strength %14), "
                   "largest height change %11 edge lengths; %12 s in all.")
               .arg(label)
               .arg(p.bilateral_iterations)
               .arg(r.spatial_scale, 0, 'g', 4)
               .arg(h > 0 ? r.spatial_scale / h : 0.0, 0, 'f', 2)
               .arg(r.bilateral_seconds, 0, 'f', 2)
               .arg(r.flow_iterations)
               .arg(p.flow_iterations < 0 ? (r.converged ? "automatic stop" : "not settled after 100: stopped")
                                          : "as asked")
               .arg(r.flow_seconds, 0, 'f', 2)
               .arg(thousands(r.at_extremum))
               .arg(h > 0 ? r.extremum_radius / h : 0.0, 0, 'f', 1)
               .arg(h > 0 ? largest / h : 0.0, 0, 'f', 2)
               .arg(seconds_since(t0), 0, 'f', 2)
               .arg(thousands(r.at_curvature_cap))
               .arg(p.strength, 0, 'g', 3));
}

// ---- Prominent Coloring ----

void coloring_parameters(const MeshModel&, RichParameterList& par) {
  par.addParam(RichEnum("curvature", 0, kColoringCurvature, "Colour by",
                        "Prominent curvature (the thesis' prominent coloring) shows edges crisply and the rest smooth; "
                        "mean and maximal curvature are the classic colourings, for comparison."));
  par.addParam(RichFloat("contrast", 1.f, "Contrast (lambda)",
                         "Multiplies the automatic lambda of grey = 0.5 + arctan(lambda kappa) / pi; larger is "
                         "harsher. Must be positive."));
  field_parameters(par);
}

void apply_coloring(FilterCall& call) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto which = static_cast<ColoringCurvature>(read_enum(call, "curvature", "Colour by", kColoringCurvature.size()));
  const double contrast = read_float(call, "contrast", "Contrast (lambda)", 1e-6, 1e6);
  const ProminentFieldParams p = read_field_parameters(call);
  View view = view_of(call.mesh(), call.log);
  const Surface surface = surface_of(view);
  ColoringResult col;
  if (which == ColoringCurvature::Prominent) {
    const ProminentFieldResult f = compute_prominent_field(surface, p);
    col = curvature_coloring(*f.curvature, &f.field, f.scale.counts, which, contrast);
    log_field(call, f, p);
  } else {
    const ScaledCurvature sc = begin_curve_filter(surface, p);
    col = curvature_coloring(*sc.curvature, nullptr, sc.scale.counts, which, contrast);
    call.log(scale_summary(sc.scale, sc.noise, sc.presmoothing, p.presmoothing));
  }
  write_grey(call.mesh(), view, col.grey, col.curvature);
  call.log(QString("%1 coloring of %2 vertices: lambda %3 (contrast %4 x automatic); vertex quality = the curvature; "
                   "%5 s.")
               .arg(kColoringCurvature[int(which)].section(' ', 0, 0))
               .arg(thousands(view.mesh.n_vertices()))
               .arg(col.lambda, 0, 'g', 4)
               .arg(contrast, 0, 'g', 3)
               .arg(seconds_since(t0), 0, 'f', 2));
}

}  // namespace

FilterSpec prominent_field_filter(int id) {
  return FilterSpec{id,
                    "Prominent Field",
                    QString(kFieldInfo) + kCitation,
                    ml::FilterInterface::Normal,
                    MeshModel::MM_NONE,
                    MeshModel::MM_VERTCURVDIR | MeshModel::MM_VERTQUALITY,
                    field_filter_parameters,
                    apply_field};
}

FilterSpec prominent_enhancement_filter(int id) {
  return FilterSpec{id,
                    "Prominent Enhancement",
                    QString(kEnhanceInfo) + kCitation,
                    ml::FilterInterface::FilterClass(ml::FilterInterface::Smoothing | ml::FilterInterface::Layer),
                    MeshModel::MM_NONE,
                    MeshModel::MM_NONE,
                    enhance_parameters,
                    apply_enhance,
                    true};
}

FilterSpec prominent_coloring_filter(int id) {
  return FilterSpec{id,
                    "Prominent Coloring",
                    QString(kColoringInfo) + "Method: " + kCitation,
                    ml::FilterInterface::VertexColoring,
                    MeshModel::MM_NONE,
                    MeshModel::MM_VERTCOLOR | MeshModel::MM_VERTQUALITY,
                    coloring_parameters,
                    apply_coloring};
}

}  // namespace reliefkit::ml
