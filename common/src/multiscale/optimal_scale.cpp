#include "reliefkit/multiscale/optimal_scale.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>

#include "reliefkit/base/cubic_form.h"
#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/memory.h"
#include "reliefkit/multiscale/scale_selection.h"
#include "reliefkit/base/smoothing.h"

namespace reliefkit {

void OptimalScaleOptions::validate() const {
  require_range(min_scale_edges, "Smallest scale (edge lengths)", 0.25, 1000);
  require_range(max_scale_edges, "Largest scale (edge lengths)", min_scale_edges, 1000);
  require_range(levels_per_octave, "Levels per octave", 1, 16);
  // A single peak of t^γ f needs γ < 1.5 (ridges, eq. 5.11) and γ < 1.3 (relief edges, eq. 5.15).
  if (gamma != 0) require_range(gamma, "Scale normalisation gamma", 0.1, curve == ScaleStrength::ReliefEdges ? 1.29 : 1.45);
  require_range(fill_weight, "Fill weight a f_max", 0, 1e6);
  if (fill_smoothness != 0) require_range(fill_smoothness, "Fill smoothness", 1e-6, 1e6);
  require_range(featureless_pull, "Featureless pull", 1e-9, 1e3);
  require_range(max_scale_growth, "Largest scale growth", 0, 1e3);
  require_range(final_smoothing_edges, "Final smoothing (edge lengths)", 0, 100);
}

double ridge_strength(double k1, double k2) { return std::max(std::abs(k1), std::abs(k2)); }

Mat3 shape_tensor(const Curvature& c, int v) {
  return c.k1[v] * c.dir1[v] * c.dir1[v].transpose() + c.k2[v] * c.dir2[v] * c.dir2[v].transpose();
}

double signed_ridge_strength_over_base(const Curvature& c, int v, const Mat3& base) {
  const Mat3 D = shape_tensor(c, v) - base;
  const Vec3 &d1 = c.dir1[v], &d2 = c.dir2[v];
  const double a = d1.dot(D * d1), b = d1.dot(D * d2), cc = d2.dot(D * d2);
  const double m = 0.5 * (a + cc), r = std::hypot(0.5 * (a - cc), b);
  return m >= 0 ? m + r : m - r;
}

double ridge_strength_over_base(const Curvature& c, int v, const Mat3& base) {
  return std::abs(signed_ridge_strength_over_base(c, v, base));
}

double relief_edge_strength(const CurvatureDerivative& C) {
  Vec2 u[3];
  const int n = cubic_form_maxima(C, u);
  double best = 0;
  for (int i = 0; i < n; ++i) best = std::max(best, C.along(u[i].x(), u[i].y()));
  return best;
}

void place_on_mesh(const TriMesh& mesh, Polylines& curves) {
  const int np = static_cast<int>(curves.points.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < np; ++i) {
    const auto [a, b] = curves.point_edge[i];
    const double w = curves.point_weight[i];
    curves.points[i] = (1 - w) * mesh.vertices[a] + w * mesh.vertices[b];
  }
}

namespace {

// The levels of a run, from the options and the mesh's scale: σ in edge lengths and in mesh units,
// log σ (edge lengths) for bracketing a scale between them, t = σ² (edge lengths²) for eq. 5.2.
struct Levels {
  std::vector<double> edges, sigma, log_edges, t;
  bool lowered = false;  // the largest scale was lowered for a small object
  int size() const { return static_cast<int>(edges.size()); }
};

std::vector<double> geometric_series(double lo, double hi, int per_octave) {
  std::vector<double> e;
  const double step = std::pow(2.0, 1.0 / per_octave);
  for (double x = lo; x <= hi * (1 + 1e-9); x *= step) e.push_back(x);
  if (e.back() < hi * (1 - 1e-9)) e.push_back(hi);  // the range's end is always a level
  return e;
}

Levels plan_levels(const MeshScale& scale, const OptimalScaleOptions& opt) {
  const double h = scale.edge;
  if (!(h > 0) || !std::isfinite(h)) throw InputError("The mesh has no edge of positive length: no scale to measure.");
  // The base surface is the largest scale doubled; a Gaussian of that size must fit on the object.
  const double size_edges = scale.object_size / h;
  if (opt.min_scale_edges * kMinObjectScales > size_edges)
    throw InputError("The mesh is only " + std::to_string(int(size_edges)) +
                     " edge lengths across: too small for a scale range starting at " +
                     std::to_string(opt.min_scale_edges).substr(0, 4) +
                     " edge lengths (multi-scale analysis needs an object at least " +
                     std::to_string(int(kMinObjectScales)) + " times the smallest scale). Nothing was changed.");
  const double fitted_max =
      std::min(opt.max_scale_edges, size_edges / (opt.max_scale_auto ? kAutoMaxScaleObjectFraction : kMinObjectScales));
  Levels l;
  l.edges = geometric_series(opt.min_scale_edges, std::max(opt.min_scale_edges, fitted_max), opt.levels_per_octave);
  l.lowered = fitted_max < opt.max_scale_edges;
  for (double e : l.edges) {
    l.sigma.push_back(e * h);
    l.log_edges.push_back(std::log(e));
    l.t.push_back(e * e);
  }
  return l;
}

// The scale space of the levels. Ridges & valleys: two implicit steps per doubling of the
// diffusion time (the scale space's default is 4) — the levels feed a peak search. Measured on the
// unit test's noisy cylinder: F1 0.960 -> 0.985, and 25.3 -> 19.5 s at 1 M faces. Relief edges
// keep 4: their strength is a third derivative, where backward Euler's kernel differs most from a
// Gaussian (with 2 the noisy disc reliefs fell from 0.96-0.99 to 0.71-0.88 recall).
ScaleSpaceOptions level_space_options(const OptimalScaleOptions& opt) {
  ScaleSpaceOptions so;
  so.substeps = opt.curve == ScaleStrength::ReliefEdges ? ScaleSpaceOptions().substeps : kOptimalScaleSubsteps;
  so.stepping = opt.stepping;
  return so;
}

// The base surface (kRidgeBaseFactor / kReliefBaseFactor x the largest scale): its shape operator
// (ridges & valleys measure the feature's curvature over it; relief edges G), its normals (the
// relief edges' tilt) and its positions (the shrink rate of the optimally smoothed surface).
struct BaseSurface {
  std::vector<Mat3> shape;
  std::vector<Vec3> position, normal;  // with the optimally smoothed surface only
  double tau = 0;                      // its diffusion time (mesh units²)
  ScaleSpaceReport space;
};

BaseSurface base_surface(const Surface& surface, const Levels& levels, const OptimalScaleOptions& opt) {
  const bool relief = opt.curve == ScaleStrength::ReliefEdges;
  const double factor = relief ? kReliefBaseFactor : kRidgeBaseFactor;
  BaseSurface b;
  b.tau = 0.5 * factor * factor * levels.sigma.back() * levels.sigma.back();
  ScaleSpaceOptions bo = level_space_options(opt);
  bo.substeps = 2;
  if (relief) {
    // Relief edges' base (4 x the largest scale) is only read for its normals, low-frequency
    // shape and shrink rate: one backward-Euler step, by Cholesky (at 1 M faces: 4.7 s; two
    // steps by conjugate gradients, 300-470 iterations each, took 9.0 s).
    bo.substeps = 1;
    bo.method = SolverMethod::Direct;
  }
  const int nv = surface.n_vertices();
  b.space = scale_space(surface, {factor * levels.sigma.back()}, bo, [&](int, const Surface& smoothed) {
    if (opt.progress) opt.progress(2, "Optimal scale: base surface");
    const std::shared_ptr<const Curvature> curvature = smoothed.curvature(CurvatureEstimator::Jet, false);
    const Curvature& c = *curvature;
    sized(b.shape, size_t(nv));
#pragma omp parallel for schedule(static)
    for (int v = 0; v < nv; ++v) b.shape[v] = shape_tensor(c, v);
    if (opt.smoothed_surface) b.position = smoothed.mesh().vertices, b.normal = c.normal;
  });
  return b;
}

// The strength f of every vertex at every level, signed (> 0 convex) and made unit-free (x h or
// h²), vertex-major: s[v * levels + k]; and, for the optimally smoothed surface, each level's
// displacements (level-major, single precision).
struct LevelStrengths {
  std::vector<double> s;
  std::vector<Eigen::Vector3f> displacement;
  ScaleSpaceReport space;
};

LevelStrengths level_strengths(const Surface& surface, const Levels& levels, const OptimalScaleOptions& opt,
                               const std::vector<Mat3>& base) {
  const bool relief = opt.curve == ScaleStrength::ReliefEdges;
  const TriMesh& mesh = surface.mesh();
  const int nl = levels.size(), nv = mesh.n_vertices();
  const double h = surface.scale().edge, norm = relief ? h * h : h;
  LevelStrengths ls;
  sized(ls.s, size_t(nv) * size_t(nl));
  if (opt.smoothed_surface) sized(ls.displacement, size_t(nv) * size_t(nl));
  ls.space = scale_space(surface, levels.sigma, level_space_options(opt), [&](int k, const Surface& smoothed) {
    if (opt.progress) opt.progress(5 + 80 * k / nl, "Optimal scale: scale space and strengths");
    const std::shared_ptr<const Curvature> curvature = smoothed.curvature(CurvatureEstimator::Jet, relief);
    const Curvature& c = *curvature;
    const std::vector<Vec3>& x = smoothed.mesh().vertices;
#pragma omp parallel for schedule(static)
    for (int v = 0; v < nv; ++v) {
      const double f = relief ? relief_edge_strength(c.dcurv[v]) : signed_ridge_strength_over_base(c, v, base[v]);
      ls.s[size_t(v) * nl + k] = std::isfinite(f) ? norm * f : 0.0;
      if (opt.smoothed_surface) ls.displacement[size_t(k) * nv + v] = (x[v] - mesh.vertices[v]).cast<float>();
    }
  });
  return ls;
}

// What noise alone reaches at each level: the 99th percentile of t^γ |f| on a noise patch (the
// surface is one).
std::vector<double> noise_percentiles(const LevelStrengths& ls, const Levels& levels, double gamma) {
  const int nl = levels.size(), nv = static_cast<int>(ls.s.size() / size_t(nl));
  std::vector<double> noise(static_cast<size_t>(nl)), level(static_cast<size_t>(nv));
  for (int k = 0; k < nl; ++k) {
    for (int v = 0; v < nv; ++v) level[v] = std::pow(levels.t[k], gamma) * std::abs(ls.s[size_t(v) * nl + k]);
    noise[k] = percentile(level, 0.99);
  }
  return noise;
}

// What noise alone gives at each level: the 99th percentile of t^γ f on a patch carrying the
// scan's estimated noise (same scales, same curve type; the patch, at least kMinScaleNoise, is
// kept in `out` for the run's later simulations). A selection weaker than what noise reaches at
// its scale anchors nothing. (The median of the scan itself was tried as the noise's strength
// first: on a relief that covers most of the surface, like the coin, it is a feature's, and the
// coin's valleys all fell below the threshold it set. Subtracting the noise from every level's
// strength before selecting biased the selection towards large scales: the disc reliefs' steps
// selected twice their width and lost 20 % recall.)
void measure_noise_floor(const Surface& surface, const OptimalScaleOptions& opt, int nl, OptimalScale& out) {
  out.noise = surface.noise();
  out.noise_patch = make_noise_patch(std::max(out.noise.relative, kMinScaleNoise), noise_patch_cells(surface.n_faces()));
  const Surface& patch = *out.noise_patch.surface;
  OptimalScaleOptions po = opt;
  po.smoothed_surface = false, po.progress = nullptr;
  // The patch's own levels (a small patch may lower the largest scale); the scan's levels above
  // them take the patch's largest.
  const Levels levels = plan_levels(patch.scale(), po);
  const std::vector<Mat3> base =
      po.curve == ScaleStrength::RidgesValleys ? base_surface(patch, levels, po).shape : std::vector<Mat3>();
  const std::vector<double> noise = noise_percentiles(level_strengths(patch, levels, po, base), levels, opt.effective_gamma());
  out.level_noise.assign(size_t(nl), 0.0);
  for (int k = 0; k < nl; ++k) out.level_noise[k] = noise[std::min<size_t>(k, noise.size() - 1)];
  out.strength_floor = *std::max_element(out.level_noise.begin(), out.level_noise.end());
}

// Eq. 5.2 per vertex: select_scale refines the best level in log t; the strength is the best
// sample's, the sign its f's. Returns the selections in edge lengths (0: none).
std::vector<double> select_scales(const LevelStrengths& ls, const Levels& levels, double gamma, double h,
                                  OptimalScale& out) {
  const int nl = levels.size(), nv = static_cast<int>(ls.s.size() / size_t(nl));
  sized(out.selected, size_t(nv));
  sized(out.strength, size_t(nv));
  out.sign.assign(size_t(nv), 0);
  std::vector<double> selected_edges(static_cast<size_t>(nv), 0.0);
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const double* sv = ls.s.data() + size_t(v) * nl;
    std::vector<double> f(nl);
    for (int k = 0; k < nl; ++k) f[k] = std::abs(sv[k]);
    const double ts = select_scale(levels.t, f.data(), 1, gamma);
    selected_edges[v] = ts > 0 ? std::sqrt(ts) : 0.0;
    out.selected[v] = selected_edges[v] * h;
    double best = 0;
    int best_k = 0;
    for (int k = 0; k < nl; ++k)
      if (std::pow(levels.t[k], gamma) * f[k] > best) best = std::pow(levels.t[k], gamma) * f[k], best_k = k;
    out.strength[v] = best;
    out.sign[v] = static_cast<signed char>(sv[best_k] > 0 ? 1 : sv[best_k] < 0 ? -1 : 0);
  }
  out.own_strength = out.strength;
  out.own_sign = out.sign;
  std::vector<double> positive;
  positive.reserve(size_t(nv));
  for (int v = 0; v < nv; ++v)
    if (out.strength[v] > 0) positive.push_back(out.strength[v]);
  out.strength_ref = percentile(positive, 0.999);
  return selected_edges;
}

// The vertices whose selection may anchor a scale. Vertices within kBorderRings rings of a
// boundary see one side only (an open scan's rim selected the finest scale at twice any feature's
// strength on the test cylinder): they neither anchor nor dominate. A selection at the top of the
// range is no peak (the strength still grew there: a feature's far tail, or a shape wider than the
// range). And a selection must be stronger than noise at its scale (level_noise, interpolated in
// log σ) by kSignificance.
std::vector<char> anchor_candidates(const MeshTopology& topo, const Levels& levels, const OptimalScale& out,
                                    const std::vector<double>& selected_edges) {
  const int nv = static_cast<int>(selected_edges.size());
  std::vector<char> eligible(static_cast<size_t>(nv), 1);
  for (int v = 0; v < nv; ++v)
    if (topo.border.offset[v + 1] > topo.border.offset[v]) eligible[v] = 0;
  for (int ring = 0; ring < kBorderRings; ++ring) {
    std::vector<char> next = eligible;
    for (int v = 0; v < nv; ++v)
      if (!eligible[v])
        for (int k = topo.ring.offset[v]; k < topo.ring.offset[v + 1]; ++k) next[topo.ring.vertex[k]] = 0;
    eligible.swap(next);
  }
  for (int v = 0; v < nv; ++v)
    if (selected_edges[v] >= levels.edges.back() * (1 - 1e-9)) eligible[v] = 0;
  for (int v = 0; v < nv; ++v) {
    if (!(selected_edges[v] > 0)) continue;
    const ScaleBracket b = bracket_scale(levels.log_edges, std::log(selected_edges[v]));
    const double noise = b.mix(out.level_noise[b.lower], out.level_noise[b.upper]);
    if (!(out.own_strength[v] > kSignificance * noise)) eligible[v] = 0;
  }
  return eligible;
}

// Each vertex takes the selection (scale, strength) of the strongest vertex whose reach —
// `reach` times its scale, along mesh edges — covers it: a feature's footprint gets the scale
// of its centre. Jacobi sweeps of a bounded propagation, in edge lengths.
void dominant_scale(const Surface& surface, double h, double reach,
                    std::vector<double>& sigma_edges, std::vector<double>& strength, std::vector<signed char>& sign) {
  const TriMesh& mesh = surface.mesh();
  const MeshTopology& topo = surface.topology();
  const int nv = mesh.n_vertices();
  struct Best { double strength, sigma, left; signed char sign; };  // left: remaining reach, edge lengths
  std::vector<Best> cur(static_cast<size_t>(nv)), next;
  double max_reach = 0;
  for (int v = 0; v < nv; ++v) {
    cur[v] = {strength[v], sigma_edges[v], sigma_edges[v] > 0 ? reach * sigma_edges[v] : 0.0, sign[v]};
    max_reach = std::max(max_reach, cur[v].left);
  }
  next = cur;
  for (int sweep = 0; sweep < int(std::ceil(max_reach)) + 1; ++sweep) {
    int changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed)
    for (int v = 0; v < nv; ++v) {
      Best b = cur[v];
      for (int k = topo.ring.offset[v]; k < topo.ring.offset[v + 1]; ++k) {
        const int u = topo.ring.vertex[k];
        const Best& c = cur[u];
        if (!(c.strength > b.strength) || !(c.left > 0)) continue;
        const double step = (mesh.vertices[u] - mesh.vertices[v]).norm() / h;
        if (step <= c.left) b = {c.strength, c.sigma, c.left - step, c.sign}, ++changed;
      }
      next[v] = b;
    }
    cur.swap(next);
    if (changed == 0) break;
  }
  for (int v = 0; v < nv; ++v) strength[v] = cur[v].strength, sigma_edges[v] = cur[v].sigma, sign[v] = cur[v].sign;
}

// Sect. 2b of the header: anchors are candidates whose own selection is (nearly) the strongest
// that reaches them (feature centres); their selections then cover their footprints, and what no
// anchor reaches is featureless (the fill sends it to the largest scale). Also the strongest
// feature within bank_reach of each vertex (bank_strength, bank_sign).
void dominant_selection(const Surface& surface, const OptimalScaleOptions& opt, const Levels& levels,
                        std::vector<double>& selected_edges, OptimalScale& out) {
  const int nv = surface.n_vertices();
  const double h = out.scale.edge;
  const std::vector<char> eligible = anchor_candidates(surface.topology(), levels, out, selected_edges);
  std::vector<double> sel = selected_edges, str = out.strength;
  std::vector<signed char> sg = out.sign;
  for (int v = 0; v < nv; ++v)
    if (!eligible[v]) str[v] = 0, sel[v] = 0;
  dominant_scale(surface, h, opt.dominant_reach, sel, str, sg);
  for (int v = 0; v < nv; ++v) {
    const bool anchor = eligible[v] && out.own_strength[v] > 0 && out.own_strength[v] >= kAnchorShare * str[v];
    if (!anchor) selected_edges[v] = 0, out.strength[v] = 0, out.sign[v] = 0;
  }
  out.bank_strength = out.strength;
  out.bank_sign = out.sign;
  std::vector<double> bank_sel = selected_edges;
  dominant_scale(surface, h, opt.dominant_reach, selected_edges, out.strength, out.sign);
  dominant_scale(surface, h, opt.bank_reach, bank_sel, out.bank_strength, out.bank_sign);
  for (int v = 0; v < nv; ++v) out.selected[v] = selected_edges[v] * h;
}

// Sect. 4: each vertex at its own scale. Each level sits τ H n inside the input (diffusion
// shrinks a curved surface). Where the scale varies, neighbours from different levels would show
// that as a step — amplified by σ² in the normalised strengths. So every vertex is brought to the
// largest level's shrinking: x = x_0 + d(σ_v) + (τ_max − τ_v) r_v, with the shrink rate r = −H n
// measured as the base's displacement from the largest level over τ_base − τ_max — a difference
// of two smooth surfaces (estimating H n from curvature left a few per cent of noise per vertex,
// and curves with it). Then the light final smoothing removes the seams.
void assemble_smoothed(const Surface& surface, const OptimalScaleOptions& opt, const Levels& levels,
                       const BaseSurface& base, LevelStrengths& ls, OptimalScale& out) {
  const TriMesh& mesh = surface.mesh();
  const int nl = levels.size(), nv = mesh.n_vertices();
  const double h = out.scale.edge;
  const std::vector<Eigen::Vector3f>& disp = ls.displacement;
  sized(out.smoothed, size_t(nv));
  const double tau_max = 0.5 * levels.sigma.back() * levels.sigma.back();
  const double u_min = levels.log_edges.front(), u_max = levels.log_edges.back();
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const double sigma = out.smoothed_ratio * out.sigma[v];
    const double u = sigma > 0 ? std::clamp(std::log(sigma / h), u_min, u_max) : u_min;
    const ScaleBracket b = bracket_scale(levels.log_edges, u);
    const int k = b.lower, k1 = b.upper;
    const double tau = 0.5 * b.mix(levels.sigma[k] * levels.sigma[k], levels.sigma[k1] * levels.sigma[k1]);
    const float w = float(b.weight);
    const Eigen::Vector3f d = (1 - w) * disp[size_t(k) * nv + v] + w * disp[size_t(k1) * nv + v];
    const Vec3 top = mesh.vertices[v] + disp[size_t(nl - 1) * nv + v].cast<double>();
    const Vec3 rate = (base.position[v] - top) / (base.tau - tau_max);
    out.smoothed[v] = mesh.vertices[v] + d.cast<double>() + (tau_max - tau) * rate;
  }
  std::vector<Eigen::Vector3f>().swap(ls.displacement);
  smooth_positions(surface, opt.final_smoothing_edges * h, out.smoothed);
}

// Eq. 5.3 as a sparse SPD system in u = log(σ / h); see the header.
std::vector<double> fill_scales(const Surface& surface, const OptimalScaleOptions& opt,
                                const std::vector<double>& selected_edges, const std::vector<double>& strength,
                                double floor, double ref, double u_min, double u_max, SolveReport& report) {
  const int nv = surface.n_vertices();
  LaplacianOptions lo;
  lo.clamp_negative = true;  // an M-matrix: the filled scale stays within the levels' range
  const LaplacianResult& lap = surface.laplacian(lo);
  const double h2 = [&] {
    double s = 0;
    int n = 0;
    for (int v = 0; v < nv; ++v)
      if (lap.mass[v] > 0) s += lap.mass[v], ++n;
    return n > 0 ? s / n : 1.0;  // the mean vertex area: m_v about 1
  }();
  // a f with a = 1 / floor (the noise's largest strength over the scales): a feature nine times
  // that gets the full weight (a f_max = 9).
  const double a = floor > 0 ? 1 / floor : (ref > 0 ? opt.fill_weight / ref : 0);
  Eigen::SparseMatrix<double> A = -opt.effective_fill_smoothness() * lap.L;
  Eigen::MatrixXd B(nv, 1), X(nv, 1);
  Eigen::VectorXd mass(nv);
  for (int v = 0; v < nv; ++v) {
    const double m = std::max(lap.mass[v] / h2, 1e-6);
    const bool has = selected_edges[v] > 0;
    const double u_hat = has ? std::clamp(std::log(selected_edges[v]), u_min, u_max) : u_max;
    const double rho = has ? std::pow(std::min(opt.fill_weight, a * strength[v]), 2) : 0.0;
    A.coeffRef(v, v) += m * (rho + opt.featureless_pull);
    B(v, 0) = m * (rho * u_hat + opt.featureless_pull * u_max);
    X(v, 0) = rho > 0 ? u_hat : u_max;
    mass[v] = m;
  }
  SolverOptions so;
  so.tolerance = 1e-6;
  so.label = "Optimal scale fill";
  // μ = kReliefFillSmoothness: conjugate gradients stopped at 1,000 iterations on 1 M faces
  // (predicted far fewer) before the Cholesky fallback; go there directly (3.8 s).
  so.prefer_direct = opt.effective_fill_smoothness() > 100 || predicted_cg_iterations(A, mass) > kDirectAboveIterations;
  Eigen::MatrixXd U = X;
  report = solve_spd(A, B, U, so);
  std::vector<double> sigma(size_t(nv), 0.0);
  for (int v = 0; v < nv; ++v) sigma[v] = std::exp(std::clamp(U(v, 0), u_min, u_max));
  return sigma;  // in edge lengths
}

// Step 3b: σ_v <= σ_u + slope |uv| for every pair of neighbours, the largest σ that holds it
// (each vertex lowered to the bound its neighbours set, until nothing changes: the bound
// travels one ring per sweep, as far as a selection's scale divided by the slope). σ in mesh units.
void limit_scale_growth(const Surface& surface, double slope, std::vector<double>& sigma) {
  const MeshTopology& topo = surface.topology();
  const std::vector<Vec3>& x = surface.mesh().vertices;
  const int nv = surface.n_vertices();
  std::vector<double> next(sigma.size());
  for (long changed = 1; changed > 0;) {
    changed = 0;
#pragma omp parallel for schedule(static) reduction(+ : changed)
    for (int v = 0; v < nv; ++v) {
      double bound = sigma[v];
      for (int k = topo.ring.offset[v]; k < topo.ring.offset[v + 1]; ++k) {
        const int u = topo.ring.vertex[k];
        if (sigma[u] > 0) bound = std::min(bound, sigma[u] + slope * (x[u] - x[v]).norm());
      }
      changed += bound < sigma[v];
      next[v] = bound;
    }
    sigma.swap(next);
  }
}

}  // namespace

double ridge_detection_ratio(double gamma) { return std::sqrt((1.5 - gamma) / gamma); }

OptimalScale optimal_scale(const Surface& surface, const OptimalScaleOptions& opt) {
  surface.require_triangles();
  opt.validate();
  OptimalScale out;
  out.scale = surface.scale();
  const double h = out.scale.edge;
  const Levels levels = plan_levels(out.scale, opt);
  out.max_scale_lowered = levels.lowered;
  out.levels = levels.sigma;
  const int nv = surface.n_vertices();
  const bool relief = opt.curve == ScaleStrength::ReliefEdges;
  const double gamma = opt.effective_gamma();
  // Relief edges' strengths do not read the base: it is built only for the smoothed surface.
  BaseSurface base;
  if (!relief || opt.smoothed_surface) base = base_surface(surface, levels, opt);
  out.base_space = base.space;
  LevelStrengths ls = level_strengths(surface, levels, opt, base.shape);
  out.space = ls.space;
  measure_noise_floor(surface, opt, levels.size(), out);
  std::vector<double> selected_edges = select_scales(ls, levels, gamma, h, out);
  std::vector<double>().swap(ls.s);
  if (opt.dominant_reach > 0) {
    if (opt.progress) opt.progress(86, "Optimal scale: each feature's scale over its footprint");
    dominant_selection(surface, opt, levels, selected_edges, out);
  }
  if (opt.progress) opt.progress(87, "Optimal scale: filling featureless areas (eq. 5.3)");
  if (opt.fill) {
    const std::vector<double> filled =
        fill_scales(surface, opt, selected_edges, out.strength, out.strength_floor, out.strength_ref,
                    levels.log_edges.front(), levels.log_edges.back(), out.fill_solve);
    sized(out.sigma, size_t(nv));
    for (int v = 0; v < nv; ++v) out.sigma[v] = filled[v] * h;
    if (opt.max_scale_growth > 0) limit_scale_growth(surface, opt.max_scale_growth, out.sigma);
  } else {
    out.sigma = out.selected;
  }
  if (opt.smoothed_surface) {
    if (opt.progress) opt.progress(93, "Optimal scale: optimally smoothed surface");
    out.smoothed_ratio = relief ? 1.0 : ridge_detection_ratio(gamma);
    assemble_smoothed(surface, opt, levels, base, ls, out);
    out.base_shape = std::move(base.shape);
    out.base_normal = std::move(base.normal);
  }
  if (opt.progress) opt.progress(100, "Optimal scale");
  return out;
}

OptimalScale optimal_scale(const TriMesh& mesh, const OptimalScaleOptions& opt) {
  return optimal_scale(Surface::borrow(mesh), opt);
}

}  // namespace reliefkit
