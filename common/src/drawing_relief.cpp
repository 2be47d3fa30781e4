#include "reliefkit/drawing_relief.h"

#include <opencv2/imgproc.hpp>

#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>

#include "reliefkit/laplacian.h"
#include "reliefkit/scale.h"

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

TriMesh relief_surface(const TriMesh& grid, const std::vector<double>& height, DrawingBase base, double circumference) {
  TriMesh m = grid;
  if (base == DrawingBase::Plane) {
    for (int v = 0; v < m.n_vertices(); ++v) m.vertices[v].z() = height[size_t(v)];
    return m;
  }
  require_range(circumference, "Cylinder circumference", 1e-12, 1e12);
  const double R = circumference / (2 * 3.14159265358979323846);
  for (int v = 0; v < m.n_vertices(); ++v) {
    const Vec3 g = grid.vertices[v];
    const double a = g.x() / R, r = R + height[size_t(v)];
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

// K_FF x_F = rhs_F for the free vertices of the SPD stiffness K (+ a tiny mass term, so that a
// part without any fixed vertex still has a unique solution).
SolveReport solve_free(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& mass, const std::vector<int>& free_of,
                       int nfree, const Eigen::VectorXd& rhs_free, Eigen::VectorXd& x_free, const Eigen::VectorXd& guess) {
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < K.outerSize(); ++c) {
    const int fc = free_of[size_t(c)];
    if (fc < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, c); it; ++it) {
      const int fr = free_of[size_t(it.row())];
      if (fr >= 0) t.emplace_back(fr, fc, it.value());
    }
    t.emplace_back(fc, fc, 1e-9 * mass[c]);
  }
  Eigen::SparseMatrix<double> A(nfree, nfree);
  A.setFromTriplets(t.begin(), t.end());
  SolverOptions so;
  so.method = SolverMethod::Auto;  // CG from the guess; CHOLMOD when it does not converge
  so.tolerance = 1e-8;
  so.max_iterations = 2000;
  Eigen::MatrixXd X = guess;
  const SolveReport r = solve_spd(A, rhs_free, X, so);
  x_free = X.col(0);
  return r;
}

}  // namespace

DrawingRelief reconstruct_drawing_relief(const TriMesh& base, const DrawingCurves& dc, const DrawingInterpretation& di,
                                         const DrawingReliefParams& p) {
  p.validate();
  require_triangles(base);
  const int nv = base.n_vertices();
  DrawingRelief out;
  out.height.assign(size_t(nv), 0);
  out.in_margin.assign(size_t(nv), 0);
  // Nearest curve and distance per pixel: distance transform of the curves' pixels, each pixel's
  // nearest ink pixel's curve.
  cv::Mat curve_of(dc.height, dc.width, CV_32S, cv::Scalar(-1)), ink(dc.height, dc.width, CV_8U, cv::Scalar(255));
  for (size_t k = 0; k < dc.curves.size(); ++k) {
    std::vector<cv::Point> pts;
    for (const auto& q : dc.curves[k]) pts.emplace_back(int(std::lround(q.x())), int(std::lround(q.y())));
    cv::polylines(curve_of, pts, false, cv::Scalar(int(k)), 1, cv::LINE_8);
    cv::polylines(ink, pts, false, cv::Scalar(0), 1, cv::LINE_8);
  }
  cv::Mat dist, label;
  cv::distanceTransform(ink, dist, label, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  std::vector<int> curve_of_label(size_t(dc.width) * dc.height + 2, -1);
  std::vector<cv::Point> pixel_of_label(size_t(dc.width) * dc.height + 2);
  for (int y = 0; y < dc.height; ++y)
    for (int x = 0; x < dc.width; ++x)
      if (ink.at<uchar>(y, x) == 0) {
        const size_t l = size_t(label.at<int>(y, x));
        curve_of_label[l] = curve_of.at<int>(y, x);
        pixel_of_label[l] = cv::Point(x, y);
      }
  auto region_at_px = [&](double x, double y) {
    const int xi = int(std::lround(x)), yi = int(std::lround(y));
    if (xi < 0 || yi < 0 || xi >= dc.width || yi >= dc.height) return -1;
    return di.regions.at<int>(yi, xi);
  };
  // A vertex's level (its region's, in mesh units; 0 on a curve or outside the drawing).
  auto level_of = [&](int v) {
    const int reg = region_at_px(base.vertices[v].x() / p.pixel_size, -base.vertices[v].y() / p.pixel_size);
    return reg >= 0 ? di.region_height[size_t(reg)] * p.step_height : 0.0;
  };
  // The local relief r at every vertex within the margin of a curve: from the height of its own
  // region to that of the region across the nearest curve point, seen locally (a curve running past
  // a junction has different regions beside it along its length, so its sides are not one pair).
  std::vector<double> r(size_t(nv), 0);
  for (int v = 0; v < nv; ++v) {
    const double px = base.vertices[v].x() / p.pixel_size, py = -base.vertices[v].y() / p.pixel_size;
    const int x = int(std::lround(px)), y = int(std::lround(py));
    if (x < 0 || y < 0 || x >= dc.width || y >= dc.height) continue;
    const double d = dist.at<float>(y, x);
    if (d > kFlatBand * p.margin) continue;  // the profile, then a flat band (see kFlatBand)
    const size_t l = size_t(label.at<int>(y, x));
    const int k = curve_of_label[l];
    if (k < 0) continue;
    const cv::Point q = pixel_of_label[l];
    const int own = di.regions.at<int>(y, x);
    if (di.profile.size() == dc.curves.size() && di.profile[size_t(k)] != CurveProfile::Step) {
      // A ridge or valley: a bump of its weight in levels over the one height of both its sides.
      const int side = own >= 0 ? own : std::max(di.sides[size_t(k)][0], di.sides[size_t(k)][1]);
      if (side < 0) continue;
      const double amp = std::max(1, di.weight[size_t(k)]) * p.step_height * (di.profile[size_t(k)] == CurveProfile::Ridge ? 1 : -1);
      r[size_t(v)] = di.region_height[size_t(side)] * p.step_height + amp * (1 - step_profile(2 * std::min(1.0, d / p.margin) - 1));
      out.in_margin[size_t(v)] = 1;
      continue;
    }
    double ux = x - q.x, uy = y - q.y;
    const double un = std::hypot(ux, uy);
    int across = -1, here = own;
    if (un > 0) {
      ux /= un, uy /= un;
      for (double step = 2.0; step <= 2 * p.margin + 3 && across < 0; step += 1)
        across = region_at_px(q.x - ux * step, q.y - uy * step);
      if (here < 0)
        for (double step = 2.0; step <= 2 * p.margin + 3 && here < 0; step += 1) here = region_at_px(q.x + ux * step, q.y + uy * step);
    } else {  // on the curve: its two sides as the curve records them
      here = di.sides[size_t(k)][0], across = di.sides[size_t(k)][1];
    }
    if (here < 0 || across < 0) continue;
    const double hh = di.region_height[size_t(here)] * p.step_height, ha = di.region_height[size_t(across)] * p.step_height;
    // Distance signed positive on this side: s(+d / w) of the way from the far side's height.
    r[size_t(v)] = ha + (hh - ha) * step_profile(d / p.margin);
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
  out.laplacian_solve = solve_free(K, lap.mass, free1, nfree1, rhs1, Lf, Eigen::VectorXd::Zero(nfree1));
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
  out.relief_solve = solve_free(K, lap.mass, free2, nfree2, rhs2, Rf, guess2);
  for (int v = 0; v < nv; ++v) out.height[size_t(v)] = free2[size_t(v)] >= 0 ? Rf[free2[size_t(v)]] : Rc[v];
  return out;
}

}  // namespace reliefkit
