#include "reliefkit/multiscale/scale_space.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "reliefkit/base/laplacian.h"

namespace reliefkit {

namespace {

// The symmetric system of one kind of unknowns (interior or boundary-loop vertices): the
// stiffness restricted to them, the mass, and the stiffness towards the vertices whose positions
// are known when it is solved.
struct Block {
  std::vector<int> vertex;                  // unknown -> mesh vertex
  Eigen::SparseMatrix<double> K;            // stiffness among the unknowns (positive semi-definite)
  Eigen::VectorXd mass;                     // per unknown
  std::vector<std::vector<std::pair<int, double>>> known;  // per unknown: (mesh vertex, weight) of known neighbours
  double median_stiffness = 0;              // median of K_ii / mass_i (cost model, solver choice)
};

// (M + Δτ K) D = -Δτ (K X_unknown + K_known X_known): the displacement over one step. A keeps K's
// structure (every row holds its diagonal); only its values change from step to step. D comes in
// as the guess (the previous step's displacement, scaled to this step's length) and goes out as
// this step's.
SolveReport step(const Block& b, double dtau, Eigen::SparseMatrix<double>& A, const std::vector<int>& diagonal,
                 std::vector<Vec3>& x, Eigen::MatrixXd& D, const ScaleSpaceOptions& opt) {
  const int n = static_cast<int>(b.vertex.size());
  if (n == 0) return {};
  const Eigen::Index nnz = b.K.nonZeros();
  const double* k = b.K.valuePtr();
  double* a = A.valuePtr();
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < nnz; ++i) a[i] = dtau * k[i];
  for (int i = 0; i < n; ++i) a[diagonal[i]] += b.mass[i];
  Eigen::MatrixXd X(n, 3);
  for (int i = 0; i < n; ++i) X.row(i) = x[b.vertex[i]].transpose();
  // K is symmetric: its row-major view (the same arrays) multiplies on every core.
  const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor>> K(n, n, nnz, b.K.outerIndexPtr(),
                                                                         b.K.innerIndexPtr(), k);
  Eigen::MatrixXd B = -dtau * (K * X);
  for (int i = 0; i < n; ++i)
    for (const auto& [v, w] : b.known[i]) B.row(i) -= dtau * w * x[v].transpose();
  SolverOptions so;
  so.method = opt.method;
  so.tolerance = opt.tolerance;
  so.prefer_direct = predicted_cg_iterations(1 + dtau * b.median_stiffness) > kDirectAboveIterations;
  so.label = "Scale space";
  SolveReport rep = solve_spd(A, B, D, so);
  for (int i = 0; i < n; ++i) x[b.vertex[i]] += D.row(i).transpose();
  return rep;
}

// n forward-Euler steps of size dtau: X += -dtau M⁻¹ (K X + K_known X_known). Stable (and
// monotone) for dtau below 1 / gershgorin_bound(b).
void explicit_steps(const Block& b, double dtau, long long n, std::vector<Vec3>& x, std::vector<Vec3>& d) {
  const int nu = static_cast<int>(b.vertex.size());
  if (nu == 0) return;
  d.resize(size_t(nu));
  const int* outer = b.K.outerIndexPtr();
  const int* inner = b.K.innerIndexPtr();
  const double* k = b.K.valuePtr();
  for (long long s = 0; s < n; ++s) {
#pragma omp parallel for schedule(static)
    for (int i = 0; i < nu; ++i) {
      Vec3 acc = Vec3::Zero();
      for (int p = outer[i]; p < outer[i + 1]; ++p) acc += k[p] * x[b.vertex[inner[p]]];  // K symmetric: column = row
      for (const auto& [v, w] : b.known[i]) acc += w * x[v];
      d[i] = (-dtau / b.mass[i]) * acc;
    }
#pragma omp parallel for schedule(static)
    for (int i = 0; i < nu; ++i) x[b.vertex[i]] += d[i];
  }
}

// Gershgorin bound on the largest eigenvalue of M⁻¹K: max_i (K_ii + sum_j≠i |K_ij|) / M_i.
double gershgorin_bound(const Block& b) {
  double bound = 0;
  for (int i = 0; i < static_cast<int>(b.vertex.size()); ++i) {
    double row = 0;
    for (int p = b.K.outerIndexPtr()[i]; p < b.K.outerIndexPtr()[i + 1]; ++p) row += std::abs(b.K.valuePtr()[p]);
    bound = std::max(bound, row / b.mass[i]);
  }
  return bound;
}

// Median of K_ii / M_i: with it, predicted_cg_iterations of M + dtau K is 5.5 sqrt(1 + dtau q).
double median_stiffness(const Block& b) {
  std::vector<double> q;
  q.reserve(b.vertex.size());
  for (int i = 0; i < static_cast<int>(b.vertex.size()); ++i) q.push_back(b.K.coeff(i, i) / b.mass[i]);
  if (q.empty()) return 0;
  std::nth_element(q.begin(), q.begin() + q.size() / 2, q.end());
  return q[q.size() / 2];
}

// Where each row's diagonal entry sits in the compressed arrays.
std::vector<int> diagonal_positions(const Eigen::SparseMatrix<double>& K) {
  std::vector<int> pos(size_t(K.cols()), -1);
  for (int c = 0; c < K.cols(); ++c)
    for (int p = K.outerIndexPtr()[c]; p < K.outerIndexPtr()[c + 1]; ++p)
      if (K.innerIndexPtr()[p] == c) pos[c] = p;
  return pos;
}

// A loop as short as a few edges (a small hole in a scan) shrinks towards a point under the 1-D
// flow: its edges' weights (1 / length) grow without bound against their mass (length / 2) and,
// measured on the Cycladic torso scan (49 K boundary vertices), the loop's system could no
// longer be solved from σ = 2.8 edge lengths on. Edges count as at least this share of their
// input length: the loop still contracts, its system stays conditioned.
constexpr double kShortestLoopEdge = 0.1;

// A step whose residual exceeds |b| (what a zero displacement leaves) solved nothing: the system
// was not positive definite. Going on would carry its garbage into every later level (and the
// curves drawn from them), so the run stops and says why.
void require_solution(const SolveReport& rep, double tau) {
  if (rep.residual <= 1) return;
  throw InputError("The surface could not be smoothed to " + std::to_string(std::sqrt(2 * tau)).substr(0, 8) +
                   " (mesh units): the diffusion's system is not positive definite there (" + rep.note +
                   "). Faces folding into slivers cause this; repair the mesh (Remove Duplicate Faces, "
                   "Remove Zero Area Faces, Repair non Manifold Edges) and try again. Nothing was changed.");
}

// The heat operator of one geometry, split into its interior and boundary-loop blocks, with the
// figures of the cost model that chooses explicit or implicit steps per level.
class Diffusion {
 public:
  // Who is what: interior (no boundary neighbour, some area), boundary loop (two boundary
  // neighbours), fixed (the rest).
  Diffusion(const Surface& surface, ScaleSpaceReport& report)
      : topo_(surface.topology()), initial_mass_(surface.laplacian().mass) {
    const int nv = surface.n_vertices();
    kind_.assign(size_t(nv), kFixed);
    index_.assign(size_t(nv), -1);
    for (int v = 0; v < nv; ++v) {
      const int nb = topo_.border.offset[v + 1] - topo_.border.offset[v];
      if (nb == 0 && initial_mass_[v] > 0) {
        kind_[v] = kInterior, index_[v] = int(inner_.vertex.size()), inner_.vertex.push_back(v);
      } else if (nb == 2) {
        kind_[v] = kLoop, index_[v] = int(loop_.vertex.size()), loop_.vertex.push_back(v);
      } else {
        ++report.fixed_vertices;
      }
    }
    report.boundary_vertices = static_cast<int>(loop_.vertex.size());
  }

  // The operator of a geometry (its Laplacian `lap`): the blocks' stiffness and mass, their system
  // matrices' structure, and the cost model's figures.
  void assemble(const TriMesh& geometry, const LaplacianResult& lap) {
    const bool new_pattern = assemble_interior(lap);
    assemble_loop(geometry);
    loop_.K.makeCompressed();
    // The system matrices take their blocks' patterns (step() writes all their values); the
    // interior's is the first level's for the whole run, the loop's is rebuilt with its triplets.
    if (new_pattern) inner_A_ = inner_.K, inner_diag_ = diagonal_positions(inner_.K);
    loop_A_ = loop_.K, loop_diag_ = diagonal_positions(loop_.K);
    inner_.median_stiffness = median_stiffness(inner_), loop_.median_stiffness = median_stiffness(loop_);
    // Cost model of one level, in sparse products: explicit steps need dtau * bound of them;
    // implicit ones about 2 per conjugate-gradient iteration (capped where Cholesky takes over).
    bound_ = std::max(gershgorin_bound(inner_), gershgorin_bound(loop_));
    stiff_ = std::max(inner_.median_stiffness, loop_.median_stiffness);
  }

  // Diffuses the positions x from time tau to target (tau < target), explicitly or implicitly,
  // whichever the cost model says is cheaper (or as `opt.stepping` asks).
  void advance(double tau, double target, const ScaleSpaceOptions& opt, std::vector<Vec3>& x,
               ScaleSpaceReport& report) {
    // `substeps` steps per doubling of the diffusion time (at least that many per level): a level
    // far above the previous one is not crossed by a few huge steps.
    const int substeps = std::max(1, opt.substeps);
    const int steps = tau > 0 ? std::max(substeps, int(std::ceil(substeps * std::log2(target / tau)))) : substeps;
    const double dtau = (target - tau) / steps;
    const double explicit_cost = std::ceil((target - tau) * bound_);
    const double implicit_cost = steps * 2.0 * std::min(kDirectAboveIterations, 5.5 * std::sqrt(1 + dtau * stiff_));
    const bool use_explicit = opt.stepping == ScaleSpaceOptions::Stepping::Explicit ||
                              (opt.stepping == ScaleSpaceOptions::Stepping::Auto && explicit_cost <= implicit_cost &&
                               explicit_cost < 1e7);
    report.level_explicit.push_back(use_explicit);
    if (use_explicit) {
      const long long n = std::max(1LL, static_cast<long long>(explicit_cost));
      const double h = (target - tau) / double(n);
      for (long long s = 0; s < n; ++s) {  // the loop first: the interior reads it
        explicit_steps(loop_, h, 1, x, scratch_);
        explicit_steps(inner_, h, 1, x, scratch_);
      }
      report.explicit_steps += n;
      return;
    }
    for (int s = 0; s < steps; ++s) {
      if (last_dtau_ > 0) inner_D_ *= dtau / last_dtau_, loop_D_ *= dtau / last_dtau_;
      last_dtau_ = dtau;
      for (int which = 0; which < 2; ++which) {  // the loop first: the interior takes it as known
        const Block& b = which == 0 ? loop_ : inner_;
        SolveReport rep = step(b, dtau, which == 0 ? loop_A_ : inner_A_, which == 0 ? loop_diag_ : inner_diag_, x,
                               which == 0 ? loop_D_ : inner_D_, opt);
        if (b.vertex.empty()) continue;
        require_solution(rep, tau + (s + 1) * dtau);
        report.converged = report.converged && rep.converged;
        report.solves.push_back(std::move(rep));
      }
    }
    report.implicit_steps += steps;
  }

 private:
  enum Kind : char { kInterior, kLoop, kFixed };

  // Interior block: K = -L restricted; the weights towards loop and fixed vertices are known terms.
  // Every level's Laplacian has the first one's pattern (the mesh's rings): the pattern is built
  // once, later levels only write their values into it.
  // Returns whether the pattern was (re)built.
  bool assemble_interior(const LaplacianResult& lap) {
    const bool new_pattern = interior_slot_.size() != size_t(lap.L.nonZeros());
    if (new_pattern) build_interior_pattern(lap);
    const int n = static_cast<int>(inner_.vertex.size());
    const Eigen::VectorXd old_mass = inner_.mass;
    inner_.mass.resize(n);
    double* k = inner_.K.valuePtr();
#pragma omp parallel for schedule(static)
    for (int i = 0; i < n; ++i) {
      const int v = inner_.vertex[i];
      // A vertex whose area vanished on the way keeps its last one (the system stays definite).
      inner_.mass[i] = lap.mass[v] > 0 ? lap.mass[v] : old_mass.size() == n ? old_mass[i] : initial_mass_[v];
      for (int e = lap.L.outerIndexPtr()[v]; e < lap.L.outerIndexPtr()[v + 1]; ++e) {
        const long slot = interior_slot_[size_t(e)];
        if (slot >= 0) k[slot] = -lap.L.valuePtr()[e];
        else inner_.known[i][size_t(-slot - 1)].second = -lap.L.valuePtr()[e];  // a stiffness entry, like the loop block's
      }
    }
    return new_pattern;
  }

  // Where each entry of the Laplacian goes: a position in K's values, or (-1 - k) for the k-th
  // known term of its row.
  void build_interior_pattern(const LaplacianResult& lap) {
    const int n = static_cast<int>(inner_.vertex.size());
    std::vector<Eigen::Triplet<double>> trip;
    inner_.known.assign(size_t(n), {});
    for (int i = 0; i < n; ++i)
      for (Eigen::SparseMatrix<double>::InnerIterator it(lap.L, inner_.vertex[i]); it; ++it) {
        const int u = static_cast<int>(it.row());
        if (kind_[u] == kInterior) trip.emplace_back(i, index_[u], 1.0);
        else inner_.known[i].push_back({u, 0.0});
      }
    inner_.K.resize(n, n);
    inner_.K.setFromTriplets(trip.begin(), trip.end());
    inner_.K.makeCompressed();
    interior_slot_.assign(size_t(lap.L.nonZeros()), 0);
    for (int i = 0; i < n; ++i) {
      int known = 0;
      const int v = inner_.vertex[i];
      for (int e = lap.L.outerIndexPtr()[v]; e < lap.L.outerIndexPtr()[v + 1]; ++e) {
        const int u = lap.L.innerIndexPtr()[e];
        if (kind_[u] != kInterior) {
          interior_slot_[size_t(e)] = -1 - known++;
          continue;
        }
        const int column = index_[u];
        const int* first = inner_.K.innerIndexPtr() + inner_.K.outerIndexPtr()[column];
        const int* last = inner_.K.innerIndexPtr() + inner_.K.outerIndexPtr()[column + 1];
        interior_slot_[size_t(e)] = std::lower_bound(first, last, i) - inner_.K.innerIndexPtr();
      }
    }
  }

  // Loop block: 1-D stiffness along the boundary polylines, weight 1 / edge length, mass half the
  // adjacent boundary edges. An edge counts as at least kShortestLoopEdge of its input length.
  void assemble_loop(const TriMesh& geometry) {
    const int n = static_cast<int>(loop_.vertex.size());
    const bool first = loop_input_length_.empty();
    if (first) loop_input_length_.resize(topo_.border.vertex.size());
    std::vector<Eigen::Triplet<double>> trip;
    loop_.mass.setZero(n);
    loop_.known.assign(size_t(n), {});
    for (int i = 0; i < n; ++i) {
      const int v = loop_.vertex[i];
      double diag = 0;
      for (int k = topo_.border.offset[v]; k < topo_.border.offset[v + 1]; ++k) {
        const int u = topo_.border.vertex[k];
        double len = (geometry.vertices[v] - geometry.vertices[u]).norm();
        if (first) loop_input_length_[size_t(k)] = len;
        len = std::max(len, kShortestLoopEdge * loop_input_length_[size_t(k)]);
        if (!(len > 0)) continue;
        loop_.mass[i] += 0.5 * len;
        diag += 1 / len;
        if (kind_[u] == kLoop) trip.emplace_back(i, index_[u], -1 / len);
        else loop_.known[i].push_back({u, -1 / len});  // K_known has the sign of the stiffness
      }
      trip.emplace_back(i, i, diag);
      if (!(loop_.mass[i] > 0)) loop_.mass[i] = 1;  // a loop of coincident points: stays put
    }
    loop_.K.resize(n, n);
    loop_.K.setFromTriplets(trip.begin(), trip.end());
  }

  const MeshTopology& topo_;
  const Eigen::VectorXd& initial_mass_;  // the input's vertex areas (the run's Surface keeps them)
  std::vector<char> kind_;
  std::vector<int> index_;
  Block inner_, loop_;
  std::vector<double> loop_input_length_;  // per border entry: the input's edge length
  std::vector<long> interior_slot_;  // per Laplacian entry: its place in inner_.K or inner_.known
  Eigen::SparseMatrix<double> inner_A_, loop_A_;
  std::vector<int> inner_diag_, loop_diag_;
  double bound_ = 0, stiff_ = 0;
  std::vector<Vec3> scratch_;
  Eigen::MatrixXd inner_D_, loop_D_;  // the last implicit step's displacements (the next one's guess)
  double last_dtau_ = 0;
};

}  // namespace

ScaleSpaceReport scale_space(const Surface& surface, const std::vector<double>& sigmas, const ScaleSpaceOptions& opt,
                             const ScaleSpaceVisitor& visit) {
  surface.require_triangles();
  for (size_t k = 0; k < sigmas.size(); ++k)
    if (!(sigmas[k] > 0) || !std::isfinite(sigmas[k]) || (k > 0 && !(sigmas[k] > sigmas[k - 1])))
      throw InputError("scale space: the scales must be positive, finite and increasing");
  ScaleSpaceReport report;
  Diffusion diffusion(surface, report);
  diffusion.assemble(surface.mesh(), surface.laplacian());
  Surface level = surface;  // the last level reached
  std::vector<Vec3> x = surface.mesh().vertices;
  double tau = 0;
  for (size_t k = 0; k < sigmas.size(); ++k) {
    if (opt.progress) opt.progress(int(100 * k / sigmas.size()), "Scale space");
    if (k > 0 && opt.reweight) diffusion.assemble(level.mesh(), level.laplacian());
    const double target = 0.5 * sigmas[k] * sigmas[k];
    diffusion.advance(tau, target, opt, x, report);
    tau = target;
    level = surface.with_positions(x);
    visit(static_cast<int>(k), level);
  }
  return report;
}

ScaleSpaceReport scale_space(const TriMesh& mesh, const std::vector<double>& sigmas, const ScaleSpaceOptions& opt,
                             const ScaleSpaceVisitor& visit) {
  return scale_space(Surface::borrow(mesh), sigmas, opt, visit);
}

}  // namespace reliefkit
