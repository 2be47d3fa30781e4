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

namespace reliefkit {

void DrawingReliefParams::validate() const {
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

DrawingRelief reconstruct_drawing_relief(const TriMesh& base, const DrawingCurves& dc, const DrawingInterpretation& di,
                                         const DrawingReliefParams& p, const std::vector<Vec2>* pixel_of_vertex) {
  p.validate();
  require_triangles(base);
  const int nv = base.n_vertices();
  if (pixel_of_vertex && int(pixel_of_vertex->size()) != nv)
    throw InputError("reconstruct_drawing_relief: one pixel position per base vertex is needed.");
  DrawingRelief out;
  out.height.assign(size_t(nv), 0);
  out.in_margin.assign(size_t(nv), 0);
  const int nc = int(dc.curves.size());
  // Every segment of every curve, numbered; per segment its curve and arc-length fraction.
  std::vector<int> seg_curve;
  std::vector<float> seg_from, seg_to;
  std::vector<Vec2> seg_dir;
  for (int k = 0; k < nc; ++k) {
    const auto& c = dc.curves[size_t(k)];
    double total = 0;
    for (size_t i = 1; i < c.size(); ++i) total += (c[i] - c[i - 1]).norm();
    double run = 0;
    for (size_t i = 1; i < c.size(); ++i) {
      const double len = (c[i] - c[i - 1]).norm();
      seg_curve.push_back(k);
      seg_from.push_back(float(total > 0 ? run / total : 0));
      run += len;
      seg_to.push_back(float(total > 0 ? run / total : 1));
      seg_dir.push_back(len > 0 ? Vec2((c[i] - c[i - 1]) / len) : Vec2(1, 0));
    }
  }
  // Nearest segment and distance per pixel: distance transform of the curves' pixels, each pixel's
  // nearest ink pixel's segment.
  cv::Mat seg_of(dc.height, dc.width, CV_32S, cv::Scalar(-1)), ink(dc.height, dc.width, CV_8U, cv::Scalar(255));
  {
    int sid = 0;
    for (int k = 0; k < nc; ++k) {
      const auto& c = dc.curves[size_t(k)];
      for (size_t i = 1; i < c.size(); ++i, ++sid) {
        const cv::Point a(int(std::lround(c[i - 1].x())), int(std::lround(c[i - 1].y()))),
            b(int(std::lround(c[i].x())), int(std::lround(c[i].y())));
        cv::line(seg_of, a, b, cv::Scalar(sid), 1, cv::LINE_8);
        cv::line(ink, a, b, cv::Scalar(0), 1, cv::LINE_8);
      }
    }
  }
  cv::Mat dist, label;
  cv::distanceTransform(ink, dist, label, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  // DIST_LABEL_PIXEL numbers the ink pixels 1..n: one entry per ink pixel, not per image pixel.
  const size_t n_ink = size_t(dc.width) * dc.height - size_t(cv::countNonZero(ink));
  std::vector<int> seg_of_label(n_ink + 1, -1);
  std::vector<cv::Point> pixel_of_label(n_ink + 1);
  for (int y = 0; y < dc.height; ++y)
    for (int x = 0; x < dc.width; ++x)
      if (ink.at<uchar>(y, x) == 0) {
        const size_t l = size_t(label.at<int>(y, x));
        seg_of_label[l] = seg_of.at<int>(y, x);
        pixel_of_label[l] = cv::Point(x, y);
      }
  auto region_at_px = [&](double x, double y) {
    const int xi = int(std::lround(x)), yi = int(std::lround(y));
    if (xi < 0 || yi < 0 || xi >= dc.width || yi >= dc.height) return -1;
    return di.regions.at<int>(yi, xi);
  };
  // Where a vertex is in the drawing (px); NaN: not covered by it.
  auto pixel = [&](int v) {
    if (pixel_of_vertex) return (*pixel_of_vertex)[size_t(v)];
    return Vec2(base.vertices[v].x() / p.pixel_size, -base.vertices[v].y() / p.pixel_size);
  };
  // A vertex's level (its region's, in mesh units; 0 on a curve or outside the drawing).
  auto level_of = [&](int v) {
    const Vec2 q = pixel(v);
    const int reg = std::isfinite(q.x()) ? region_at_px(q.x(), q.y()) : -1;
    return reg >= 0 ? di.region_height[size_t(reg)] * p.step_height : 0.0;
  };
  // The local relief r at every vertex within the margin of a curve (eqs. 7.1-7.3): from the
  // height of its own region to that of the region across the nearest curve point, seen locally (a
  // curve running past a junction has different regions beside it along its length, so its sides
  // are not one pair), shaped by the profile of the curve's stretch there.
  std::vector<double> r(size_t(nv), 0);
  for (int v = 0; v < nv; ++v) {
    const Vec2 pv = pixel(v);
    if (!std::isfinite(pv.x()) || !std::isfinite(pv.y())) {  // outside the drawing: the ground
      out.in_margin[size_t(v)] = 1;
      continue;
    }
    const int x = int(std::lround(pv.x())), y = int(std::lround(pv.y()));
    if (x < 0 || y < 0 || x >= dc.width || y >= dc.height) continue;
    const double d = dist.at<float>(y, x);
    if (d > kFlatBand * p.margin) continue;  // the profile, then a flat band (see kFlatBand)
    const size_t l = size_t(label.at<int>(y, x));
    const int sg = seg_of_label[l];
    if (sg < 0) continue;
    const int k = seg_curve[size_t(sg)];
    const cv::Point q = pixel_of_label[l];
    const int own = di.regions.at<int>(y, x);
    double ux = x - q.x, uy = y - q.y;
    const double un = std::hypot(ux, uy);
    int across = -1, here = own;
    bool on_left = true;
    if (un > 0) {
      ux /= un, uy /= un;
      for (double step = 2.0; step <= 2 * p.margin + 3 && across < 0; step += 1)
        across = region_at_px(q.x - ux * step, q.y - uy * step);
      if (here < 0)
        for (double step = 2.0; step <= 2 * p.margin + 3 && here < 0; step += 1) here = region_at_px(q.x + ux * step, q.y + uy * step);
      const Vec2 dir = seg_dir[size_t(sg)];
      on_left = ux * dir.y() - uy * dir.x() > 0;  // left of the direction of travel, image y down
    } else {  // on the curve: its two sides as the curve records them
      here = di.sides[size_t(k)][0], across = di.sides[size_t(k)][1];
    }
    const bool step_curve = di.is_step.empty() || di.is_step[size_t(k)];
    if (!step_curve) {  // a ridge / valley alone: both sides at one height
      if (here < 0) here = across;
      across = here;
    }
    if (here < 0 || across < 0) continue;
    const double hh = di.region_height[size_t(here)] * p.step_height, ha = di.region_height[size_t(across)] * p.step_height;
    const double h_left = on_left ? hh : ha, h_right = on_left ? ha : hh;
    const double t = std::min(1.0, d / p.margin) * (on_left ? -1 : 1);
    // The stretch of the curve this point is beside, and its profile.
    const ProfileSpan* span = nullptr;
    if (!di.profiles.empty() && !di.profiles[size_t(k)].empty()) {
      const double at = 0.5 * (seg_from[size_t(sg)] + seg_to[size_t(sg)]);
      for (const ProfileSpan& sp : di.profiles[size_t(k)])
        if (at >= sp.from && at <= sp.to) span = &sp;
    }
    double value;
    if (span == nullptr || span->profile == CurveProfile::Step) {
      const double S = span && !span->shape.empty() ? free_form(span->shape, t) : step_profile(t);
      value = h_left + (h_right - h_left) * S;
    } else {
      const double amp = std::max(1, di.weight.empty() ? 0 : di.weight[size_t(k)]) * p.step_height *
                         (span->profile == CurveProfile::Ridge ? 1 : -1);
      const double B = !span->shape.empty() ? free_form(span->shape, t) : 1 - step_profile(2 * std::abs(t) - 1);
      // Beside a step curve, a ridge stretch rides on its step.
      value = (step_curve ? h_left + (h_right - h_left) * step_profile(t) : hh) + amp * B;
    }
    r[size_t(v)] = value;
    out.in_margin[size_t(v)] = 1;
  }
  // eqs. 7.4 and 7.6, two Laplacian solves. L: the Laplacian of r where a vertex and all its
  // neighbours are in a margin (there Delta r is known), harmonic elsewhere. R: r in the margins,
  // Delta R = L elsewhere. Because each margin is held flat beyond its profile (kFlatBand), L fades
  // to zero at the margins' outer edges and the free surface between curves follows the levels.
  const MeshTopology topo = mesh_topology(base);
  // The base's border holds its region's level (with the paper as ground: 0) where no margin
  // reaches it; left free, the border took whatever the interpolated Laplacian made of it (on a
  // real drawing: 14 steps below the paper at a corner of the grid).
  for (int v = 0; v < nv; ++v)
    if (!out.in_margin[size_t(v)] && topo.border.offset[size_t(v) + 1] > topo.border.offset[size_t(v)]) {
      r[size_t(v)] = level_of(v);
      out.in_margin[size_t(v)] = 1;
    }
  const LaplacianResult lap = cotangent_laplacian(base, topo);
  const Eigen::SparseMatrix<double> K = -lap.L;  // positive semi-definite stiffness
  Eigen::VectorXd rv(nv);
  for (int v = 0; v < nv; ++v) rv[v] = r[size_t(v)];
  const Eigen::VectorXd Kr = K * rv;
  std::vector<char> interior(out.in_margin);  // margin vertices whose neighbours are all in margins
  for (int c = 0; c < K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it)
      if (!out.in_margin[size_t(it.row())]) interior[size_t(c)] = 0;
  // Step 1 (eq. 7.4): L = Delta r = -M^-1 K r on the interior margin vertices; K L = 0 elsewhere.
  std::vector<int> free1(size_t(nv), -1);
  int nfree1 = 0;
  Eigen::VectorXd Lc = Eigen::VectorXd::Zero(nv);
  for (int v = 0; v < nv; ++v)
    if (interior[size_t(v)])
      Lc[v] = lap.mass[v] > 0 ? -Kr[v] / lap.mass[v] : 0;
    else
      free1[size_t(v)] = nfree1++;
  const Eigen::VectorXd KLc = K * Lc;
  Eigen::VectorXd rhs1(nfree1), Lf;
  for (int v = 0; v < nv; ++v)
    if (free1[size_t(v)] >= 0) rhs1[free1[size_t(v)]] = -KLc[v];
  out.laplacian_solve = solve_free(K, lap.mass, free1, nfree1, rhs1, Lf, Eigen::VectorXd::Zero(nfree1), p.solver);
  Eigen::VectorXd Lap = Lc;
  for (int v = 0; v < nv; ++v)
    if (free1[size_t(v)] >= 0) Lap[v] = Lf[free1[size_t(v)]];
  out.laplacian.assign(Lap.data(), Lap.data() + nv);
  // Step 2 (eq. 7.6): R = r in the margins; Delta R = L, i.e. K R = -M L, elsewhere.
  std::vector<int> free2(size_t(nv), -1);
  int nfree2 = 0;
  Eigen::VectorXd Rc = Eigen::VectorXd::Zero(nv);
  for (int v = 0; v < nv; ++v)
    if (out.in_margin[size_t(v)])
      Rc[v] = r[size_t(v)];
    else
      free2[size_t(v)] = nfree2++;
  const Eigen::VectorXd KRc = K * Rc;
  Eigen::VectorXd rhs2(nfree2), Rf;
  for (int v = 0; v < nv; ++v)
    if (free2[size_t(v)] >= 0) rhs2[free2[size_t(v)]] = -lap.mass[v] * Lap[v] - KRc[v];
  Eigen::VectorXd guess2(nfree2);  // the interpretation's levels (what the thesis starts from)
  for (int v = 0; v < nv; ++v)
    if (free2[size_t(v)] >= 0) guess2[free2[size_t(v)]] = level_of(v);
  out.relief_solve = solve_free(K, lap.mass, free2, nfree2, rhs2, Rf, guess2, p.solver);
  for (int v = 0; v < nv; ++v) out.height[size_t(v)] = free2[size_t(v)] >= 0 ? Rf[free2[size_t(v)]] : Rc[v];
  return out;
}

}  // namespace reliefkit

namespace reliefkit {

DrawingProjection project_drawing(const TriMesh& base, const cv::Rect& extent, Vec3 view) {
  require_triangles(base);
  if (extent.width < 2 || extent.height < 2) throw InputError("The drawing is too small to project (at least 2 x 2 pixels).");
  const int nv = base.n_vertices();
  DrawingProjection out;
  const VertexFaces vf = vertex_faces(base);
  const std::vector<Vec3> normals = vertex_normals(base, vf);
  // Area-weighted centroid, covariance and mean normal.
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
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);  // eigenvalues increasing
  Vec3 e_small = es.eigenvectors().col(0), e_mid = es.eigenvectors().col(1), e_big = es.eigenvectors().col(2);
  if (view.norm() > 0 && std::isfinite(view.norm())) {
    view.normalize();
    // The image plane's axes: the base's largest extents seen along the view.
    e_big = (e_big - e_big.dot(view) * view);
    if (e_big.norm() < 1e-6) e_big = e_mid - e_mid.dot(view) * view;
    e_big.normalize();
    e_mid = view.cross(e_big).normalized();
  } else {
    // Along the axis of least extent, towards the side most of the area faces away from.
    view = area_normal.dot(e_small) >= 0 ? Vec3(-e_small) : e_small;
  }
  out.view = view;
  auto proj = [&](const Vec3& p, const Vec3& axis) { return (p - c).dot(axis); };
  // Candidates: vertices facing the viewer.
  std::vector<char> facing(size_t(nv), 0);
  double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
  for (int v = 0; v < nv; ++v) {
    if (!(normals[size_t(v)].dot(-view) > 0.05)) continue;
    facing[size_t(v)] = 1;
    const double a = proj(base.vertices[v], e_big), b = proj(base.vertices[v], e_mid);
    a0 = std::min(a0, a), a1 = std::max(a1, a), b0 = std::min(b0, b), b1 = std::max(b1, b);
  }
  if (a0 > a1) throw InputError("No part of the base faces the view direction: the drawing cannot be projected onto it.");
  // The drawing's longer side along the base's longer projected side (when they differ by more
  // than 10 %; otherwise, upright in the world); right x up = -view (not mirrored).
  const bool wide = extent.width >= extent.height;
  Vec3 right = (a1 - a0 >= b1 - b0) == wide ? e_big : e_mid, up = (a1 - a0 >= b1 - b0) == wide ? e_mid : e_big;
  // Upright: the drawing's up along the world's +y as far as possible (+z when the view is along y).
  const Vec3 world_up = std::abs(view.y()) < 0.9 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
  if (std::max(a1 - a0, b1 - b0) < 1.1 * std::min(a1 - a0, b1 - b0)) {
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
  out.right = right, out.up = up;
  double r0 = 1e300, r1 = -1e300, u0 = 1e300, u1 = -1e300;
  for (int v = 0; v < nv; ++v)
    if (facing[size_t(v)]) {
      const double r = proj(base.vertices[v], right), u = proj(base.vertices[v], up);
      r0 = std::min(r0, r), r1 = std::max(r1, r), u0 = std::min(u0, u), u1 = std::max(u1, u);
    }
  out.pixel_size = std::max((r1 - r0) / (extent.width - 1), (u1 - u0) / (extent.height - 1));
  if (!(out.pixel_size > 0)) throw InputError("The base's part facing the view has no extent across it.");
  const double rc = 0.5 * (r0 + r1), uc = 0.5 * (u0 + u1);
  // Occlusion: the nearest depth per cell of a grid over the projected base (cells of about two
  // edge lengths); a vertex more than a few edge lengths behind it is hidden.
  std::nth_element(edges.begin(), edges.begin() + long(edges.size() / 2), edges.end());
  const double h = edges[edges.size() / 2], cell = 2 * h;
  const int gw = std::max(1, int((r1 - r0) / cell) + 1), gh = std::max(1, int((u1 - u0) / cell) + 1);
  std::vector<double> nearest(size_t(gw) * gh, 1e300);
  auto cell_of = [&](const Vec3& p) {
    const int i = std::clamp(int((proj(p, right) - r0) / cell), 0, gw - 1), j = std::clamp(int((proj(p, up) - u0) / cell), 0, gh - 1);
    return size_t(j) * gw + i;
  };
  for (int v = 0; v < nv; ++v)
    if (facing[size_t(v)]) {
      double& n = nearest[cell_of(base.vertices[v])];
      n = std::min(n, proj(base.vertices[v], view));
    }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.pixel.assign(size_t(nv), Vec2(nan, nan));
  for (int v = 0; v < nv; ++v) {
    if (!facing[size_t(v)]) continue;
    const Vec3& p = base.vertices[v];
    if (proj(p, view) > nearest[cell_of(p)] + 3 * h) continue;
    const double px = extent.x + 0.5 * (extent.width - 1) + (proj(p, right) - rc) / out.pixel_size;
    const double py = extent.y + 0.5 * (extent.height - 1) - (proj(p, up) - uc) / out.pixel_size;
    constexpr double kSlack = 1e-6;  // rounding at the fitted extent's edges
    if (px < extent.x - kSlack || py < extent.y - kSlack || px > extent.x + extent.width - 1 + kSlack ||
        py > extent.y + extent.height - 1 + kSlack)
      continue;
    out.pixel[size_t(v)] = Vec2(px, py);
    ++out.covered;
  }
  out.edge_px = h / out.pixel_size;
  return out;
}

TriMesh displace_along_normals(const TriMesh& base, const std::vector<double>& height) {
  TriMesh m = base;
  const std::vector<Vec3> n = vertex_normals(base, vertex_faces(base));
  for (int v = 0; v < m.n_vertices(); ++v) m.vertices[v] += height[size_t(v)] * n[size_t(v)];
  return m;
}

}  // namespace reliefkit
