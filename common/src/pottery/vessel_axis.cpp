// ReliefKit — the axis of a vessel or sherd from its scan. See reliefkit/pottery/vessel_axis.h.
//
//
// Measured (build/bench/bench_pottery; docs/pottery.md): whole vessels and halves within 0.02
// degrees, rim sherds of a third, a fifth and a tenth of the circumference within 0.2; a body
// sherd of 25 degrees from an evenly rounded shoulder 1-10 degrees, with an uncertainty that
// says so. Tried and left out, with their figures in docs/pottery.md:
// smoothing 1/2/3/5 edge lengths (3 kept), a bilateral normal filter, the profile on the raw
// positions, the rim's plane as a rim chart holds it, least trimmed squares for the profile.
#include "reliefkit/base/angles.h"
#include "reliefkit/pottery/vessel_axis.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <array>
#include <numeric>
#include <random>
#include <unordered_map>

#include "reliefkit/base/scale.h"
#include "reliefkit/base/smoothing.h"

namespace reliefkit {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
constexpr size_t kFitFaces = 150000;

// A face as a sample of the surface: its centroid in the piece's own frame (centred on the
// area-weighted centroid, scaled by the RMS distance from it), its unit normal and its area.
struct FaceSample {
  Vec3 q, n;
  double area = 0;
};
struct PieceFrame {
  Vec3 centre = Vec3::Zero();
  double scale = 1;
};

std::vector<FaceSample> face_samples(const TriMesh& mesh, const std::vector<Vec3>& vertex_normal, PieceFrame& frame) {
  std::vector<FaceSample> samples(mesh.faces.size());
  double total = 0;
  Vec3 sum = Vec3::Zero();
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 cross = (b - a).cross(c - a);
    const double twice_area = cross.norm();
    FaceSample& s = samples[f];
    s.q = (a + b + c) / 3;
    s.area = twice_area > 0 && std::isfinite(twice_area) ? twice_area / 2 : 0;
    const Vec3 n = vertex_normal[t[0]] + vertex_normal[t[1]] + vertex_normal[t[2]];
    s.n = s.area > 0 && n.norm() > 0 ? Vec3(n.normalized()) : Vec3::Zero();
    total += s.area;
    sum += s.area * s.q;
  }
  if (!(total > 0)) throw InputError("the mesh has no face with an area: no axis can be fitted");
  frame.centre = sum / total;
  double spread = 0;
  for (const FaceSample& s : samples) spread += s.area * (s.q - frame.centre).squaredNorm();
  frame.scale = std::sqrt(spread / total);
  for (FaceSample& s : samples) s.q = (s.q - frame.centre) / frame.scale;
  return samples;
}

Vec6 plucker(const FaceSample& s) {
  Vec6 l;
  l << s.q.cross(s.n), s.n;
  return l;
}

// Σ w l lᵀ over the faces (the moment matrix of the weighted normal lines).
Mat6 normal_line_moments(const std::vector<FaceSample>& samples, const std::vector<double>& weight) {
  Mat6 total = Mat6::Zero();
#pragma omp parallel
  {
    Mat6 local = Mat6::Zero();
#pragma omp for schedule(static) nowait
    for (long f = 0; f < static_cast<long>(samples.size()); ++f) {
      if (weight[f] <= 0) continue;
      const Vec6 l = plucker(samples[f]);
      local.selfadjointView<Eigen::Lower>().rankUpdate(l, weight[f]);
    }
#pragma omp critical
    total += local;
  }
  return total.selfadjointView<Eigen::Lower>();
}

// The axis whose line complex the weighted normal lines fit best: d the smallest eigenvector of
// the Schur complement with d̄ solved out, d̄ then made orthogonal to d (a rotation, no pitch).
struct ComplexFit {
  Vec3 direction, point;
  Vec3 eigenvalues;  // of the direction problem, ascending
};

// The axis `start` tilted by x[0], x[1] (radians, about two directions square to it) and moved
// across itself by x[2], x[3].
ComplexFit moved_axis(const ComplexFit& start, const Eigen::Vector4d& x) {
  const Vec3 d0 = start.direction, u = d0.unitOrthogonal(), v = d0.cross(u);
  ComplexFit c = start;
  c.direction = (d0 + x[0] * u + x[1] * v).normalized();
  c.point = start.point + x[2] * u + x[3] * v;
  return c;
}
// Nelder-Mead over an axis' two tilts and two offsets from x = 0 (`steps`: the first simplex'
// edges); stops when the simplex is within 1e-5 radians and `offset_tolerance`, or after 300 steps.
template <class Cost>
Eigen::Vector4d nelder_mead(const Cost& cost, const double (&steps)[4], double offset_tolerance) {
  std::array<Eigen::Vector4d, 5> simplex;
  std::array<double, 5> value;
  for (int k = 0; k < 5; ++k) {
    simplex[k] = Eigen::Vector4d::Zero();
    if (k > 0) simplex[k][k - 1] = steps[k - 1];
    value[k] = cost(simplex[k]);
  }
  for (int iteration = 0; iteration < 300; ++iteration) {
    std::array<int, 5> order{0, 1, 2, 3, 4};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return value[a] < value[b]; });
    const int best = order[0], worst = order[4], second = order[3];
    Eigen::Vector4d centre = Eigen::Vector4d::Zero();
    for (int k = 0; k < 4; ++k) centre += simplex[order[k]] / 4;
    const Eigen::Vector4d reflected = centre + (centre - simplex[worst]);
    const double fr = cost(reflected);
    if (fr < value[best]) {
      const Eigen::Vector4d expanded = centre + 2 * (centre - simplex[worst]);
      const double fe = cost(expanded);
      simplex[worst] = fe < fr ? expanded : reflected, value[worst] = std::min(fe, fr);
    } else if (fr < value[second]) {
      simplex[worst] = reflected, value[worst] = fr;
    } else {
      const Eigen::Vector4d contracted = centre + 0.5 * (simplex[worst] - centre);
      const double fc = cost(contracted);
      if (fc < value[worst]) {
        simplex[worst] = contracted, value[worst] = fc;
      } else {
        for (int k : order)
          if (k != best) simplex[k] = simplex[best] + 0.5 * (simplex[k] - simplex[best]), value[k] = cost(simplex[k]);
      }
    }
    if ((simplex[order[4]] - simplex[best]).head<2>().norm() < 1e-5 && (simplex[order[4]] - simplex[best]).tail<2>().norm() < offset_tolerance)
      break;
  }
  int best = 0;
  for (int k = 1; k < 5; ++k)
    if (value[k] < value[best]) best = k;
  return simplex[best];
}

// With `across` given, the direction is sought square to it (the second family of a torus-like
// piece, below).
ComplexFit fit_line_complex(const Mat6& m, const Vec3* across = nullptr) {
  const Mat3 m11 = m.topLeftCorner<3, 3>(), m12 = m.topRightCorner<3, 3>();
  // The normals span no direction along the axis (a cylinder's): that part of d̄ is free, and
  // the ridge sets it to 0, as d̄ ⊥ d asks.
  const Mat3 m22 = m.bottomRightCorner<3, 3>() + (1e-12 * m.bottomRightCorner<3, 3>().trace() + 1e-300) * Mat3::Identity();
  const Eigen::LDLT<Mat3> m22_inv(m22);
  const Mat3 schur = m11 - m12 * m22_inv.solve(m12.transpose());
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(schur);
  ComplexFit fit;
  fit.direction = eig.eigenvectors().col(0).normalized();
  fit.eigenvalues = eig.eigenvalues();
  if (across) {
    Eigen::Matrix<double, 3, 2> plane;
    plane.col(0) = across->unitOrthogonal();
    plane.col(1) = across->cross(plane.col(0)).normalized();
    const Eigen::Matrix2d reduced = plane.transpose() * schur * plane;
    const double half = reduced.trace() / 2, radius = std::hypot((reduced(0, 0) - reduced(1, 1)) / 2, reduced(0, 1));
    const double smallest = half - radius;  // its eigenvector: (b, smallest - a) or (smallest - c, b)
    Eigen::Vector2d e(reduced(0, 1), smallest - reduced(0, 0));
    if (e.norm() < 1e-300) e = Eigen::Vector2d(smallest - reduced(1, 1), reduced(1, 0));
    if (e.norm() < 1e-300) e = Eigen::Vector2d(1, 0);
    fit.direction = (plane * e.normalized()).normalized();
  }
  Vec3 moment = -m22_inv.solve(m12.transpose() * fit.direction);
  moment -= moment.dot(fit.direction) * fit.direction;
  fit.point = fit.direction.cross(moment);
  return fit;
}

// How far a face's normal turns from the plane through the axis and its centroid (radians).
double off_axis_angle(const FaceSample& s, const Vec3& d, const Vec3& a) {
  const Vec3 v = s.q - a;
  const Vec3 radial = v - v.dot(d) * d;
  const double distance = radial.norm();
  if (distance < 1e-9) return 0;
  return std::asin(std::clamp(d.dot(radial.cross(s.n)) / distance, -1.0, 1.0));
}

double tukey(double u) { return std::abs(u) < 1 ? (1 - u * u) * (1 - u * u) : 0; }

// The axis of a given direction whose position the normal lines fit best: with d fixed the
// residual d · ((q − a) × n) = d · (q × n) − a · (n × d) is linear in a (least squares over the
// faces `probe`, a kept square to d).
ComplexFit axis_with_direction(const std::vector<FaceSample>& samples, const std::vector<int>& probe, const Vec3& d) {
  Mat3 normal = Mat3::Zero();
  Vec3 right = Vec3::Zero();
  for (int f : probe) {
    const Vec3 g = samples[f].n.cross(d);
    normal += samples[f].area * g * g.transpose();
    right += samples[f].area * d.dot(samples[f].q.cross(samples[f].n)) * g;
  }
  normal += (1e-9 * normal.trace() + 1e-300) * d * d.transpose();
  ComplexFit fit;
  fit.direction = d;
  fit.point = normal.ldlt().solve(right);
  fit.point -= fit.point.dot(d) * d;
  fit.eigenvalues = Vec3::Zero();
  return fit;
}

// Candidate starts of the reweighting: the least-squares axis of all faces and axes fitted to
// small random sets of faces (RANSAC: 8 faces, drawn by area), the best few by the area whose
// normal lines agree within 2 degrees, one per distinct axis. On a small sherd the break
// surfaces are a third of the area and pull the least-squares axis far off; a set of wall faces
// alone finds the wall's. A small sherd of a bulging wall is also nearly a piece of a torus,
// whose normals meet a second line (the profile's centres of curvature): both are kept here and
// told apart by the profile they give (profile_thickness).
std::vector<ComplexFit> candidate_starts(const std::vector<FaceSample>& samples, const ComplexFit& least_squares) {
  std::vector<double> cumulative(samples.size());
  double total = 0;
  for (size_t f = 0; f < samples.size(); ++f) cumulative[f] = (total += samples[f].area);
  std::vector<int> probe;  // the faces that score a candidate: at most about 20,000
  const size_t stride = std::max<size_t>(1, samples.size() / 20000);
  for (size_t f = 0; f < samples.size(); f += stride) probe.push_back(int(f));
  auto agreement = [&](const ComplexFit& c) {
    double area = 0;
    for (int f : probe)
      if (std::abs(off_axis_angle(samples[f], c.direction, c.point)) < 2 / kDegreesPerRadian) area += samples[f].area;
    return area;
  };
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> uniform(0, total);
  std::vector<std::pair<double, ComplexFit>> scored{{agreement(least_squares), least_squares}};
  for (int trial = 0; trial < 300; ++trial) {
    Mat6 m = Mat6::Zero();
    for (int k = 0; k < 8; ++k) {
      const size_t f = std::upper_bound(cumulative.begin(), cumulative.end(), uniform(rng)) - cumulative.begin();
      const Vec6 l = plucker(samples[std::min(f, samples.size() - 1)]);
      m += l * l.transpose();
    }
    const ComplexFit candidate = fit_line_complex(m);
    scored.emplace_back(agreement(candidate), candidate);
  }
  std::sort(scored.begin(), scored.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<ComplexFit> starts;
  for (const auto& [area, c] : scored) {
    bool distinct = true;
    for (const ComplexFit& s : starts)
      distinct = distinct && (std::abs(s.direction.dot(c.direction)) < std::cos(10 / kDegreesPerRadian) ||
                              (s.point - c.point).norm() > 0.2);
    if (distinct) starts.push_back(c);
    if (starts.size() == 4) break;
  }
  // A small sherd of a bulging wall is nearly a piece of a torus: its normals also meet the
  // tangent of the circle of the profile's centres, which runs along the parallels. The axis of
  // the other family then runs square to that line and to the mean normal.
  Vec3 mean_normal = Vec3::Zero();
  for (int f : probe) mean_normal += samples[f].area * samples[f].n * (samples[f].n.dot(starts[0].direction) >= 0 ? 1 : -1);
  const Vec3 other = starts[0].direction.cross(mean_normal);
  if (other.norm() > 1e-9) starts.push_back(axis_with_direction(samples, probe, other.normalized()));
  return starts;
}

// The wall's faces that measure how thin the profile is about an axis: up to 4000 of the faces
// kept (weight above half) of one wall — those whose normals point away from the axis, or towards
// it if more do (an axis on the wrong side, or a scan with its faces turned inwards).
struct WallPoint {
  Vec3 q, n;
};
std::vector<WallPoint> outer_wall_points(const std::vector<FaceSample>& samples, const std::vector<double>& weight,
                                    const Vec3& d, const Vec3& a) {
  std::vector<WallPoint> away, towards;  // the two walls: normals away from the axis and towards it
  for (size_t f = 0; f < samples.size(); ++f) {
    if (weight[f] <= 0.5 * samples[f].area) continue;
    const Vec3 v = samples[f].q - a;
    const Vec3 radial = v - v.dot(d) * d;
    const double c = radial.norm() > 0 ? radial.normalized().dot(samples[f].n) : 0;
    if (c > 0.5) away.push_back({samples[f].q, samples[f].n});
    if (c < -0.5) towards.push_back({samples[f].q, samples[f].n});
  }
  const std::vector<WallPoint>& points = away.size() >= towards.size() ? away : towards;
  std::vector<WallPoint> kept;
  const size_t stride = std::max<size_t>(1, points.size() / 4000);
  for (size_t k = 0; k < points.size(); k += stride) kept.push_back(points[k]);
  return kept;
}

// How thick the outer wall's profile is about this axis: the points taken to (radius, height),
// ordered along the profile's main direction and cut into 8 runs of equal count, a cubic fitted
// across each; the mean squared residual (frame units squared). A true axis folds the wall from
// all around onto one thin curve; a wrong one smears it, however the normals agree locally.
// Only points whose normal, in the (radius, height) plane, is within 60 degrees of square to the
// main direction count: where the wall turns further (a rounded rim folding over, the corner that
// smoothing rounds at a break) no cubic across the main direction follows it. With them counted
// they ruled a small sherd: its axis leaned 1-3 degrees into a thinner-looking fold (docs/pottery.md).
double profile_thickness(const std::vector<WallPoint>& points, const Vec3& d, const Vec3& a) {
  if (points.size() < 40) return std::numeric_limits<double>::infinity();
  std::vector<Vec2> rz(points.size()), nrz(points.size());
  Vec2 mean = Vec2::Zero();
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec3 v = points[k].q - a;
    const double h = v.dot(d);
    const Vec3 radial = v - h * d;
    rz[k] = Vec2(radial.norm(), h);
    nrz[k] = Vec2(radial.norm() > 0 ? points[k].n.dot(radial) / radial.norm() : 0, points[k].n.dot(d));
    mean += rz[k] / double(points.size());
  }
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const Vec2& p : rz) cov += (p - mean) * (p - mean).transpose();
  const Vec2 along = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov).eigenvectors().col(1);
  const Vec2 across(-along.y(), along.x());
  std::vector<Vec2> ty;
  ty.reserve(rz.size());
  for (size_t k = 0; k < rz.size(); ++k)
    if (std::abs(nrz[k].dot(along)) < 0.5) ty.push_back(Vec2((rz[k] - mean).dot(along), (rz[k] - mean).dot(across)));
  if (ty.size() < 40) return std::numeric_limits<double>::infinity();
  std::sort(ty.begin(), ty.end(), [](const Vec2& x, const Vec2& y) { return x.x() < y.x(); });
  const size_t runs = 8, n = ty.size();
  double sum = 0;
  for (size_t r = 0; r < runs; ++r) {
    const size_t begin = n * r / runs, end = n * (r + 1) / runs;
    const double t0 = ty[begin].x(), span = std::max(ty[end - 1].x() - t0, 1e-12);
    Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
    Eigen::Vector4d right = Eigen::Vector4d::Zero();
    for (size_t k = begin; k < end; ++k) {
      const double t = (ty[k].x() - t0) / span;
      const Eigen::Vector4d basis(1, t, t * t, t * t * t);
      normal += basis * basis.transpose(), right += ty[k].y() * basis;
    }
    const Eigen::Vector4d c = (normal + 1e-12 * Eigen::Matrix4d::Identity()).ldlt().solve(right);
    for (size_t k = begin; k < end; ++k) {
      const double t = (ty[k].x() - t0) / span;
      const double residual = ty[k].y() - (c[0] + t * (c[1] + t * (c[2] + t * c[3])));
      sum += residual * residual;
    }
  }
  return sum / double(n);
}

// One reweighting pass: the axis from the current weights, then each face's weight from its
// angle (Tukey's biweight; the cutoff from the median angle of the faces still weighted).
struct Reweighting {
  ComplexFit fit;
  double cutoff = 0;
  double spread = 0;  // the robust standard deviation of the angles (radians)
};
Reweighting reweight(const std::vector<FaceSample>& samples, const ComplexFit& axis, std::vector<double>& weight,
                     const VesselAxisParams& params) {
  Reweighting r;
  r.fit = axis;
  std::vector<double> angle(samples.size());
  std::vector<std::pair<double, double>> kept;
  const size_t stride = std::max<size_t>(1, samples.size() / 20000);  // the median from about 20,000 faces
  for (size_t f = 0; f < samples.size(); ++f) {
    angle[f] = off_axis_angle(samples[f], r.fit.direction, r.fit.point);
    if (weight[f] > 0 && f % stride == 0) kept.emplace_back(std::abs(angle[f]), samples[f].area);
  }
  const double robust_sigma = 1.4826 * weighted_median(kept);
  r.spread = robust_sigma;
  r.cutoff = params.outlier_angle_deg > 0 ? params.outlier_angle_deg / kDegreesPerRadian
                                          : std::max(4.685 * robust_sigma, 2.0 / kDegreesPerRadian);
  for (size_t f = 0; f < samples.size(); ++f) weight[f] = samples[f].area * tukey(angle[f] / r.cutoff);
  return r;
}

// The axis moved to where the outer wall's profile is thinnest (Nelder-Mead over two angles of
// tilt and two offsets across the axis; steps of 1 degree and of a tenth of a cell to start).
// The normal lines leave a small sherd's axis loosely held — a bulging wall is nearly a piece of
// a torus — while the profile it folds the wall onto is sharp only about the true axis.
ComplexFit thinnest_profile_axis(const std::vector<WallPoint>& probe, const ComplexFit& start, double cell) {
  auto cost = [&](const Eigen::Vector4d& x) {
    const ComplexFit c = moved_axis(start, x);
    return profile_thickness(probe, c.direction, c.point);
  };
  const double steps[4] = {1 / kDegreesPerRadian, 1 / kDegreesPerRadian, 0.1 * cell, 0.1 * cell};
  ComplexFit c = moved_axis(start, nelder_mead(cost, steps, 1e-4 * cell));
  c.point -= c.point.dot(c.direction) * c.direction;
  return c;
}

// Reweighting from a start until the axis settles: the axis from the weights, the weights from the axis.
Reweighting reweight_from(const std::vector<FaceSample>& samples, const ComplexFit& start, std::vector<double>& weight,
                          const VesselAxisParams& params, int& iterations) {
  Reweighting last{start, 0};
  ComplexFit axis = start;
  for (iterations = 1; iterations <= params.max_iterations; ++iterations) {
    Reweighting r = reweight(samples, axis, weight, params);
    r.fit = axis = fit_line_complex(normal_line_moments(samples, weight));
    const bool settled = iterations > 1 && std::abs(r.fit.direction.dot(last.fit.direction)) > 1 - 1e-14 &&
                         (r.fit.point - last.fit.point).norm() < 1e-8;
    last = r;
    if (settled) break;
  }
  iterations = std::min(iterations, params.max_iterations);
  return last;
}

// 16 patches of the piece: 4 by angle around the axis × 4 along it, each holding about the same
// area (for the jackknife).
std::vector<int> piece_patches(const std::vector<FaceSample>& samples, const std::vector<double>& weight, const Vec3& d,
                               const Vec3& a) {
  const Vec3 u = d.unitOrthogonal(), v = d.cross(u);
  std::vector<double> around(samples.size()), along(samples.size());
  for (size_t f = 0; f < samples.size(); ++f) {
    const Vec3 x = samples[f].q - a;
    around[f] = std::atan2(x.dot(v), x.dot(u));
    along[f] = x.dot(d);
  }
  // Angles measured from the middle of the piece's angular range (a sherd may straddle ±π).
  double cx = 0, cy = 0;
  for (size_t f = 0; f < samples.size(); ++f) cx += weight[f] * std::cos(around[f]), cy += weight[f] * std::sin(around[f]);
  const double middle = std::atan2(cy, cx);
  for (double& t : around) t = std::remainder(t - middle, 2 * M_PI);
  auto quartile_of = [&](const std::vector<double>& value) {
    std::vector<std::pair<double, double>> vw;
    for (size_t f = 0; f < samples.size(); ++f)
      if (weight[f] > 0) vw.emplace_back(value[f], weight[f]);
    std::sort(vw.begin(), vw.end());
    double total = 0;
    for (const auto& x : vw) total += x.second;
    std::array<double, 3> cut{};
    double run = 0;
    int k = 0;
    for (const auto& x : vw) {
      run += x.second;
      while (k < 3 && run >= total * (k + 1) / 4) cut[k++] = x.first;
    }
    return cut;
  };
  const auto around_cut = quartile_of(around), along_cut = quartile_of(along);
  std::vector<int> patch(samples.size());
  for (size_t f = 0; f < samples.size(); ++f) {
    const int i = int(std::upper_bound(around_cut.begin(), around_cut.end(), around[f]) - around_cut.begin());
    const int j = int(std::upper_bound(along_cut.begin(), along_cut.end(), along[f]) - along_cut.begin());
    patch[f] = 4 * i + j;
  }
  return patch;
}


// The jackknife over the patches: the fit again without each patch (the moment matrix is a sum
// over faces, so each is the whole minus the patch's), the spread of the directions and of the
// axis' crossing of the plane through the piece's centre across the axis.
struct Jackknife {
  double angle = 0, offset = 0;  // standard errors: radians, frame units
};
Jackknife jackknife(const std::vector<FaceSample>& samples, const std::vector<double>& weight, const ComplexFit& fit) {
  const std::vector<int> patch = piece_patches(samples, weight, fit.direction, fit.point);
  std::array<Mat6, 16> part;
  part.fill(Mat6::Zero());
  for (size_t f = 0; f < samples.size(); ++f)
    if (weight[f] > 0) part[patch[f]] += weight[f] * plucker(samples[f]) * plucker(samples[f]).transpose();
  Mat6 whole = Mat6::Zero();
  for (const Mat6& m : part) whole += m;
  std::vector<Vec3> directions, crossings;
  for (const Mat6& m : part) {
    if (m.trace() <= 0) continue;
    ComplexFit g = fit_line_complex(whole - m);
    if (g.direction.dot(fit.direction) < 0) g.direction = -g.direction;
    const double t = -g.point.dot(fit.direction) / g.direction.dot(fit.direction);
    directions.push_back(g.direction);
    crossings.push_back(g.point + t * g.direction);
  }
  Jackknife j;
  const double k = double(directions.size());
  if (k < 2) return j;
  auto spread = [&](const std::vector<Vec3>& x) {
    Vec3 mean = Vec3::Zero();
    for (const Vec3& v : x) mean += v / k;
    double sum = 0;
    for (const Vec3& v : x) sum += (v - mean).squaredNorm();
    return std::sqrt((k - 1) / k * sum);
  };
  j.angle = spread(directions);
  j.offset = spread(crossings);
  return j;
}

// Refuses what the fit cannot decide, saying what was measured.
// The jackknife of the thinnest-profile step: the wall's probe points cut into 8 groups (quarters
// of the piece's angle about the axis, each in two halves along it), the axis moved to the
// thinnest profile again without each group. Where the profile holds the axis loosely (a small
// body sherd of an evenly rounded shoulder) the 8 answers scatter, and the stated uncertainty
// grows with them; the normal lines' own jackknife sees none of that.
Jackknife profile_jackknife(const std::vector<WallPoint>& probe, const ComplexFit& fit, double cell) {
  Jackknife j;
  if (probe.size() < 400) return j;
  const Vec3 d = fit.direction, u = d.unitOrthogonal(), v = d.cross(u);
  std::vector<std::pair<double, size_t>> around(probe.size());
  Vec3 centre = Vec3::Zero();
  for (const WallPoint& p : probe) centre += p.q / double(probe.size());
  const Vec3 middle = centre - fit.point;
  const double middle_angle = std::atan2(middle.dot(v), middle.dot(u));
  std::vector<double> along(probe.size());
  for (size_t k = 0; k < probe.size(); ++k) {
    const Vec3 x = probe[k].q - fit.point;
    around[k] = {std::remainder(std::atan2(x.dot(v), x.dot(u)) - middle_angle, 2 * M_PI), k};
    along[k] = (probe[k].q - centre).dot(d);
  }
  std::sort(around.begin(), around.end());
  constexpr int kGroups = 8;
  std::array<std::vector<WallPoint>, kGroups> without;
  for (size_t rank = 0; rank < around.size(); ++rank) {
    const size_t k = around[rank].second;
    const int group = 2 * int(4 * rank / around.size()) + (along[k] > 0);
    for (int g = 0; g < kGroups; ++g)
      if (g != group) without[size_t(g)].push_back(probe[k]);
  }
  std::array<ComplexFit, kGroups> refit;
#pragma omp parallel for schedule(dynamic, 1)
  for (int g = 0; g < kGroups; ++g) refit[size_t(g)] = thinnest_profile_axis(without[size_t(g)], fit, cell);
  double angles = 0, offsets = 0;
  for (const ComplexFit& r : refit) {
    const Vec3 rd = r.direction.dot(d) < 0 ? Vec3(-r.direction) : r.direction;
    angles += std::pow(std::acos(std::min(1.0, rd.dot(d))), 2);
    // Where each axis crosses the plane through the probe's centre across the full fit's axis.
    const Vec3 here = fit.point + (centre - fit.point).dot(d) * d;
    const Vec3 there = r.point + (here - r.point).dot(d) / rd.dot(d) * rd;
    offsets += (there - here).squaredNorm();
  }
  j.angle = std::sqrt((kGroups - 1.0) / kGroups * angles);
  j.offset = std::sqrt((kGroups - 1.0) / kGroups * offsets);
  return j;
}

void check_determined(const VesselAxisFit& fit) {
  char what[400];
  if (fit.direction_ambiguity > 0.3) {
    std::snprintf(what, sizeof what,
                  "no axis of revolution is determined: directions fit about equally well (ratio of the two best "
                  "%.2f; a sphere or a piece of one fits every axis through its centre)",
                  fit.direction_ambiguity);
    throw InputError(what);
  }
  if (fit.position_spread < 1e-3) {
    std::snprintf(what, sizeof what,
                  "no axis of revolution is determined: the surface's normals are nearly parallel (spread %.1e; a flat "
                  "piece fits every axis square to it)",
                  fit.position_spread);
    throw InputError(what);
  }
  if (fit.wall_share < 0.35 || fit.rms_angle_deg > 8) {
    std::snprintf(what, sizeof what,
                  "this is no piece of a surface of revolution: the normals of only %.0f %% of the surface meet one "
                  "line within %.1f degrees (the rest turn away: a figurine, a tile, a fragment of something not "
                  "thrown on a wheel); give the axis if it is known",
                  100 * fit.wall_share, fit.cutoff_deg);
    throw InputError(what);
  }
}

// How fully the weighted normals span the plane across the axis: the ratio of the two
// eigenvalues of their moments there (1: all around, as on a whole pot; 0: all parallel).
double normal_spread_across(const std::vector<FaceSample>& samples, const std::vector<double>& weight, const Vec3& d) {
  Mat3 m = Mat3::Zero();
  for (size_t f = 0; f < samples.size(); ++f) {
    if (weight[f] <= 0) continue;
    const Vec3 n = samples[f].n - samples[f].n.dot(d) * d;
    m += weight[f] * n * n.transpose();
  }
  const Vec3 u = d.unitOrthogonal(), v = d.cross(u);
  const double uu = u.dot(m * u), uv = u.dot(m * v), vv = v.dot(m * v);
  const double mean = (uu + vv) / 2, radius = std::hypot((uu - vv) / 2, uv);  // the 2 × 2 eigenvalues
  return mean + radius > 0 ? std::max(mean - radius, 0.0) / (mean + radius) : 0;
}

// Each start reweighted, then moved to the thinnest profile (`cell`: the first offset step).
struct Tried {
  Reweighting r;
  std::vector<double> w;
  double thickness = 0;
  int iterations = 0;
};
std::vector<Tried> try_candidates(const std::vector<FaceSample>& samples, const VesselAxisParams& params, double cell) {
  std::vector<double> area(samples.size());
  for (size_t f = 0; f < samples.size(); ++f) area[f] = samples[f].area;
  std::vector<Tried> tried;
  for (const ComplexFit& start : candidate_starts(samples, fit_line_complex(normal_line_moments(samples, area)))) {
    Tried t;
    t.w.resize(samples.size());
    t.r = reweight_from(samples, start, t.w, params, t.iterations);
    const std::vector<WallPoint> probe = outer_wall_points(samples, t.w, t.r.fit.direction, t.r.fit.point);
    t.r.fit = thinnest_profile_axis(probe, t.r.fit, cell);
    t.thickness = profile_thickness(probe, t.r.fit.direction, t.r.fit.point);
    tried.push_back(std::move(t));
  }
  return tried;
}

// Only the axes whose normal lines agree about as tightly as the best's (robust spread of the
// angles within 1.5 times the least) compete on the profile: an axis running beside or through a
// small piece can fold its wall thinly too, but its normals agree only within 10 degrees where the
// wall's own axis has 3. Two axes more than 10 degrees apart that fold the wall about as thinly
// (within twice): the piece cannot tell them apart (a small sherd of a bulging wall is nearly a
// piece of a torus), refused.
const Tried& choose_axis(const std::vector<Tried>& tried) {
  double tightest = std::numeric_limits<double>::infinity();
  for (const Tried& t : tried) tightest = std::min(tightest, t.r.spread);
  const Tried* chosen = nullptr;
  for (const Tried& t : tried)
    if (t.r.spread <= 1.5 * tightest && (!chosen || t.thickness < chosen->thickness)) chosen = &t;
  for (const Tried& t : tried) {
    const double cosine = std::abs(t.r.fit.direction.dot(chosen->r.fit.direction));
    if (t.r.spread <= 1.5 * tightest && cosine < std::cos(10 / kDegreesPerRadian) && t.thickness < 2 * chosen->thickness) {
      char what[300];
      std::snprintf(what, sizeof what,
                    "two axes fit this piece about equally well (%.0f degrees apart; the profile about the second is "
                    "only %.1f times as thick): it is too small or too evenly curved to tell; give the axis, or scan "
                    "a piece with rim or base",
                    std::acos(std::min(1.0, cosine)) * kDegreesPerRadian, t.thickness / chosen->thickness);
      throw InputError(what);
    }
  }
  return *chosen;
}

// Every face (not only the fit's sample) weighed about the chosen axis with its cut-off; the
// share of the area kept and the rms angle of the wall.
void weigh_every_face(const std::vector<FaceSample>& all, const Reweighting& last, VesselAxisFit& fit) {
  const ComplexFit& axis = last.fit;
  double total = 0, kept = 0, angle_sum = 0, weight_sum = 0;
  fit.face_weight.resize(all.size());
  fit.face_normal.resize(all.size());
  for (size_t f = 0; f < all.size(); ++f) {
    const double a = all[f].area;
    const double angle = off_axis_angle(all[f], axis.direction, axis.point);
    fit.face_weight[f] = a > 0 ? tukey(angle / last.cutoff) : 0;
    fit.face_normal[f] = all[f].n;
    total += a;
    if (fit.face_weight[f] > 0.5) kept += a;
    angle_sum += a * fit.face_weight[f] * angle * angle;
    weight_sum += a * fit.face_weight[f];
  }
  fit.wall_share = kept / total;
  fit.rms_angle_deg = weight_sum > 0 ? std::sqrt(angle_sum / weight_sum) * kDegreesPerRadian : 90;
  fit.cutoff_deg = last.cutoff * kDegreesPerRadian;
}

}  // namespace

void VesselAxisParams::validate() const {
  if (!(outlier_angle_deg >= 0 && outlier_angle_deg <= 45))
    throw InputError("Outlier angle must be between 0 (automatic) and 45 degrees");
  if (max_iterations < 1 || max_iterations > 1000) throw InputError("Iterations must be between 1 and 1000");
  if (!(smoothing_edges >= 0 && smoothing_edges <= 50)) throw InputError("Normal smoothing must be between 0 and 50 edge lengths");
}

std::vector<Vec3> smoothed_face_normals(const Surface& surface, double smoothing_edges) {
  const Surface smoothed = smoothed_surface(surface, smoothing_edges * surface.scale().edge);
  PieceFrame frame;
  const std::vector<FaceSample> samples = face_samples(smoothed.mesh(), smoothed.normals(), frame);
  std::vector<Vec3> normal(samples.size());
  for (size_t f = 0; f < samples.size(); ++f) normal[f] = samples[f].n;
  return normal;
}

std::vector<double> off_axis_angles(const TriMesh& mesh, const std::vector<Vec3>& face_normal, const AxisLine& axis) {
  std::vector<double> angle(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    FaceSample s;
    s.q = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3;
    s.n = face_normal[f];
    angle[f] = std::abs(off_axis_angle(s, axis.direction, axis.point)) * kDegreesPerRadian;
  }
  return angle;
}

VesselAxisFit fit_vessel_axis(const Surface& surface, const VesselAxisParams& params) {
  params.validate();
  surface.require_triangles();
  require_usable_scale(surface.scale());
  PieceFrame frame;
  const Surface smoothed = smoothed_surface(surface, params.smoothing_edges * surface.scale().edge);
  const std::vector<FaceSample> all = face_samples(smoothed.mesh(), smoothed.normals(), frame);
  // The fit runs on at most kFitFaces faces, evenly strided (their areas weigh them): more add
  // nothing to an axis held by the whole piece, and the last step weighs every face.
  std::vector<FaceSample> samples;
  const size_t stride = (all.size() + kFitFaces - 1) / kFitFaces;
  for (size_t f = 0; f < all.size(); f += stride) samples.push_back(all[f]);
  const double cell = 3 * surface.scale().edge / frame.scale;
  const std::vector<Tried> tried = try_candidates(samples, params, cell);
  const Tried& chosen = choose_axis(tried);
  const ComplexFit& axis = chosen.r.fit;
  VesselAxisFit fit;
  fit.iterations = chosen.iterations;
  weigh_every_face(all, chosen.r, fit);
  fit.direction_ambiguity = axis.eigenvalues[1] > 0 ? std::max(axis.eigenvalues[0], 0.0) / axis.eigenvalues[1] : 1;
  fit.position_spread = normal_spread_across(samples, chosen.w, axis.direction);
  check_determined(fit);
  const Jackknife j = jackknife(samples, chosen.w, axis);
  const Jackknife p = profile_jackknife(outer_wall_points(samples, chosen.w, axis.direction, axis.point), axis, cell);
  fit.angle_uncertainty_deg = std::max(j.angle, p.angle) * kDegreesPerRadian;
  fit.offset_uncertainty = std::max(j.offset, p.offset) * frame.scale;
  fit.axis.direction = axis.direction;
  fit.axis.point = frame.centre + frame.scale * (axis.point - axis.point.dot(axis.direction) * axis.direction);
  return fit;
}

}  // namespace reliefkit
