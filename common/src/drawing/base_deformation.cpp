// ReliefKit — deformation of the base model to the drawing's outlines (thesis sect. 7.5, eq. 7.7
// and 7.8): the model placed on the outlines, its silhouette vertices pulled to them while its
// uniform Laplacian coordinates are kept, one Cholesky solve per pass. See base_library.h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "reliefkit/base/coarsening.h"
#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/solvers.h"
#include "reliefkit/base/surface.h"
#include "reliefkit/drawing/base_library.h"
#include "silhouette_raster.h"

namespace reliefkit {
namespace {
using silhouette::Raster;
using silhouette::view_axes;

struct Box2 {
  Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  void add(const Vec2& p) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
  Vec2 size() const { return hi - lo; }
  Vec2 centre() const { return 0.5 * (hi + lo); }
};
Box2 box_of(const Outline& o) {
  Box2 b;
  for (const auto& p : o) b.add(p);
  return b;
}

// The world point with the view's two coordinates set to `m` and the depth of `p` kept (the
// inverse of view_coordinates on the view's axes).
Vec3 with_view_coordinates(ViewKind view, Vec3 p, const Vec2& m) {
  const auto axes = view_axes(view);
  for (int k = 0; k < 2; ++k) {
    const int a = std::abs(axes[size_t(k)]) - 1;
    p[a] = axes[size_t(k)] > 0 ? m[k] : -m[k];
  }
  return p;
}
}  // namespace

std::vector<ViewOutline> round_object_views(const std::vector<ViewOutline>& views) {
  std::vector<ViewOutline> fit = views;
  if (views.size() == 1 && views[0].kind != ViewKind::Top)
    fit.push_back({views[0].kind == ViewKind::Front ? ViewKind::Side : ViewKind::Front, views[0].outline});
  return fit;
}

TriMesh place_on_outlines(const TriMesh& model, const std::vector<ViewOutline>& views) {
  if (views.empty()) return model;
  double log_scale = 0;
  int n = 0;
  for (const auto& v : views) {
    const Box2 m = box_of(mesh_outline(model, v.kind, 512)), d = box_of(v.outline);
    for (int k = 0; k < 2; ++k)
      if (m.size()[k] > 0 && d.size()[k] > 0) { log_scale += std::log(d.size()[k] / m.size()[k]); ++n; }
  }
  const double s = n > 0 ? std::exp(log_scale / n) : 1.0;
  TriMesh out = model;
  for (auto& p : out.vertices) p *= s;
  Vec3 shift = Vec3::Zero(), count = Vec3::Zero();
  for (const auto& v : views) {
    const Vec2 d = box_of(v.outline).centre() - box_of(mesh_outline(out, v.kind, 512)).centre();
    const auto axes = view_axes(v.kind);
    for (int k = 0; k < 2; ++k) {
      const int a = std::abs(axes[size_t(k)]) - 1;
      shift[a] += (axes[size_t(k)] > 0 ? 1 : -1) * d[k];
      count[a] += 1;
    }
  }
  for (int a = 0; a < 3; ++a)
    if (count[a] > 0) shift[a] /= count[a];
  for (auto& p : out.vertices) p += shift;
  return out;
}

double silhouette_error(const TriMesh& mesh, const std::vector<ViewOutline>& views, int resolution) {
  double worst = 0;
  for (const auto& v : views) {
    const double diag = outline_diagonal(v.outline);
    if (!(diag > 0)) continue;
    worst = std::max(worst, outline_hausdorff(mesh_outline(mesh, v.kind, resolution), v.outline) / diag);
  }
  return worst;
}

namespace {
constexpr double kAnchor = 1e-6;  // keeps vertices of parts no view constrains where they are

// What stays the same in every pass for finding the model's silhouettes: its edges, its mean
// edge and each view's outline densely sampled.
struct SilhouetteSetting {
  std::vector<MeshEdge> edges;           // for the contour generators
  double edge = 0;                       // mean edge length: raster size and matching slack
  std::vector<std::vector<Vec2>> dense;  // each view's outline, densely sampled
};

SilhouetteSetting silhouette_setting(const Surface& model, const std::vector<ViewOutline>& views) {
  SilhouetteSetting s;
  s.edges = mesh_edges(model.mesh(), model.topology().faces);
  s.edge = edge_length_stats(model.mesh()).mean;
  for (const auto& v : views) s.dense.push_back(silhouette::densify(v.outline, outline_diagonal(v.outline) / 3000));
  return s;
}

// What stays the same in every pass of the solve: the Laplacian coordinates (eq. 7.7) of the mesh
// solved for — the model, or its coarse copy.
struct LaplacianSystem {
  Eigen::SparseMatrix<double> L, LtL;
  Eigen::MatrixXd V0, delta;  // the positions and their Laplacian coordinates
};

LaplacianSystem laplacian_system(const TriMesh& mesh, const VertexRing& ring) {
  LaplacianSystem s;
  s.L = uniform_laplacian(ring);
  s.LtL = (s.L.transpose() * s.L).pruned();
  s.V0.resize(mesh.n_vertices(), 3);
  for (int i = 0; i < mesh.n_vertices(); ++i) s.V0.row(i) = mesh.vertices[size_t(i)].transpose();
  s.delta = s.L * s.V0;
  return s;
}

// Unnormalised face normals of the current shape.
std::vector<Vec3> face_normals(const TriMesh& mesh) {
  std::vector<Vec3> fn(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    fn[f] = (mesh.vertices[size_t(t[1])] - mesh.vertices[size_t(t[0])]).cross(mesh.vertices[size_t(t[2])] - mesh.vertices[size_t(t[0])]);
  }
  return fn;
}

// Vertices of the contour generators seen along the world axis `depth`: ends of border edges and
// of edges with one face towards the view and the other away (a face seen edge-on is neither).
std::vector<char> contour_vertices(int n, const std::vector<MeshEdge>& edges, const std::vector<Vec3>& fn, int depth) {
  std::vector<char> on(size_t(n), 0);
  for (const auto& e : edges) {
    bool contour = e.faces != 2;
    if (!contour) {
      const double a = fn[size_t(e.face[0])][depth], b = fn[size_t(e.face[1])][depth];
      contour = (a > 0 && b < 0) || (a < 0 && b > 0);
    }
    if (contour) on[size_t(e.a)] = on[size_t(e.b)] = 1;
  }
  return on;
}

// The model's silhouette in one view: its raster and the contour vertices on the raster's rim.
struct ViewSilhouette {
  Raster raster;
  Outline own;               // the model's outline (world units)
  std::vector<int> vertex;   // silhouette vertices
  std::vector<Vec2> at;      // their view coordinates
};

ViewSilhouette view_silhouette(const TriMesh& current, const std::vector<char>& candidate, ViewKind view, double edge,
                               int resolution) {
  ViewSilhouette s;
  Box2 ext;
  for (const auto& p : current.vertices) ext.add(view_coordinates(view, p));
  const double extent = std::max(ext.size().x(), ext.size().y());
  const int res = resolution > 0 ? resolution : std::clamp(int(2 * extent / std::max(edge, 1e-300)), 256, 2048);
  const auto axes = view_axes(view);
  s.raster = silhouette::rasterize(current, axes[0], axes[1], res);
  if (s.raster.mask.empty()) return s;
  cv::Mat dist;
  cv::distanceTransform(s.raster.mask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const double tol = 1.5 + 0.5 * edge * s.raster.scale;
  for (int i = 0; i < current.n_vertices(); ++i) {
    if (!candidate[size_t(i)]) continue;
    const Vec2 q = view_coordinates(view, current.vertices[size_t(i)]);
    const Vec2 px = s.raster.to_pixel(q);
    const int x = std::clamp(int(px.x()), 0, dist.cols - 1), y = std::clamp(int(px.y()), 0, dist.rows - 1);
    if (dist.at<float>(y, x) <= tol) {
      s.vertex.push_back(i);
      s.at.push_back(q);
    }
  }
  s.own = silhouette::raster_outline(s.raster);
  return s;
}

// Normal of the closed outline `own` at its point nearest to p (zero for a short outline).
Vec2 outline_normal_near(const Outline& own, const Vec2& p) {
  if (own.size() <= 8) return Vec2::Zero();
  size_t at = 0;
  double best = 1e300;
  for (size_t k = 0; k < own.size(); ++k) {
    const double d = (own[k] - p).squaredNorm();
    if (d < best) { best = d; at = k; }
  }
  const size_t m = own.size();
  const Vec2 tangent = own[(at + 3) % m] - own[(at + m - 3) % m];
  return tangent.norm() > 0 ? Vec2(-tangent.y(), tangent.x()).normalized() : Vec2::Zero();
}

// The nearest crossing of the line p + t normal with the drawn outline, |t| < reach; false if none.
bool crossing_along(const Vec2& p, const Vec2& normal, const Outline& drawn, double reach, Vec2& hit) {
  if (normal.squaredNorm() == 0) return false;
  double tbest = reach;
  bool found = false;
  for (size_t k = 0; k < drawn.size(); ++k) {
    const Vec2 a = drawn[k], e = drawn[(k + 1) % drawn.size()] - a;
    const double den = normal.x() * e.y() - normal.y() * e.x();  // cross(normal, e)
    if (std::abs(den) < 1e-300) continue;
    const Vec2 w = a - p;
    const double t = (w.x() * e.y() - w.y() * e.x()) / den;            // along the normal
    const double u = (w.x() * normal.y() - w.y() * normal.x()) / den;  // along the segment
    if (u < 0 || u > 1 || std::abs(t) >= std::abs(tbest)) continue;
    tbest = t;
    found = true;
  }
  if (found) hit = p + tbest * normal;
  return found;
}

Vec2 closest_point(const std::vector<Vec2>& points, const Vec2& p) {
  double best = 1e300;
  Vec2 at = p;
  for (const auto& d : points) {
    const double dd = (d - p).squaredNorm();
    if (dd < best) { best = dd; at = d; }
  }
  return at;
}

// Each silhouette vertex matched to the drawing's outline along the normal of the model's own
// outline at the vertex (the nearest crossing either way; the thesis' closest point when the normal
// crosses no line within a quarter of the outline's size): closest points alone leave a concave
// part the model lacks (a goblet's stem) unreached.
std::vector<Vec2> matches_along_normals(const ViewSilhouette& s, const Outline& drawn, const std::vector<Vec2>& dense) {
  const double reach = 0.25 * outline_diagonal(drawn);
  std::vector<Vec2> match(s.at.size());
#pragma omp parallel for schedule(static)
  for (long k = 0; k < long(s.at.size()); ++k) {
    const Vec2 p = s.at[size_t(k)];
    if (!crossing_along(p, outline_normal_near(s.own, p), drawn, reach, match[size_t(k)]))
      match[size_t(k)] = closest_point(dense, p);
  }
  return match;
}

// Each outline point pulls its closest silhouette vertex (so parts no normal reaches, a corner,
// are covered too), but only when that vertex is about as close as the model's outline itself:
// where the outline runs along faces seen edge-on (a flat lid seen from the side) the nearest
// silhouette vertex can be far, and must not be dragged along. -1: the point pulls none.
std::vector<int> outline_pulls(const ViewSilhouette& s, const std::vector<Vec2>& dense, double edge) {
  std::vector<int> chosen(dense.size(), -1);
  if (s.at.empty()) return chosen;
  const double slack = 2 * edge;  // 5 or 10 edges: the goblet closer (2.8 %, 1.2 %), a bowl's one solve worse
#pragma omp parallel for schedule(static)
  for (long j = 0; j < long(dense.size()); ++j) {
    const Vec2& d = dense[size_t(j)];
    double best = 1e300, own_best = 1e300;
    int at = -1;
    for (size_t k = 0; k < s.at.size(); ++k) {
      const double dd = (d - s.at[k]).squaredNorm();
      if (dd < best) { best = dd; at = int(k); }
    }
    for (const auto& o : s.own) own_best = std::min(own_best, (d - o).squaredNorm());
    if (s.own.empty() || std::sqrt(best) <= std::sqrt(own_best) + slack) chosen[size_t(j)] = at;
  }
  return chosen;
}

// Where the silhouette vertices should go in the world (W: targets per vertex, V': their sum).
struct Targets {
  Eigen::VectorXd weight;
  Eigen::MatrixXd sum;
  int constrained = 0;
};

// Adds one view's targets: a vertex's target is the mean of its own match and of the outline
// points that chose it, its depth kept.
void add_view_targets(const TriMesh& current, const ViewOutline& view, const ViewSilhouette& s,
                      const std::vector<Vec2>& dense, double edge, Targets& t) {
  const std::vector<Vec2> match = matches_along_normals(s, view.outline, dense);
  const std::vector<int> chosen = outline_pulls(s, dense, edge);
  std::vector<Vec2> back_sum(s.vertex.size(), Vec2::Zero());
  std::vector<int> back_count(s.vertex.size(), 0);
  for (size_t j = 0; j < dense.size(); ++j)
    if (chosen[j] >= 0) { back_sum[size_t(chosen[j])] += dense[j]; ++back_count[size_t(chosen[j])]; }
  for (size_t k = 0; k < s.vertex.size(); ++k) {
    const int i = s.vertex[k];
    Vec2 m = match[k];
    if (back_count[k] > 0) m = 0.5 * (m + back_sum[k] / back_count[k]);
    t.weight[i] += 1;
    t.sum.row(i) += with_view_coordinates(view.kind, current.vertices[size_t(i)], m).transpose();
    ++t.constrained;
  }
}

Targets silhouette_targets(const TriMesh& current, const SilhouetteSetting& sys, const std::vector<ViewOutline>& views,
                           int resolution) {
  const int n = current.n_vertices();
  Targets t{Eigen::VectorXd::Zero(n), Eigen::MatrixXd::Zero(n, 3), 0};
  const std::vector<Vec3> fn = face_normals(current);
  for (size_t vi = 0; vi < views.size(); ++vi) {
    const auto candidate = contour_vertices(n, sys.edges, fn, view_depth_axis(views[vi].kind));
    const ViewSilhouette s = view_silhouette(current, candidate, views[vi].kind, sys.edge, resolution);
    if (s.raster.mask.empty()) continue;
    add_view_targets(current, views[vi], s, sys.dense[vi], sys.edge, t);
  }
  return t;
}

// eq. 7.8's silhouette term, sum of w_i |x_i - t_i|^2 over the pulled vertices, in the solve's
// unknowns X as (M, B) of its normal equations: on the model x = X, so M = W and B = sum of w t;
// on the coarse copy x_i = m_i + P_i (X - V0) (m: the model's rest positions, V0: the copy's), so
// M = Psᵀ W Ps and B = Psᵀ W (t - m + Ps V0) — M within the pattern of PᵀP.
struct PullTerm {
  Eigen::SparseMatrix<double> M;
  Eigen::MatrixXd B;
};

PullTerm pull_on_model(const Targets& t) {
  PullTerm pull{Eigen::SparseMatrix<double>(t.weight.size(), t.weight.size()), t.sum};
  pull.M.setIdentity();
  pull.M = pull.M * t.weight.asDiagonal();
  return pull;
}

// The model and its coarse copy: the copy's vertices are the solve's unknowns, the model moves as
// the copy does (P, coarsening.h).
struct CoarseCopy {
  CoarseMesh coarse;
  Interpolation P;
};

PullTerm pull_on_copy(const Targets& t, const TriMesh& model, const CoarseCopy& copy, const Eigen::MatrixXd& V0) {
  std::vector<int> pulled;
  for (int i = 0; i < model.n_vertices(); ++i)
    if (t.weight[i] > 0) pulled.push_back(i);
  const long k = long(pulled.size());
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd w(k);
  Eigen::MatrixXd b(k, 3);
  for (long r = 0; r < k; ++r) {
    const int i = pulled[size_t(r)];
    for (Interpolation::InnerIterator it(copy.P, i); it; ++it) entries.emplace_back(int(r), int(it.col()), it.value());
    w[r] = t.weight[i];
    b.row(r) = t.sum.row(i) / t.weight[i] - model.vertices[size_t(i)].transpose();
  }
  Eigen::SparseMatrix<double> Ps(k, V0.rows());
  Ps.setFromTriplets(entries.begin(), entries.end());
  b += Ps * V0;
  const Eigen::SparseMatrix<double> PsT = Ps.transpose();
  const Eigen::SparseMatrix<double> WPs = w.asDiagonal() * Ps;
  return {PsT * WPs, PsT * (w.asDiagonal() * b)};
}

// One solve of eq. 7.8's normal equations: (alpha LtL + M + eps) X = alpha Lt delta_ref + B + eps V0.
Eigen::MatrixXd solve_pass(const LaplacianSystem& sys, const PullTerm& pull, const Eigen::MatrixXd& Ltdelta_ref,
                           double alpha, SpdFactorization& factorization, std::string& summary) {
  Eigen::SparseMatrix<double> anchor(sys.LtL.rows(), sys.LtL.cols());
  anchor.setIdentity();
  // A sum, not coeffRef: a vertex of the coarse copy in no face has no diagonal entry in LtL.
  const Eigen::SparseMatrix<double> A = alpha * sys.LtL + pull.M + kAnchor * anchor;
  const Eigen::MatrixXd B = alpha * Ltdelta_ref + pull.B + kAnchor * sys.V0;
  Eigen::MatrixXd X;
  SolverOptions o;
  o.label = "Least-squares solve (Cholesky)";
  const SolveReport rep = solve_spd(A, B, X, factorization, o);
  // A numerical failure, not the user's input: reported as an internal error.
  if (!rep.converged)
    throw std::runtime_error("the deformation's least-squares solve failed (" + rep.note +
                             "; the model may be too large for the memory).");
  summary = rep.summary();
  return X;
}

void check_deform_input(const Surface& model, const std::vector<ViewOutline>& views, const DeformParams& params) {
  model.require_triangles();
  if (!(params.alpha > 0) || !std::isfinite(params.alpha))
    throw InputError("Shape weight (alpha) must be a positive number.");
  if (params.passes < 1 || params.passes > 20) throw InputError("Passes must be between 1 and 20.");
  for (const auto& p : model.mesh().vertices)
    if (!p.allFinite()) throw InputError("The model has vertices without coordinates (NaN).");
  for (const auto& v : views)
    if (v.outline.size() < 3) throw InputError(std::string("The ") + view_name(v.kind) + " view has no outline.");
}

std::vector<Vec3> positions_of(const Eigen::MatrixXd& X) {
  std::vector<Vec3> out(size_t(X.rows()));
  for (long i = 0; i < X.rows(); ++i) out[size_t(i)] = X.row(i).transpose();
  return out;
}

// The model's positions moved as its coarse copy was (X against the copy's rest positions V0).
std::vector<Vec3> moved_as_copy(const TriMesh& model, const CoarseCopy& copy, const Eigen::MatrixXd& X,
                                const Eigen::MatrixXd& V0) {
  const Eigen::MatrixXd shift = copy.P * (X - V0);
  std::vector<Vec3> out = model.vertices;
  for (size_t i = 0; i < out.size(); ++i) out[i] += shift.row(long(i)).transpose();
  return out;
}

// RMS |L(v') - L(v)| / RMS |L(v)| of the model's uniform Laplacian coordinates.
double laplacian_change(const Surface& model, const TriMesh& moved) {
  const Eigen::SparseMatrix<double> L = uniform_laplacian(model.topology().ring);
  Eigen::MatrixXd V0(moved.n_vertices(), 3), V1(moved.n_vertices(), 3);
  for (int i = 0; i < moved.n_vertices(); ++i) {
    V0.row(i) = model.mesh().vertices[size_t(i)].transpose();
    V1.row(i) = moved.vertices[size_t(i)].transpose();
  }
  const Eigen::MatrixXd delta = L * V0;
  const double d0 = delta.norm();
  return d0 > 0 ? (L * V1 - delta).norm() / d0 : 0;
}

using StageProgress = std::function<void(int percent, const char* what)>;

// Another pass while the last three brought the silhouette closer by 0.2 % of the outline's size
// (a large change can get worse for a pass before it gets better).
bool still_improving(std::vector<double>& history, const TriMesh& current, const std::vector<ViewOutline>& views) {
  history.push_back(silhouette_error(current, views, 512));
  if (history.back() < 2e-3) return false;
  return history.size() < 4 || history[history.size() - 4] - history.back() >= 2e-3;
}

// The passes: the model's silhouettes found on the model, the least-squares solve on the model
// itself (coarse null: the thesis' method) or on its coarse copy (the model then moved as the copy).
TriMesh deform_in_passes(const Surface& model, const CoarseCopy* copy, const std::vector<ViewOutline>& views,
                         const DeformParams& params, DeformReport& rep, const StageProgress& progress) {
  progress(2, "Laplacian coordinates");
  const SilhouetteSetting setting = silhouette_setting(model, views);
  const TriMesh* coarse = copy ? &copy->coarse.mesh : nullptr;
  const LaplacianSystem sys = coarse ? laplacian_system(*coarse, vertex_rings(*coarse, vertex_faces(*coarse)))
                                     : laplacian_system(model.mesh(), model.topology().ring);
  // On the model the pattern is the same in every pass: ordered once. For a single pass AMD
  // (measured on a 117 K-face jug: 0.07 s to order, 0.73 s to factor); for several, CHOLMOD's own
  // choice (0.7 s to order, but 0.5 s per factorization). On the copy the pull's pattern follows
  // the silhouette, so each pass is ordered again: AMD, quick on a copy of <= 20 K faces.
  SpdFactorization factorization(params.passes == 1 || copy ? SpdFactorization::Ordering::Amd : SpdFactorization::Ordering::Best);
  Eigen::MatrixXd Ltdelta_ref = sys.L.transpose() * sys.delta, X = sys.V0;
  Surface current = model;
  std::vector<double> history;  // silhouette error after each pass
  for (int pass = 0; pass < params.passes; ++pass) {
    const int p0 = 5 + 90 * pass / params.passes, p1 = 5 + 90 * (pass + 1) / params.passes;
    progress(p0, "Silhouette of the model");
    const Targets targets = silhouette_targets(current.mesh(), setting, views, params.resolution);
    rep.silhouette_vertices = targets.constrained;
    progress((p0 + p1) / 2, "Least-squares solve (Cholesky)");
    // The first pass is the thesis' solve; a further pass keeps the Laplacian coordinates of the
    // pass before (the deformation grows in steps, so that a large change — a cylinder made a
    // goblet — is reached, not just begun).
    const PullTerm pull = copy ? pull_on_copy(targets, model.mesh(), *copy, sys.V0) : pull_on_model(targets);
    X = solve_pass(sys, pull, Ltdelta_ref, params.alpha, factorization, rep.solver);
    current = model.with_positions(copy ? moved_as_copy(model.mesh(), *copy, X, sys.V0) : positions_of(X));
    rep.passes = pass + 1;
    if (pass + 1 == params.passes || !still_improving(history, current.mesh(), views)) break;
    Ltdelta_ref = sys.L.transpose() * (sys.L * X);
  }
  rep.solver += "; " + std::to_string(factorization.factorizations()) + " factorization(s) in " + std::to_string(rep.passes) +
                " pass(es)";
  return current.mesh();
}
}  // namespace

TriMesh deform_to_outlines(const Surface& model, const std::vector<ViewOutline>& views, const DeformParams& params,
                           DeformReport* report) {
  check_deform_input(model, views, params);
  const StageProgress progress = [&](int pc, const char* what) { if (params.progress) params.progress(pc, what); };
  DeformReport rep;
  rep.hausdorff_before = silhouette_error(model.mesh(), views);
  // A large model's passes solve on a coarse copy (coarsening.h): the displacement is smooth over
  // the surface and the model's detail rides on it, and a pass then factorizes a fraction of the
  // model's system. Its silhouettes are still the model's own.
  CoarseCopy copy;
  const bool on_copy = params.passes > 1 && params.coarse_faces > 0 && model.mesh().n_faces() > 2 * params.coarse_faces;
  if (on_copy) {
    progress(1, "Coarse copy of the model");
    copy.coarse = coarsen_mesh(model.mesh(), params.coarse_faces);
    copy.P = interpolation_from_coarse(model.mesh(), copy.coarse);
    rep.coarse_faces = copy.coarse.mesh.n_faces();
  }
  const TriMesh out = deform_in_passes(model, on_copy ? &copy : nullptr, views, params, rep, progress);
  if (on_copy) rep.solver += " on a coarse copy of " + std::to_string(rep.coarse_faces) + " faces";
  progress(97, "Measuring the result");
  rep.laplacian_change = laplacian_change(model, out);
  rep.hausdorff_after = silhouette_error(out, views);
  if (report) *report = rep;
  progress(100, "Deformed");
  return out;
}

TriMesh deform_to_outlines(const TriMesh& model, const std::vector<ViewOutline>& views, const DeformParams& params,
                           DeformReport* report) {
  return deform_to_outlines(Surface::borrow(model), views, params, report);
}

std::string base_fit_warning(const DeformReport& report) {
  if (!(report.hausdorff_after > kPoorBaseFit)) return "";
  char figures[96];
  std::snprintf(figures, sizeof figures, "%.1f %% of the outline's size off the drawing (more than %.0f %%)",
                100 * report.hausdorff_after, 100 * kPoorBaseFit);
  return std::string("Warning: the base stays ") + figures + ": the model could not be bent to this outline. Try another "
         "match (Use model), a second view, or check the outline (a drawing cut by the image's border, text run into it).";
}

}  // namespace reliefkit
