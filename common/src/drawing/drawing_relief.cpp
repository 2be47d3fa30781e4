#include "reliefkit/drawing/drawing_relief.h"

#include <opencv2/imgproc.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <limits>

#include "reliefkit/base/curvature.h"
#include "reliefkit/base/laplacian.h"
#include "reliefkit/base/scale.h"
#include "reliefkit/base/surface.h"

namespace reliefkit {

void DrawingReliefParams::validate() const {
  require_range(shading_depth, "Shading engraved (steps)", 0, 100);
  require_range(margin, "Margin width (px)", 0.5, 1000);
  require_range(step_height, "Step height", 1e-12, 1e12);
  require_range(pixel_size, "Pixel size", 1e-12, 1e12);
}

TriMesh drawing_grid(int width, int height, double cell, double pixel_size, int x0, int y0) {
  if (width < 2 || height < 2) throw InputError("The drawing is too small for a relief (at least 2 x 2 pixels).");
  require_range(cell, "Grid cell (px)", 0.1, 1e6);
  const int nx = std::max(2, int(std::ceil((width - 1) / cell)) + 1), ny = std::max(2, int(std::ceil((height - 1) / cell)) + 1);
  TriMesh m;
  m.vertices.reserve(size_t(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double px = x0 + std::min(i * cell, double(width - 1)), py = y0 + std::min(j * cell, double(height - 1));
      m.vertices.push_back(Vec3(px * pixel_size, -py * pixel_size, 0));
    }
  m.faces.reserve(size_t(nx - 1) * (ny - 1) * 2);
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      // Counter-clockwise seen from +z (y up in mesh units; image rows go down).
      m.faces.push_back({a, d, b});
      m.faces.push_back({a, c, d});
    }
  return m;
}

cv::Rect drawing_extent(const DrawingCurves& dc, double pad) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& c : dc.curves)
    for (const auto& q : c) x0 = std::min(x0, q.x()), y0 = std::min(y0, q.y()), x1 = std::max(x1, q.x()), y1 = std::max(y1, q.y());
  if (x0 > x1) return cv::Rect(0, 0, dc.width, dc.height);
  const int a = std::max(0, int(std::floor(x0 - pad))), b = std::max(0, int(std::floor(y0 - pad)));
  const int c = std::min(dc.width - 1, int(std::ceil(x1 + pad))), d = std::min(dc.height - 1, int(std::ceil(y1 + pad)));
  return cv::Rect(a, b, std::max(2, c - a + 1), std::max(2, d - b + 1));
}

double drawing_cell(const DrawingInterpretation& di, double margin) {
  double cell = margin / 2;
  if (di.region_count > 0 && !di.regions.empty()) {
    const cv::Mat free = di.regions >= 0;
    cv::Mat dist;
    cv::distanceTransform(free, dist, cv::DIST_L2, cv::DIST_MASK_5);
    std::vector<float> widest(size_t(di.region_count), 0.f);
    for (int y = 0; y < dist.rows; ++y) {
      const int* lab = di.regions.ptr<int>(y);
      const float* d = dist.ptr<float>(y);
      for (int x = 0; x < dist.cols; ++x)
        if (lab[x] >= 0) widest[size_t(lab[x])] = std::max(widest[size_t(lab[x])], d[x]);
    }
    // The regions that take part: those some step borders.
    std::vector<char> used(size_t(di.region_count), 0);
    for (size_t k = 0; k < di.sides.size(); ++k)
      if (k < di.step.size() && di.step[k] != 0)
        for (int r : di.sides[k])
          if (r >= 0) used[size_t(r)] = 1;
    std::vector<float> w;
    for (int r = 0; r < di.region_count; ++r)
      if (used[size_t(r)]) w.push_back(2 * widest[size_t(r)]);
    if (!w.empty()) {
      std::nth_element(w.begin(), w.begin() + long(w.size() / 100), w.end());
      cell = std::min(cell, 0.25 * w[w.size() / 100]);
    }
  }
  return std::max(0.5, cell);
}

TriMesh relief_surface(const TriMesh& grid, const std::vector<double>& height, DrawingBase base, double circumference,
                       double front) {
  TriMesh m = grid;
  if (base == DrawingBase::Plane) {
    for (int v = 0; v < m.n_vertices(); ++v) m.vertices[v].z() = height[size_t(v)];
    return m;
  }
  require_range(circumference, "Cylinder circumference", 1e-12, 1e12);
  const double R = circumference / (2 * 3.14159265358979323846);
  for (int v = 0; v < m.n_vertices(); ++v) {
    const Vec3 g = grid.vertices[v];
    const double a = (g.x() - front) / R, r = R + height[size_t(v)];
    m.vertices[v] = Vec3(r * std::sin(a), g.y(), r * std::cos(a));  // outward normal (sin a, 0, cos a): faces stay outward
  }
  return m;
}

namespace {

// The step's profile s(t), t in [-1, 1] (eq. 7.1): 0 to 1 with zero first and second derivatives
// at both ends, so that the Laplacian of r vanishes where the margin meets the free surface. (A
// tanh cut at the margin left a curvature of 0.27 / w^2 there, which eq. 7.4 carried into whole
// regions: 8 steps of bulge on the test drawing.)
double step_profile(double t) {
  t = std::clamp(t, -1.0, 1.0);
  return 0.5 + (15 * t - 10 * t * t * t + 3 * t * t * t * t * t) / 16;
}

// Each margin is held over kFlatBand x its width: the profile within w of the curve, flat beyond.
// The thin plate continues the curvature it meets at the band's edge; with the profile alone
// (two grid rows on either side) the raised discs of the test drawing bulged by two steps and the
// ground between them sagged by one.
constexpr double kFlatBand = 4.0;

// A free-form shape (samples (t, value), t increasing) at t: linear between samples, constant
// beyond the first and last.
double free_form(const std::vector<Vec2>& shape, double t) {
  if (t <= shape.front().x()) return shape.front().y();
  for (size_t i = 1; i < shape.size(); ++i)
    if (t <= shape[i].x()) {
      const double a = (t - shape[i - 1].x()) / (shape[i].x() - shape[i - 1].x());
      return (1 - a) * shape[i - 1].y() + a * shape[i].y();
    }
  return shape.back().y();
}

// K_FF x_F = rhs_F for the free vertices of the SPD stiffness K (+ a tiny mass term, so that a
// part without any fixed vertex still has a unique solution).
SolveReport solve_free(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass, const std::vector<int>& free_of,
                       int nfree, const Eigen::VectorXd& rhs_free, Eigen::VectorXd& x_free, const Eigen::VectorXd& guess,
                       SolverMethod method) {
  // The free rows and columns of K, column by column (free indices increase with the vertex index,
  // so each column's rows stay sorted).
  Eigen::SparseMatrix<double> A(nfree, nfree);
  A.reserve(K.nonZeros());
  for (int c = 0; c < K.outerSize(); ++c) {
    const int fc = free_of[size_t(c)];
    if (fc < 0) continue;
    A.startVec(fc);
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it) {
      const int fr = free_of[size_t(it.row())];
      if (fr >= 0) A.insertBack(fr, fc) = it.value() + (fr == fc ? 1e-9 * mass[c] : 0.0);
    }
  }
  A.finalize();
  SolverOptions so;
  so.method = method;  // Auto: CG from the guess; CHOLMOD when it does not converge
  so.tolerance = 1e-7;  // 0.2 % of a step from CHOLMOD's relief on the benchmark (1e-6: 1.7 %)
  so.max_iterations = 2000;
  Eigen::MatrixXd X = guess;
  const SolveReport r = solve_spd(A, rhs_free, X, so);
  x_free = X.col(0);
  return r;
}

}  // namespace

namespace {

// Every segment of every curve, numbered: its curve, arc-length fractions and direction.
struct CurveSegments {
  std::vector<int> curve;
  std::vector<float> from, to;
  std::vector<Vec2> dir;
};

CurveSegments curve_segments(const DrawingCurves& dc) {
  CurveSegments s;
  for (int k = 0; k < int(dc.curves.size()); ++k) {
    const auto& c = dc.curves[size_t(k)];
    double total = 0;
    for (size_t i = 1; i < c.size(); ++i) total += (c[i] - c[i - 1]).norm();
    double run = 0;
    for (size_t i = 1; i < c.size(); ++i) {
      const double len = (c[i] - c[i - 1]).norm();
      s.curve.push_back(k);
      s.from.push_back(float(total > 0 ? run / total : 0));
      run += len;
      s.to.push_back(float(total > 0 ? run / total : 1));
      s.dir.push_back(len > 0 ? Vec2((c[i] - c[i - 1]) / len) : Vec2(1, 0));
    }
  }
  return s;
}

// Per pixel: the distance to the nearest pixel of a structure curve (shading strokes shape no
// margin), that pixel and its segment.
struct NearestInk {
  cv::Mat dist, label;                   // distance; label of the nearest ink pixel (1..n)
  std::vector<int> segment_of_label;     // per label
  std::vector<cv::Point> pixel_of_label;
};

NearestInk nearest_ink(const DrawingCurves& dc, const std::vector<char>& shading) {
  cv::Mat seg_of(dc.height, dc.width, CV_32S, cv::Scalar(-1)), ink(dc.height, dc.width, CV_8U, cv::Scalar(255));
  int sid = 0;
  for (size_t k = 0; k < dc.curves.size(); ++k) {
    const auto& c = dc.curves[k];
    if (k < shading.size() && shading[k]) {
      sid += int(c.size() > 1 ? c.size() - 1 : 0);
      continue;
    }
    for (size_t i = 1; i < c.size(); ++i, ++sid) {
      const cv::Point a(int(std::lround(c[i - 1].x())), int(std::lround(c[i - 1].y()))),
          b(int(std::lround(c[i].x())), int(std::lround(c[i].y())));
      cv::line(seg_of, a, b, cv::Scalar(sid), 1, cv::LINE_8);
      cv::line(ink, a, b, cv::Scalar(0), 1, cv::LINE_8);
    }
  }
  NearestInk n;
  cv::distanceTransform(ink, n.dist, n.label, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  // DIST_LABEL_PIXEL numbers the ink pixels 1..n: one entry per ink pixel, not per image pixel.
  const size_t n_ink = size_t(dc.width) * dc.height - size_t(cv::countNonZero(ink));
  n.segment_of_label.assign(n_ink + 1, -1);
  n.pixel_of_label.resize(n_ink + 1);
  for (int y = 0; y < dc.height; ++y)
    for (int x = 0; x < dc.width; ++x)
      if (ink.at<uchar>(y, x) == 0) {
        const size_t l = size_t(n.label.at<int>(y, x));
        n.segment_of_label[l] = seg_of.at<int>(y, x);
        n.pixel_of_label[l] = cv::Point(x, y);
      }
  return n;
}

// The drawing as the base sees it: where each vertex is in the drawing and its region's level.
struct DrawingOnBase {
  const TriMesh& base;
  const DrawingCurves& dc;
  const DrawingInterpretation& di;
  const DrawingReliefParams& p;
  const std::vector<Vec2>* pixel_of_vertex;

  int region_at_px(double x, double y) const {
    const int xi = int(std::lround(x)), yi = int(std::lround(y));
    if (xi < 0 || yi < 0 || xi >= dc.width || yi >= dc.height) return -1;
    return di.regions.at<int>(yi, xi);
  }
  // Where a vertex is in the drawing (px); NaN: not covered by it.
  Vec2 pixel(int v) const {
    if (pixel_of_vertex) return (*pixel_of_vertex)[size_t(v)];
    return Vec2(base.vertices[size_t(v)].x() / p.pixel_size, -base.vertices[size_t(v)].y() / p.pixel_size);
  }
  // A vertex's region (-1 on a curve or outside the drawing).
  int region_of(int v) const {
    const Vec2 q = pixel(v);
    return std::isfinite(q.x()) ? region_at_px(q.x(), q.y()) : -1;
  }
  // A vertex's level (its region's, in mesh units; 0 on a curve or outside the drawing).
  double level_of(int v) const {
    const int reg = region_of(v);
    return reg >= 0 ? di.region_height[size_t(reg)] * p.step_height : 0.0;
  }
};

// The regions on either side of the curve near pixel (x, y), seen locally from its nearest curve
// point q (a curve running past a junction has different regions beside it along its length).
struct LocalSides {
  int here = -1, across = -1;
  bool on_left = true;  // (x, y) left of the curve's direction of travel, image y down
};

LocalSides local_sides(const DrawingOnBase& d, int x, int y, const cv::Point& q, const Vec2& dir, int curve) {
  LocalSides s;
  s.here = d.di.regions.at<int>(y, x);
  double ux = x - q.x, uy = y - q.y;
  const double un = std::hypot(ux, uy);
  const double reach = 2 * d.p.margin + 3;
  if (un > 0) {
    ux /= un, uy /= un;
    for (double step = 2.0; step <= reach && s.across < 0; step += 1) s.across = d.region_at_px(q.x - ux * step, q.y - uy * step);
    if (s.here < 0)
      for (double step = 2.0; step <= reach && s.here < 0; step += 1) s.here = d.region_at_px(q.x + ux * step, q.y + uy * step);
    s.on_left = ux * dir.y() - uy * dir.x() > 0;
  } else {  // on the curve: its two sides as the curve records them
    s.here = d.di.sides[size_t(curve)][0], s.across = d.di.sides[size_t(curve)][1];
  }
  return s;
}

// The stretch of curve k at arc-length fraction `at`, or null when the curve has one profile.
const ProfileSpan* span_at(const DrawingInterpretation& di, int k, double at) {
  const ProfileSpan* span = nullptr;
  if (!di.profiles.empty() && !di.profiles[size_t(k)].empty())
    for (const ProfileSpan& sp : di.profiles[size_t(k)])
      if (at >= sp.from && at <= sp.to) span = &sp;
  return span;
}

// The local relief r at a vertex at pixel (x, y) within the margin of a curve (eqs. 7.1-7.3): from
// the height of its own region to that of the region across the nearest curve point, shaped by
// the profile of the curve's stretch there. False when the vertex is beyond the margin's flat band
// or its sides are unknown.
bool margin_relief(const DrawingOnBase& d, const CurveSegments& segs, const NearestInk& ink, int x, int y, double& value) {
  const double dist = ink.dist.at<float>(y, x);
  if (dist > kFlatBand * d.p.margin) return false;  // the profile, then a flat band (see kFlatBand)
  const size_t l = size_t(ink.label.at<int>(y, x));
  const int sg = ink.segment_of_label[l];
  if (sg < 0) return false;
  const int k = segs.curve[size_t(sg)];
  LocalSides s = local_sides(d, x, y, ink.pixel_of_label[l], segs.dir[size_t(sg)], k);
  const bool step_curve = d.di.is_step.empty() || d.di.is_step[size_t(k)];
  if (!step_curve) {  // a ridge / valley alone: both sides at one height
    if (s.here < 0) s.here = s.across;
    s.across = s.here;
  }
  if (s.here < 0 || s.across < 0) return false;
  const double hh = d.di.region_height[size_t(s.here)] * d.p.step_height;
  const double ha = d.di.region_height[size_t(s.across)] * d.p.step_height;
  const double h_left = s.on_left ? hh : ha, h_right = s.on_left ? ha : hh;
  const double t = std::min(1.0, dist / d.p.margin) * (s.on_left ? -1 : 1);
  const ProfileSpan* span = span_at(d.di, k, 0.5 * (segs.from[size_t(sg)] + segs.to[size_t(sg)]));
  if (span == nullptr || span->profile == CurveProfile::Step) {
    const double S = span && !span->shape.empty() ? free_form(span->shape, t) : step_profile(t);
    value = h_left + (h_right - h_left) * S;
    return true;
  }
  const double amp = std::max(1, d.di.weight.empty() ? 0 : d.di.weight[size_t(k)]) * d.p.step_height *
                     (span->profile == CurveProfile::Ridge ? 1 : -1);
  const double B = !span->shape.empty() ? free_form(span->shape, t) : 1 - step_profile(2 * std::abs(t) - 1);
  // Beside a step curve, a ridge stretch rides on its step.
  value = (step_curve ? h_left + (h_right - h_left) * step_profile(t) : hh) + amp * B;
  return true;
}

// r and the margin flags at every vertex; outside the drawing a vertex is ground (in a margin, r 0).
void local_relief(const DrawingOnBase& d, std::vector<double>& r, std::vector<char>& in_margin) {
  const int nv = d.base.n_vertices();
  const CurveSegments segs = curve_segments(d.dc);
  const NearestInk ink = nearest_ink(d.dc, d.di.shading);
  r.assign(size_t(nv), 0);
  in_margin.assign(size_t(nv), 0);
  for (int v = 0; v < nv; ++v) {
    const Vec2 pv = d.pixel(v);
    if (!std::isfinite(pv.x()) || !std::isfinite(pv.y())) {
      in_margin[size_t(v)] = 1;
      continue;
    }
    const int x = int(std::lround(pv.x())), y = int(std::lround(pv.y()));
    if (x < 0 || y < 0 || x >= d.dc.width || y >= d.dc.height) continue;
    if (margin_relief(d, segs, ink, x, y, r[size_t(v)])) in_margin[size_t(v)] = 1;
  }
}

// Unknowns of a solve: the vertices not held (free index per vertex, -1 when held).
struct FreeSet {
  std::vector<int> of_vertex;
  int count = 0;
};
FreeSet free_where(const std::vector<char>& held) {
  FreeSet f;
  f.of_vertex.assign(held.size(), -1);
  for (size_t v = 0; v < held.size(); ++v)
    if (!held[v]) f.of_vertex[v] = f.count++;
  return f;
}

// Step 1 (eq. 7.4): L = Delta r = -M^-1 K r where a vertex and all its neighbours are in a margin
// (there Delta r is known), K L = 0 elsewhere.
Eigen::VectorXd interpolated_laplacian(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass,
                                       const Eigen::VectorXd& rv, const std::vector<char>& in_margin,
                                       SolverMethod method, SolveReport& report) {
  const int nv = int(rv.size());
  std::vector<char> interior(in_margin);  // margin vertices whose neighbours are all in margins
  for (int c = 0; c < K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it)
      if (!in_margin[size_t(it.row())]) interior[size_t(c)] = 0;
  const FreeSet f = free_where(interior);
  const Eigen::VectorXd Kr = K * rv;
  Eigen::VectorXd Lap = Eigen::VectorXd::Zero(nv);
  for (int v = 0; v < nv; ++v)
    if (interior[size_t(v)]) Lap[v] = mass[v] > 0 ? -Kr[v] / mass[v] : 0;
  const Eigen::VectorXd KLc = K * Lap;
  Eigen::VectorXd rhs(f.count), Lf;
  for (int v = 0; v < nv; ++v)
    if (f.of_vertex[size_t(v)] >= 0) rhs[f.of_vertex[size_t(v)]] = -KLc[v];
  report = solve_free(K, mass, f.of_vertex, f.count, rhs, Lf, Eigen::VectorXd::Zero(f.count), method);
  for (int v = 0; v < nv; ++v)
    if (f.of_vertex[size_t(v)] >= 0) Lap[v] = Lf[f.of_vertex[size_t(v)]];
  return Lap;
}

// One solve of step 2 (eq. 7.6): R = r where held; Delta R = L, i.e. K R = -M L, elsewhere, started
// from `start` (the interpretation's levels: what the thesis starts from, or the previous pass).
std::vector<double> relief_solve(const DrawingOnBase& d, const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass,
                                 const Eigen::VectorXd& Lap, const std::vector<double>& r, const std::vector<char>& held,
                                 const std::vector<double>& start, SolveReport& report) {
  const int nv = int(r.size());
  const FreeSet f = free_where(held);
  Eigen::VectorXd Rc = Eigen::VectorXd::Zero(nv);
  for (int v = 0; v < nv; ++v)
    if (held[size_t(v)]) Rc[v] = r[size_t(v)];
  const Eigen::VectorXd KRc = K * Rc;
  Eigen::VectorXd rhs(f.count), guess(f.count), Rf;
  for (int v = 0; v < nv; ++v)
    if (f.of_vertex[size_t(v)] >= 0) {
      rhs[f.of_vertex[size_t(v)]] = -mass[v] * Lap[v] - KRc[v];
      guess[f.of_vertex[size_t(v)]] = start[size_t(v)];
    }
  report = solve_free(K, mass, f.of_vertex, f.count, rhs, Rf, guess, d.p.solver);
  std::vector<double> height(static_cast<size_t>(nv));
  for (int v = 0; v < nv; ++v) height[size_t(v)] = f.of_vertex[size_t(v)] >= 0 ? Rf[f.of_vertex[size_t(v)]] : Rc[v];
  return height;
}

// How far the free surface may leave its region's level (steps), and how many solves it gets to
// settle within that bound.
constexpr double kFreeSurfaceBound = 0.5;
constexpr int kMaxBoundPasses = 6;

// Step 2, bounded: eq. 7.6 lets the interpolated Laplacian carry a margin's bend far into a region
// (on a plate of 28 tools the paper sank 4.5 steps below the ground between them and rose 2.6 above
// the highest level). Each free vertex is held within kFreeSurfaceBound steps of its region's level,
// never below the ground (level 0):
// where a solve leaves that range the vertex is held at the bound and the relief solved again (an
// obstacle problem by active sets), until no vertex leaves it.
std::vector<double> interpolated_relief(const DrawingOnBase& d, const Eigen::SparseMatrix<double>& K,
                                        const Eigen::VectorXd& mass, const Eigen::VectorXd& Lap, std::vector<double> r,
                                        std::vector<char> held, DrawingRelief& out) {
  const int nv = int(r.size());
  std::vector<double> height(static_cast<size_t>(nv));
  for (int v = 0; v < nv; ++v) height[size_t(v)] = d.level_of(v);
  const double bound = kFreeSurfaceBound * d.p.step_height, slack = 1e-3 * d.p.step_height;
  const double top = d.p.step_height * (d.di.region_height.empty() ? 0 : *std::max_element(d.di.region_height.begin(),
                                                                                           d.di.region_height.end()));
  for (int pass = 0; pass <= kMaxBoundPasses; ++pass) {
    if (pass < kMaxBoundPasses) height = relief_solve(d, K, mass, Lap, r, held, height, out.relief_solve);
    long newly = 0;
    for (int v = 0; v < nv; ++v) {
      if (held[size_t(v)]) continue;
      // On a curve's extension there is no region to keep to: between the ground and the top.
      const int reg = d.region_of(v);
      const bool region = reg >= 0;
      const double level = region ? d.di.region_height[size_t(reg)] * d.p.step_height : 0.0, h = height[size_t(v)];
      const double lo = region ? std::max(0.0, level - bound) : 0.0, hi = (region ? level : top) + bound;
      if (h >= lo - slack && h <= hi + slack) continue;
      height[size_t(v)] = r[size_t(v)] = std::clamp(h, lo, hi);  // after the last pass: clamped
      held[size_t(v)] = 1, ++newly;
    }
    out.bounded_vertices += newly;
    if (newly == 0) break;
  }
  return height;
}

// The base's vertex spacing in pixels of the drawing: the median length of the faces' first edges.
double spacing_px(const DrawingOnBase& d) {
  std::vector<double> len;
  for (const auto& f : d.base.faces) {
    const double l = (d.pixel(f[1]) - d.pixel(f[0])).norm();
    if (std::isfinite(l)) len.push_back(l);
  }
  if (len.empty()) return 1;
  std::nth_element(len.begin(), len.begin() + long(len.size() / 2), len.end());
  return len[len.size() / 2];
}

// The shading strokes as fine grooves (DrawingReliefParams::shading_depth steps deep): each vertex
// within a groove's half-width of a stroke is lowered by depth x (1 - (dist / half)^2)^2. The
// half-width is 1.5 px, or the vertex spacing where the base is coarser, so that a groove is seen.
void engrave_shading(const DrawingOnBase& d, std::vector<double>& height) {
  if (!(d.p.shading_depth > 0) || d.di.shading_curves == 0) return;
  const cv::Mat dist = curve_distance(d.dc, d.di.shading, true);
  const double half = std::max(1.5, spacing_px(d)), depth = d.p.shading_depth * d.p.step_height;
  for (int v = 0; v < d.base.n_vertices(); ++v) {
    const Vec2 q = d.pixel(v);
    const int x = std::isfinite(q.x()) ? int(std::lround(q.x())) : -1, y = std::isfinite(q.y()) ? int(std::lround(q.y())) : -1;
    if (x < 0 || y < 0 || x >= d.dc.width || y >= d.dc.height) continue;
    const double t = dist.at<float>(y, x) / half;
    if (t < 1) height[size_t(v)] -= depth * (1 - t * t) * (1 - t * t);
  }
}

}  // namespace

DrawingRelief reconstruct_drawing_relief(const Surface& base, const DrawingCurves& dc, const DrawingInterpretation& di,
                                         const DrawingReliefParams& p, const std::vector<Vec2>* pixel_of_vertex) {
  p.validate();
  base.require_triangles();
  const int nv = base.n_vertices();
  if (pixel_of_vertex && int(pixel_of_vertex->size()) != nv)
    throw InputError("reconstruct_drawing_relief: one pixel position per base vertex is needed.");
  const DrawingOnBase d{base.mesh(), dc, di, p, pixel_of_vertex};
  DrawingRelief out;
  std::vector<double> r;
  local_relief(d, r, out.in_margin);
  // The base's border holds its region's level (with the paper as ground: 0) where no margin
  // reaches it; left free, the border took whatever the interpolated Laplacian made of it (on a
  // real drawing: 14 steps below the paper at a corner of the grid).
  const VertexRing& border = base.topology().border;
  for (int v = 0; v < nv; ++v)
    if (!out.in_margin[size_t(v)] && border.offset[size_t(v) + 1] > border.offset[size_t(v)]) {
      r[size_t(v)] = d.level_of(v);
      out.in_margin[size_t(v)] = 1;
    }
  // eqs. 7.4 and 7.6, two Laplacian solves. Because each margin is held flat beyond its profile
  // (kFlatBand), L fades to zero at the margins' outer edges and the free surface between curves
  // follows the levels.
  const LaplacianResult& lap = base.laplacian();
  const Eigen::SparseMatrix<double> K = -lap.L;  // positive semi-definite stiffness
  const Eigen::VectorXd rv = Eigen::Map<const Eigen::VectorXd>(r.data(), nv);
  const Eigen::VectorXd Lap = interpolated_laplacian(K, lap.mass, rv, out.in_margin, p.solver, out.laplacian_solve);
  out.laplacian.assign(Lap.data(), Lap.data() + nv);
  out.height = interpolated_relief(d, K, lap.mass, Lap, r, out.in_margin, out);
  engrave_shading(d, out.height);
  return out;
}

DrawingRelief reconstruct_drawing_relief(const TriMesh& base, const DrawingCurves& dc, const DrawingInterpretation& di,
                                         const DrawingReliefParams& p, const std::vector<Vec2>* pixel_of_vertex) {
  return reconstruct_drawing_relief(Surface::borrow(base), dc, di, p, pixel_of_vertex);
}

}  // namespace reliefkit

namespace reliefkit {
namespace {

// The base's area-weighted centroid, principal axes (eigenvalues increasing: least extent first),
// area normal, and the median length of each face's first edge.
struct BaseShape {
  Vec3 centroid, area_normal;
  Vec3 axis[3];
  double edge = 0;
};

BaseShape base_shape(const TriMesh& base) {
  BaseShape s;
  Vec3 c = Vec3::Zero(), area_normal = Vec3::Zero();
  double total = 0;
  std::vector<double> edges;
  for (const auto& f : base.faces) {
    const Vec3 &a = base.vertices[f[0]], &b = base.vertices[f[1]], &d = base.vertices[f[2]];
    const Vec3 n = (b - a).cross(d - a);
    const double A = 0.5 * n.norm();
    c += A * (a + b + d) / 3, total += A, area_normal += 0.5 * n;
    edges.push_back((b - a).norm());
  }
  if (!(total > 0)) throw InputError("The base has no area: it cannot carry a drawing.");
  c /= total;
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const auto& f : base.faces) {
    const Vec3 &a = base.vertices[f[0]], &b = base.vertices[f[1]], &d = base.vertices[f[2]];
    const double A = 0.5 * (b - a).cross(d - a).norm();
    for (const Vec3* q : {&a, &b, &d}) C += (A / 3) * (*q - c) * (*q - c).transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
  for (int k = 0; k < 3; ++k) s.axis[k] = es.eigenvectors().col(k);
  s.centroid = c;
  s.area_normal = area_normal;
  std::nth_element(edges.begin(), edges.begin() + long(edges.size() / 2), edges.end());
  s.edge = edges[edges.size() / 2];
  return s;
}

// A range of projections onto an axis.
struct Span {
  double lo = 1e300, hi = -1e300;
  void add(double x) { lo = std::min(lo, x), hi = std::max(hi, x); }
  double size() const { return hi - lo; }
};

// The image's right and up on the base: the drawing's longer side along the base's longer
// projected side `a` (or `b`; upright in the world when they differ by less than 10 %); right x up
// = -view (not mirrored); up along the world's +y as far as possible (+z when the view is along y).
void orient_image(const Vec3& view, const Vec3& axis_a, const Vec3& axis_b, const Span& a, const Span& b, bool wide,
                  Vec3& right, Vec3& up) {
  right = (a.size() >= b.size()) == wide ? axis_a : axis_b, up = (a.size() >= b.size()) == wide ? axis_b : axis_a;
  const Vec3 world_up = std::abs(view.y()) < 0.9 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  if (std::max(a.size(), b.size()) < 1.1 * std::min(a.size(), b.size())) {
    up = (world_up - world_up.dot(view) * view).normalized();
    right = up.cross(-view).normalized();
  }
  if (std::abs(up.dot(world_up)) >= 0.3) {
    if (up.dot(world_up) < 0) up = -up;
    if (right.cross(up).dot(-view) < 0) right = -right;
  } else {  // the drawing lies sideways on the base: its x towards the world's up
    if (right.dot(world_up) < 0) right = -right;
    if (right.cross(up).dot(-view) < 0) up = -up;
  }
}

// Occlusion: the nearest depth per cell of a grid over the projected base (cells of `cell`); a
// vertex more than `behind` farther than its cell's nearest is hidden.
struct DepthGrid {
  Span r, u;
  double cell = 1;
  int w = 1, h = 1;
  std::vector<double> nearest;
  size_t cell_of(double pr, double pu) const {
    const int i = std::clamp(int((pr - r.lo) / cell), 0, w - 1), j = std::clamp(int((pu - u.lo) / cell), 0, h - 1);
    return size_t(j) * w + i;
  }
};

}  // namespace

namespace {

// Where the image lies on the base: pixel (px, py) at origin + px s right - py s up, seen along view.
struct ImageFrame {
  Vec3 view, right, up, origin;
  double pixel_size = 1;
};

// The vertices facing the viewer (normal against the view).
std::vector<char> facing_vertices(const Surface& surface, const Vec3& view) {
  const std::vector<Vec3>& normals = surface.normals();
  std::vector<char> facing(normals.size(), 0);
  for (size_t v = 0; v < normals.size(); ++v) facing[v] = normals[v].dot(-view) > 0.05;
  return facing;
}

// The drawing's `extent` laid on the base in `frame`: a vertex is covered when it faces the viewer,
// nothing of the base lies in front of it (a grid of about two edge lengths keeps the nearest depth
// per cell) and its pixel is within the extent.
DrawingProjection cover_base(const Surface& surface, const std::vector<char>& facing, const ImageFrame& frame,
                             const cv::Rect& extent, double edge) {
  const TriMesh& base = surface.mesh();
  const int nv = base.n_vertices();
  DrawingProjection out;
  out.view = frame.view, out.right = frame.right, out.up = frame.up, out.pixel_size = frame.pixel_size;
  auto proj = [&](const Vec3& p, const Vec3& axis) { return (p - frame.origin).dot(axis); };
  DepthGrid g;
  for (int v = 0; v < nv; ++v)
    if (facing[size_t(v)]) g.r.add(proj(base.vertices[v], frame.right)), g.u.add(proj(base.vertices[v], frame.up));
  g.cell = 2 * edge;
  g.w = std::max(1, int(g.r.size() / g.cell) + 1), g.h = std::max(1, int(g.u.size() / g.cell) + 1);
  g.nearest.assign(size_t(g.w) * g.h, 1e300);
  auto cell_of = [&](const Vec3& p) { return g.cell_of(proj(p, frame.right), proj(p, frame.up)); };
  for (int v = 0; v < nv; ++v)
    if (facing[size_t(v)]) {
      double& n = g.nearest[cell_of(base.vertices[v])];
      n = std::min(n, proj(base.vertices[v], frame.view));
    }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.pixel.assign(size_t(nv), Vec2(nan, nan));
  for (int v = 0; v < nv; ++v) {
    if (!facing[size_t(v)]) continue;
    const Vec3& p = base.vertices[v];
    if (proj(p, frame.view) > g.nearest[cell_of(p)] + 3 * edge) continue;
    const double px = proj(p, frame.right) / frame.pixel_size, py = -proj(p, frame.up) / frame.pixel_size;
    constexpr double kSlack = 1e-6;  // rounding at the extent's edges
    if (px < extent.x - kSlack || py < extent.y - kSlack || px > extent.x + extent.width - 1 + kSlack ||
        py > extent.y + extent.height - 1 + kSlack)
      continue;
    out.pixel[size_t(v)] = Vec2(px, py);
    ++out.covered;
  }
  out.edge_px = edge / frame.pixel_size;
  return out;
}

}  // namespace

DrawingProjection project_drawing(const Surface& surface, const cv::Rect& extent, Vec3 view) {
  surface.require_triangles();
  if (extent.width < 2 || extent.height < 2) throw InputError("The drawing is too small to project (at least 2 x 2 pixels).");
  const TriMesh& base = surface.mesh();
  const BaseShape shape = base_shape(base);
  Vec3 e_small = shape.axis[0], e_mid = shape.axis[1], e_big = shape.axis[2];
  if (view.norm() > 0 && std::isfinite(view.norm())) {
    view.normalize();
    // The image plane's axes: the base's largest extents seen along the view.
    e_big = (e_big - e_big.dot(view) * view);
    if (e_big.norm() < 1e-6) e_big = e_mid - e_mid.dot(view) * view;
    e_big.normalize();
    e_mid = view.cross(e_big).normalized();
  } else {
    // Along the axis of least extent, towards the side most of the area faces away from.
    view = shape.area_normal.dot(e_small) >= 0 ? Vec3(-e_small) : e_small;
  }
  auto proj = [&](const Vec3& p, const Vec3& axis) { return (p - shape.centroid).dot(axis); };
  const std::vector<char> facing = facing_vertices(surface, view);
  Span a, b;
  for (int v = 0; v < base.n_vertices(); ++v)
    if (facing[size_t(v)]) a.add(proj(base.vertices[v], e_big)), b.add(proj(base.vertices[v], e_mid));
  if (a.lo > a.hi) throw InputError("No part of the base faces the view direction: the drawing cannot be projected onto it.");
  ImageFrame f;
  f.view = view;
  orient_image(view, e_big, e_mid, a, b, extent.width >= extent.height, f.right, f.up);
  Span r, u;  // the facing part's extent across the view
  for (int v = 0; v < base.n_vertices(); ++v)
    if (facing[size_t(v)]) r.add(proj(base.vertices[v], f.right)), u.add(proj(base.vertices[v], f.up));
  f.pixel_size = std::max(r.size() / (extent.width - 1), u.size() / (extent.height - 1));
  if (!(f.pixel_size > 0)) throw InputError("The base's part facing the view has no extent across it.");
  // The extent's centre on the facing part's centre.
  const double cx = extent.x + 0.5 * (extent.width - 1), cy = extent.y + 0.5 * (extent.height - 1);
  f.origin = shape.centroid + (0.5 * (r.lo + r.hi) - cx * f.pixel_size) * f.right + (0.5 * (u.lo + u.hi) + cy * f.pixel_size) * f.up;
  return cover_base(surface, facing, f, extent, shape.edge);
}

DrawingProjection project_drawing_as_drawn(const Surface& surface, const cv::Rect& extent, double pixel_size) {
  surface.require_triangles();
  if (!(pixel_size > 0) || !std::isfinite(pixel_size)) throw InputError("The drawing's pixel size must be a positive number.");
  ImageFrame f;
  f.view = Vec3(0, 0, -1), f.right = Vec3(1, 0, 0), f.up = Vec3(0, 1, 0), f.origin = Vec3::Zero(), f.pixel_size = pixel_size;
  const std::vector<char> facing = facing_vertices(surface, f.view);
  DrawingProjection out = cover_base(surface, facing, f, extent, base_shape(surface.mesh()).edge);
  if (out.covered == 0)
    throw InputError("Placed as drawn, the drawing covers no vertex of the layer facing it (+z): the layer is not in the "
                     "drawing's frame (x right, y up, mm from the same DPI and scale) — made by \"Vessel from Profile "
                     "Drawing\" from this drawing, say. Choose the placement fitted to the layer instead.");
  return out;
}

DrawingProjection project_drawing(const TriMesh& base, const cv::Rect& extent, Vec3 view) {
  return project_drawing(Surface::borrow(base), extent, view);
}

TriMesh displace_along_normals(const Surface& base, const std::vector<double>& height) {
  TriMesh m = base.mesh();
  const std::vector<Vec3>& n = base.normals();
  for (int v = 0; v < m.n_vertices(); ++v) m.vertices[v] += height[size_t(v)] * n[size_t(v)];
  return m;
}

TriMesh displace_along_normals(const TriMesh& base, const std::vector<double>& height) {
  return displace_along_normals(Surface::borrow(base), height);
}

}  // namespace reliefkit
