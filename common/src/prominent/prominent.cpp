#include "reliefkit/base/angles.h"
#include "reliefkit/prominent/prominent.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <tuple>

#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/memory.h"
#include "reliefkit/base/smoothing.h"

namespace reliefkit {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The direction u (tangent at a vertex of normal a) carried to the tangent plane of normal b by
// the smallest rotation taking a to b (fig. 6.6 (a)).
Vec3 transport(const Vec3& u, const Vec3& a, const Vec3& b) { return u - (u.dot(b) / (1 + a.dot(b))) * (a + b); }

// The solve's relative residual. The field's median angle on the test reliefs is the same at 1e-2
// and 1e-3 (0.2-1.2 deg), but far from every feature the field converges last and contributes
// little to the residual: on a plane carrying one disc, at 1e-2 the field there was left rough
// (mean angle between neighbours 15 deg, 25 iterations) once the plane's open border no longer
// drew false features to anchor it; 3e-3: 1.1 deg, 72 iterations (1e-3: 1.07 deg, 127).
constexpr double kFieldTolerance = 3e-3;

// Below this cosine between neighbouring normals (a fold, a flipped face) the pair is not coupled.
constexpr double kMinNormalCos = -0.5;

}  // namespace

void ProminentFieldParams::validate() const {
  presmoothing.check("Pre-smoothing", 0, 100);
  base_scale.check("Base surface scale", 0.5, 10000);
  require_range(theta, "Feature threshold theta", 1e-6, 1e6);
  require_range(constraint_weight, "Constraint weight", 1e-6, 1e6);
}

namespace {

// The smooth-field system of eqs. 6.3 / 6.6: the Hermitian connection Laplacian plus the
// constraint term, one complex unknown per vertex (the field's angle, times k, in its frame).
struct FieldSystem {
  const LaplacianResult& lap;
  const std::vector<Vec3>& normal;
  const std::vector<Vec3>& e1;
  std::vector<Vec3> e2;
  const std::vector<Vec3>& target;
  const std::vector<double>& beta;
  double weight;
  double k;  // 2 for a line field (the angle doubled), 1 for a vector field
  HermitianMatrix A;  // L's pattern
  Eigen::VectorXcd rhs, guess;

  // The rotation T_jp that turns p's frame into j's (the angle of p's e1 seen in j's frame),
  // applied k times, as (cos, sin); false where the pair is not coupled.
  bool rotation(int p, int j, double& cs, double& sn) const {
    if (!(normal[p].dot(normal[j]) > kMinNormalCos)) return false;
    const Vec3 u = transport(e1[p], normal[p], normal[j]);
    cs = u.dot(e1[j]), sn = u.dot(e2[j]);
    const double len = std::hypot(cs, sn);
    if (!(len > 0)) return false;
    cs /= len, sn /= len;
    if (k == 2) std::tie(cs, sn) = std::make_pair(cs * cs - sn * sn, 2 * cs * sn);  // the angle doubled
    return true;
  }

  // Row p of A (H_pj = -w conj(T_jp), Hermitian), and p's entries of the right-hand side and the
  // starting guess.
  void fill(int p) {
    const Eigen::SparseMatrix<double>& L = lap.L;
    const int first = int(L.outerIndexPtr()[p]), n = int(L.outerIndexPtr()[p + 1]) - first;
    const int* cols = L.innerIndexPtr() + first;
    const double* w = L.valuePtr() + first;
    std::complex<double>* row = A.valuePtr() + first;
    double diag = 0;
    int diag_at = -1;
    for (int q = 0; q < n; ++q) {
      const int j = cols[q];
      row[q] = 0;
      double cs, sn;
      if (j == p) {
        diag_at = q;
      } else if (w[q] > 0 && std::isfinite(w[q]) && rotation(p, j, cs, sn)) {
        row[q] = {-w[q] * cs, w[q] * sn};
        diag += w[q];
      }
    }
    const double m = lap.mass[p];
    const double mu = weight * beta[p] * m, eps = 1e-6 * weight * m;  // weight: per unit area
    if (diag_at >= 0) row[diag_at] = diag + mu + eps;
    const Vec3& r = target[p];
    const double phi = std::atan2(r.dot(e2[p]), r.dot(e1[p]));
    const std::complex<double> z = std::polar(1.0, k * phi);
    rhs[p] = mu * z;
    guess[p] = beta[p] * z;  // free vertices start at 0
  }

  void build() {
    const int nv = int(lap.L.cols());
    e2.resize(nv);
#pragma omp parallel for schedule(static)
    for (int p = 0; p < nv; ++p) e2[p] = normal[p].cross(e1[p]);
    A.resize(nv, nv);
    A.resizeNonZeros(lap.L.nonZeros());
    std::copy(lap.L.outerIndexPtr(), lap.L.outerIndexPtr() + nv + 1, A.outerIndexPtr());
    std::copy(lap.L.innerIndexPtr(), lap.L.innerIndexPtr() + lap.L.nonZeros(), A.innerIndexPtr());
    rhs.resize(nv);
    guess.resize(nv);
#pragma omp parallel for schedule(dynamic, 4096)
    for (int p = 0; p < nv; ++p) fill(p);
  }

  // The field from the solution z: its angle divided by k in each frame, unit; where |z| is
  // (nearly) zero no feature reaches and the field is the target.
  void read_field(const Eigen::VectorXcd& X, ProminentFieldResult& out) const {
    const int nv = int(e2.size());
    sized(out.field, size_t(nv), Vec3(Vec3::Zero()));
    sized(out.strength, size_t(nv));
    long long unreached = 0;
#pragma omp parallel for schedule(static) reduction(+ : unreached)
    for (int p = 0; p < nv; ++p) {
      const double x = X[p].real(), y = X[p].imag();
      const double s = std::hypot(x, y);
      out.strength[p] = std::isfinite(s) ? s : 0;
      if (!(s > 1e-3)) {
        out.field[p] = target[p];
        ++unreached;
        continue;
      }
      const double phi = std::atan2(y, x) / k;
      out.field[p] = std::cos(phi) * e1[p] + std::sin(phi) * e2[p];
    }
    out.unreached = unreached;
  }
};

}  // namespace

void solve_prominent_field(const Surface& surface, const std::vector<Vec3>& normal, const std::vector<Vec3>& e1,
                           const std::vector<Vec3>& target, const std::vector<double>& beta, double weight,
                           FieldRepresentation representation, ProminentFieldResult& out) {
  LaplacianOptions lo;
  lo.clamp_negative = true;  // the same Laplacian as the base normals': the run computes it once
  FieldSystem sys{surface.laplacian(lo), normal, e1, {}, target, beta, weight,
                  representation == FieldRepresentation::Line ? 2.0 : 1.0, {}, {}, {}};
  sys.build();
  SolverOptions so;
  so.tolerance = kFieldTolerance;
  so.max_iterations = 2000;
  so.label = "Prominent field";
  Eigen::VectorXcd X = sys.guess;
  out.solve = solve_hpd(sys.A, sys.rhs, X, so);
  sys.read_field(X, out);
}

namespace {

// The relief-edge options the prominent field reads chapter 4's fields with.
ReliefEdgeParams relief_edge_params(const ProminentFieldParams& p) {
  ReliefEdgeParams rp;
  rp.estimator = p.estimator;
  rp.presmoothing = p.presmoothing;
  rp.base_scale = p.base_scale;
  rp.progress = p.progress;
  return rp;
}

// What the prominent field keeps of chapter 4's per-vertex fields.
void take_relief_fields(ReliefEdgeFields&& re, ProminentFieldResult& out) {
  static_cast<ScaledCurvature&>(out) = std::move(static_cast<ScaledCurvature&>(re));
  out.base = std::move(re.base);
  out.base_scale = re.base_scale;
  out.feature_width = re.feature_width;
  out.relief_direction = std::move(re.direction);
  out.tilt = std::move(re.angle);
  out.fit_error = std::move(re.fit_error);
}

// Per vertex: the prominent direction r_p (eq. 6.2) and whether p is a feature point (eq. 6.4,
// with the thresholds scaled by 2 / theta; see ProminentFieldParams::theta).
void prominent_directions(const ProminentFieldParams& p, ProminentFieldResult& out) {
  const Curvature& c = *out.curvature;
  const int nv = static_cast<int>(c.k1.size());
  // kappa_0: the curvature of the scan's most curved tenth (see kFeatureCurvaturePercentile).
  std::vector<double> maxabs(nv);
  for (int v = 0; v < nv; ++v) maxabs[v] = std::max(std::abs(c.k1[v]), std::abs(c.k2[v]));
  out.curvature_threshold = percentile(counted_values(maxabs, out.scale.counts), kFeatureCurvaturePercentile);
  sized(out.principal, size_t(nv), Vec3(Vec3::Zero()));
  sized(out.prominent, size_t(nv), Vec3(Vec3::Zero()));
  sized(out.alpha, size_t(nv));
  sized(out.beta, size_t(nv));
  long long ridge_points = 0, edge_points = 0;
  const double k0 = out.curvature_threshold, relax = 2 / p.theta;
#pragma omp parallel for schedule(static) reduction(+ : ridge_points, edge_points)
  for (int v = 0; v < nv; ++v) {
    const bool first = std::abs(c.k1[v]) >= std::abs(c.k2[v]);
    const double big = first ? std::abs(c.k1[v]) : std::abs(c.k2[v]);
    const double small = first ? std::abs(c.k2[v]) : std::abs(c.k1[v]);
    const double ratio = small > 0 ? big / small : (big > 0 ? 1e300 : 1.0);
    const Vec3& g = out.relief_direction[v];
    Vec3 t = first ? c.dir1[v] : c.dir2[v];
    if (t.dot(g) < 0) t = -t;
    out.principal[v] = t;
    const double a = (big < k0 || ratio < 2) ? 1.0 : ratio > 4 ? 0.0 : (4 - ratio) / 2;  // eq. 6.2
    out.alpha[v] = a;
    Vec3 r = a * g + (1 - a) * t;
    const double rn = r.norm();
    out.prominent[v] = rn > 1e-12 ? Vec3(r / rn) : g;
    const bool ridge = ratio > 2 && big > k0 * relax;  // eq. 6.4
    const bool edge = out.fit_error[v] <= kFeatureFitError && out.tilt[v] >= out.tilt_threshold * relax;
    ridge_points += ridge;
    edge_points += !ridge && edge;
    out.beta[v] = (ridge || edge) ? 1.0 : 0.0;
  }
  out.ridge_points = ridge_points;
  out.edge_points = edge_points;
}

}  // namespace

ProminentFieldResult compute_prominent_field(const TriMesh& mesh, const ProminentFieldParams& p) {
  return compute_prominent_field(Surface::borrow(mesh), p);
}

ProminentFieldResult compute_prominent_field(const Surface& surface, const ProminentFieldParams& p) {
  p.validate();
  // Chapter 4's per-vertex fields give the curvature, the base normals and the relief direction g
  // with its step-model fit; a relief-edge point tilts at least the weak hysteresis tilt, automatic
  // from the zero crossings of G (no curves are selected).
  const ReliefEdgeParams rp = relief_edge_params(p);
  ReliefEdgeFields re = compute_relief_edge_fields(surface, rp);
  const double weak_tilt = relief_edge_thresholds(surface, re, relief_edge_crossings(surface, re), rp).weak_angle;
  const auto t0 = std::chrono::steady_clock::now();
  if (p.progress) p.progress(95, "Prominent field");
  ProminentFieldResult out;
  take_relief_fields(std::move(re), out);
  out.tilt_threshold = weak_tilt;
  prominent_directions(p, out);
  const Curvature& c = *out.curvature;
  const double h = out.scale.edge;
  solve_prominent_field(surface, c.normal, c.dir1, out.prominent, out.beta, p.constraint_weight / (h * h),
                        p.representation, out);
  if (p.representation == FieldRepresentation::Line) {  // lines have no sign: show them up the relief
#pragma omp parallel for schedule(static)
    for (int v = 0; v < surface.n_vertices(); ++v)
      if (out.field[v].dot(out.relief_direction[v]) < 0) out.field[v] = -out.field[v];
  }
  out.field_seconds = seconds_since(t0);
  if (p.progress) p.progress(100, "Prominent field");
  return out;
}

// ---- Enhancement ----

// The automatic stop: no vertex moved more than kFlowSettled of the step in the last iteration,
// or fewer than kFlowSettledShare of the vertices that moved in the first one still move, or the
// iteration's total motion fell below that share of the first's (the flow steepens the relief's
// outlines first, then creeps along them for a long tail: on the coin 16 % of the vertices still
// moved after 25 iterations, 6 % after 95).
constexpr double kFlowSettled = 0.05, kFlowSettledShare = 0.1;
// The stopping rule's neighbourhood reaches at least this multiple of the features' width: a
// vertex on a worn step's shoulder must see the plateau it is to rise to.
constexpr double kExtremumWidths = 2.0;
// The flow leaves vertices tilted more than this against the base (radians).
constexpr double kFlowMaxTilt = 0.78539816339744831;

void EnhanceParams::validate() const {
  field.validate();
  spatial_scale.check("Smoothing scale sigma_c", 0.1, 100);
  if (bilateral_iterations < 0 || bilateral_iterations > 100)
    throw InputError("Bilateral iterations must be between 0 and 100 (got " + std::to_string(bilateral_iterations) + ")");
  if (flow_iterations < -1 || flow_iterations > 10000)
    throw InputError("Flow iterations must be -1 (automatic) or between 0 and 10000 (got " +
                     std::to_string(flow_iterations) + ")");
  require_range(flow_step, "Flow step", 1e-4, 1);
  require_range(strength, "Enhancement strength", 0.01, 100);
}

namespace {

// Calls f(j, |p_j - p_v|) for every vertex j != v connected to v through vertices within
// `radius` of p_v (the surface neighbourhood of Fleishman et al.). `stamp` / `mark` are the
// caller's per-thread scratch (mark sized #V).
template <class F>
void for_each_near(const VertexRing& ring, const std::vector<Vec3>& pos, int v, double radius, std::vector<int>& mark,
                   int stamp, std::vector<int>& queue, F f) {
  queue.clear();
  queue.push_back(v);
  mark[v] = stamp;
  const double r2 = radius * radius;
  for (size_t q = 0; q < queue.size(); ++q) {
    const int u = queue[q];
    for (int k = ring.offset[u]; k < ring.offset[u + 1]; ++k) {
      const int j = ring.vertex[k];
      if (mark[j] == stamp) continue;
      mark[j] = stamp;
      const double d2 = (pos[j] - pos[v]).squaredNorm();
      if (!(d2 <= r2)) continue;
      queue.push_back(j);
      f(j, d2);
    }
  }
}

}  // namespace

std::vector<Vec3> bilateral_pass(const Surface& at, double sigma_c, const std::vector<Vec3>* field) {
  const int nv = at.n_vertices();
  const MeshTopology& topology = at.topology();
  const std::vector<Vec3>& positions = at.mesh().vertices;
  const std::vector<Vec3>& raw = at.normals();
  const double sc2 = 2 * sigma_c * sigma_c, ss2 = 2 * 0.25 * sigma_c * sigma_c, sr2 = 2 * 0.16 * sigma_c * sigma_c;
  std::vector<Vec3> out(positions);
  std::vector<std::vector<int>> marks = per_thread(size_t(nv), -1);
#pragma omp parallel
  {
    std::vector<int> queue, &mark = marks[size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1024)
    for (int v = 0; v < nv; ++v) {
      const Vec3& pv = positions[v];
      // Mollified normal: the neighbourhood's normals weighted by distance.
      Vec3 n = raw[v];
      for_each_near(topology.ring, positions, v, 2 * sigma_c, mark, 2 * v, queue,
                    [&](int j, double d2) { n += std::exp(-d2 / sc2) * raw[j]; });
      const double nn = n.norm();
      if (!(nn > 0)) continue;
      n /= nn;
      const Vec3* s = field ? &(*field)[v] : nullptr;
      double sum = 0, wsum = 0;
      for_each_near(topology.ring, positions, v, 2 * sigma_c, mark, 2 * v + 1, queue, [&](int j, double d2) {
        const Vec3 dp = positions[j] - pv;
        const double hj = n.dot(dp);
        double w = std::exp(-d2 / sc2 - hj * hj / ss2);
        if (s) {
          const double rj = s->dot(dp);
          w *= std::exp(-rj * rj / sr2);
        }
        sum += w * hj;
        wsum += w;
      });
      if (wsum > 0) out[v] = pv + (sum / wsum) * n;
    }
  }
  return out;
}

namespace {

// Step 1: the bilateral filter along the prominent field, bilateral_iterations times.
std::vector<Vec3> bilateral_steps(const Surface& surface, const EnhanceParams& p, const EnhanceResult& out) {
  Surface step = surface;
  for (int it = 0; it < p.bilateral_iterations; ++it) {
    if (p.progress) p.progress(it * 30 / std::max(1, p.bilateral_iterations), "Bilateral filter");
    step = surface.with_positions(bilateral_pass(step, out.spatial_scale, p.prominent_term ? &out.field.field : nullptr));
  }
  return step.mesh().vertices;
}

// Step 2's per-vertex state: each vertex moves along its base normal by u, between lo and hi.
struct FlowState {
  std::vector<double> lo, hi;   // the stopping rule's heights (then the curvature caps), along the base normal
  std::vector<double> near;     // where the flow acts: near feature points, in [0, 1]
  std::vector<double> u;        // height change along the base normal
  std::vector<char> stopped;
  std::vector<char> capped;     // bit 0: hi is the curvature cap, bit 1: lo is
};

// The flow's start: each vertex may move up to the extremum of the heights (over its base tangent
// plane) of its neighbourhood on the step-1 surface, and only near feature points.
FlowState flow_start(const Surface& surface, const EnhanceResult& out) {
  const MeshTopology& topo = surface.topology();
  const std::vector<Vec3>& nb = out.field.base.normal;
  const std::vector<Vec3>& pos = out.bilateral;
  const int nv = surface.n_vertices();
  FlowState s;
  s.lo.assign(nv, 0), s.hi.assign(nv, 0);
  std::vector<std::vector<int>> marks = per_thread(size_t(nv), -1);
#pragma omp parallel
  {
    std::vector<int> queue, &mark = marks[size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 1024)
    for (int v = 0; v < nv; ++v)
      for_each_near(topo.ring, pos, v, out.extremum_radius, mark, v, queue, [&](int j, double) {
        const double hj = nb[v].dot(pos[j] - pos[v]);
        s.lo[v] = std::min(s.lo[v], hj), s.hi[v] = std::max(s.hi[v], hj);
      });
  }
  s.near = out.field.beta;  // beta diffused over sigma_c
  diffuse(surface, out.spatial_scale, s.near);
  for (auto& x : s.near) x = std::clamp(2 * x, 0.0, 1.0);
  s.u.assign(nv, 0);
  s.stopped.assign(nv, 0);
  s.capped.assign(nv, 0);
  // Boundary vertices' one-sided curvature is no guide: they stay. So do vertices tilted more than
  // kFlowMaxTilt against the base: there the base is no ground under a relief but a part thinner
  // than the base scale (the bunny's ears, the statuette's arms), and moving along its normal
  // sheared the surface into creases.
  const double min_cos = std::cos(kFlowMaxTilt);
  for (int v = 0; v < nv; ++v)
    if (s.near[v] < 0.01 || topo.border.offset[v + 1] > topo.border.offset[v] ||
        out.field.curvature->normal[v].dot(nb[v]) < min_cos)
      s.stopped[v] = 1;
  return s;
}

// The positions after the flow's height changes so far.
std::vector<Vec3> flow_positions(const EnhanceResult& out, const std::vector<double>& u) {
  const std::vector<Vec3>& nb = out.field.base.normal;
  std::vector<Vec3> pos;
  sized(pos, u.size(), Vec3(Vec3::Zero()));
  for (size_t v = 0; v < u.size(); ++v) pos[v] = out.bilateral[v] + u[v] * nb[v];
  return pos;
}

// The curvature along the field at the current positions, diffused over h: neighbours along a
// feature move together (the jet fits' noise made outlines jagged).
std::vector<double> flow_curvature(const Surface& current, const std::vector<Vec3>& field, double h) {
  const std::shared_ptr<const Curvature> curvature = current.curvature(CurvatureEstimator::Jet, false);
  const Curvature& c = *curvature;
  const int nv = current.n_vertices();
  std::vector<double> kp(nv);
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) kp[v] = c.normal_curvature(v, field[v]);
  diffuse(current, h, kp);
  return kp;
}

// After the first iteration's curvature: each vertex may restore what its own curvature took
// away, no more — the height a parabola of that curvature gains over the stopping rule's radius
// rho. Without it the flow cascaded (a shoulder that rose made its neighbour concave, which sank,
// and so on) and terraced smooth bodies: creases and craters on the bunny and the statuette.
// Nor more than the data supports: back to the scan where step 1 rounded it (`step_one`: its
// move along the base normal, averaged over sigma_c, so that the noise it removed stays removed)
// and beyond by kFlowNoiseMoves x the noise's standard deviation; further, the flow invents
// relief (noisy steps came out twice as steep as the clean ones).
// It moves only the way its curvature first pushed it (outwards where convex), so that a vertex
// whose curvature flips as its neighbours move does not oscillate.
void cap_heights(double strength, const std::vector<double>& kp, double rho, double noise_sigma,
                 const std::vector<double>& step_one, FlowState& s) {
  const double rho2 = rho * rho;
  for (size_t v = 0; v < kp.size(); ++v) {
    const double back_to_scan = std::max(0.0, kp[v] >= 0 ? -step_one[v] : step_one[v]);
    const double cap = strength * std::min(0.5 * std::abs(kp[v]) * rho2, back_to_scan + kFlowNoiseMoves * noise_sigma);
    if (kp[v] >= 0) {
      s.lo[v] = 0;
      if (cap < s.hi[v]) s.hi[v] = cap, s.capped[v] = 1;
    } else {
      s.hi[v] = 0;
      if (-cap > s.lo[v]) s.lo[v] = -cap, s.capped[v] = 2;
    }
  }
}

// Step 1's move along the base normal, averaged over sigma_c: what it rounded, not the noise.
std::vector<double> step_one_move(const Surface& surface, const EnhanceResult& out) {
  const std::vector<Vec3>& input = surface.mesh().vertices;
  std::vector<double> move(input.size());
  for (size_t v = 0; v < input.size(); ++v) move[v] = out.field.base.normal[v].dot(out.bilateral[v] - input[v]);
  diffuse(surface, out.spatial_scale, move);
  return move;
}

struct FlowMoves {
  double largest = 0, total = 0;  // the largest and the summed move of the iteration
  long long moving = 0;           // vertices that moved
};

// One flow iteration: every vertex not stopped moves along its base normal by up to max_move,
// as far as its curvature along the field (relative to kappa_ref) pushes it; a vertex that
// reaches its bounds stops there (counted in out.at_extremum or out.at_curvature_cap).
FlowMoves move_vertices(const std::vector<double>& kp, double kappa_ref, double max_move,
                        const std::vector<Vec3>& normal, FlowState& s, EnhanceResult& out) {
  const std::vector<Vec3>& nb = out.field.base.normal;
  const int nv = static_cast<int>(kp.size());
  double largest = 0, total = 0;
  long long moving = 0, at_ext = 0, at_cap = 0;
#pragma omp parallel for schedule(static) reduction(max : largest) reduction(+ : moving, at_ext, at_cap, total)
  for (int v = 0; v < nv; ++v) {
    if (s.stopped[v]) continue;
    double d = s.near[v] * max_move * std::clamp(kp[v] / kappa_ref, -1.0, 1.0) * nb[v].dot(normal[v]);
    if (s.hi[v] <= 0) d = std::min(d, 0.0);  // monotone: only ever the first way (see cap_heights)
    if (s.lo[v] >= 0) d = std::max(d, 0.0);
    if (d == 0) continue;
    double nu = s.u[v] + d;
    if (nu > s.hi[v] || nu < s.lo[v]) {
      const bool up = nu > s.hi[v];
      nu = std::clamp(nu, s.lo[v], s.hi[v]);
      s.stopped[v] = 1;
      if (s.capped[v] & (up ? 1 : 2))
        ++at_cap;
      else
        ++at_ext;
    }
    largest = std::max(largest, std::abs(nu - s.u[v]));
    total += std::abs(nu - s.u[v]);
    s.u[v] = nu;
    ++moving;
  }
  out.at_extremum += at_ext;
  out.at_curvature_cap += at_cap;
  return {largest, total, moving};
}

// Step 2: inverse-curvature flow along the prominent direction, each vertex moving along its base
// normal and stopping at the extremum of the heights of its neighbourhood on the step-1 surface.
void inverse_curvature_flow(const Surface& surface, const EnhanceParams& p, EnhanceResult& out) {
  const ProminentFieldResult& f = out.field;
  FlowState s = flow_start(surface, out);
  const int max_it = p.flow_iterations >= 0 ? p.flow_iterations : EnhanceParams::kMaxFlowIterations;
  const double max_move = p.flow_step * f.scale.edge;
  double kappa_ref = 0, first_total = 0;
  long long first_moving = 0;
  out.converged = p.flow_iterations < 0;
  for (int it = 0; it < max_it; ++it) {
    if (p.progress) p.progress(30 + 70 * it / std::max(1, max_it), "Inverse-curvature flow");
    const Surface current = surface.with_positions(flow_positions(out, s.u));
    const std::vector<double> kp = flow_curvature(current, f.field, f.scale.edge);
    if (it == 0) {
      std::vector<double> a;
      for (size_t v = 0; v < kp.size(); ++v)
        if (!s.stopped[v]) a.push_back(std::abs(kp[v]));
      kappa_ref = percentile(a, 0.9);
      if (!(kappa_ref > 0)) break;
      cap_heights(p.strength, kp, out.extremum_radius, f.noise.sigma, step_one_move(surface, out), s);
    }
    const FlowMoves m = move_vertices(kp, kappa_ref, max_move, current.curvature(CurvatureEstimator::Jet, false)->normal, s, out);
    out.flow_iterations = it + 1;
    if (it == 0) first_moving = m.moving, first_total = m.total;
    if (p.flow_iterations < 0 && (m.moving <= kFlowSettledShare * first_moving ||
                                  m.largest < kFlowSettled * max_move || m.total <= kFlowSettledShare * first_total))
      break;
    if (p.flow_iterations < 0 && it + 1 == max_it) out.converged = false;
  }
  out.positions = flow_positions(out, s.u);
  out.height_change = std::move(s.u);
}

}  // namespace

EnhanceResult enhance_relief(const TriMesh& mesh, const EnhanceParams& p) {
  return enhance_relief(Surface::borrow(mesh), p);
}

EnhanceResult enhance_relief(const Surface& surface, const EnhanceParams& p) {
  p.validate();
  EnhanceResult out;
  out.field = compute_prominent_field(surface, p.field);
  const double h = out.field.scale.edge;
  p.spatial_scale.check("Smoothing scale sigma_c", 0.1, 100, h);
  out.spatial_scale = p.spatial_scale.resolve(h, EnhanceParams::kDefaultSpatialEdges * h);
  out.extremum_radius = std::max(2 * out.spatial_scale, kExtremumWidths * out.field.feature_width);
  auto t0 = std::chrono::steady_clock::now();
  out.bilateral = bilateral_steps(surface, p, out);
  out.bilateral_seconds = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  inverse_curvature_flow(surface, p, out);
  out.flow_seconds = seconds_since(t0);
  if (p.progress) p.progress(100, "Enhancement");
  return out;
}

// ---- Coloring ----

ColoringResult arctan_coloring(std::vector<double> curvature, const std::vector<char>& counts, double contrast) {
  require_range(contrast, "Contrast lambda", 1e-9, 1e9);
  if (!(contrast > 0)) throw InputError("Contrast lambda must be positive");
  ColoringResult r;
  std::vector<double> a;
  a.reserve(curvature.size());
  for (size_t v = 0; v < curvature.size(); ++v)
    if ((counts.empty() || counts[v]) && std::isfinite(curvature[v]) && curvature[v] != 0)
      a.push_back(std::abs(curvature[v]));
  const double ref = percentile(std::move(a), 0.9);
  r.lambda = contrast / (ref > 0 ? ref : 1.0);
  r.grey.resize(curvature.size());
  for (size_t v = 0; v < curvature.size(); ++v)
    r.grey[v] = std::isfinite(curvature[v]) ? 0.5 + std::atan(r.lambda * curvature[v]) / kPi : 0.5;
  r.curvature = std::move(curvature);
  return r;
}

ColoringResult curvature_coloring(const Curvature& c, const std::vector<Vec3>* field, const std::vector<char>& counts,
                                  ColoringCurvature which, double contrast) {
  const size_t nv = c.k1.size();
  if (which == ColoringCurvature::Prominent && (!field || field->size() != nv))
    throw std::invalid_argument("curvature_coloring: the prominent field has another vertex count than the mesh");
  std::vector<double> k(nv);
#pragma omp parallel for schedule(static)
  for (long v = 0; v < long(nv); ++v) {
    switch (which) {
      case ColoringCurvature::Prominent: k[v] = c.normal_curvature(int(v), (*field)[v]); break;
      case ColoringCurvature::Mean: k[v] = c.mean(int(v)); break;
      case ColoringCurvature::Maximal: k[v] = std::abs(c.k1[v]) >= std::abs(c.k2[v]) ? c.k1[v] : c.k2[v]; break;
    }
  }
  return arctan_coloring(std::move(k), counts, contrast);
}

}  // namespace reliefkit
