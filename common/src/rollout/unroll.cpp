// ReliefKit — rollouts around an axis. See reliefkit/rollout/unroll.h.
#include "reliefkit/rollout/unroll.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>

#include <Eigen/Dense>

#include "reliefkit/base/scale.h"

namespace reliefkit {
namespace {

constexpr double kPi = M_PI;
constexpr double kDeg = 180.0 / M_PI;

bool report(Progress progress, int percent, const char* what) { return progress ? progress(percent, what) : true; }

// The angle in (-pi, pi].
double wrapped(double angle) {
  const double a = std::remainder(angle, 2 * kPi);
  return a <= -kPi ? a + 2 * kPi : a;
}

// The axis as asked: fitted (the vessel fit, which refuses what turns about no axis), +Z through
// the origin (a mesh "Vessel Axis and Profile" oriented), or given.
AxisLine axis_for(const Surface& surface, const UnrollParams& params, Rollout& out) {
  out.axis_source = params.axis_source;
  switch (params.axis_source) {
    case AxisSource::oriented_z:
      return AxisLine{};
    case AxisSource::given: {
      AxisLine a = params.given_axis;
      a.direction.normalize();
      return a;
    }
    case AxisSource::fitted:
      break;
  }
  out.fit = fit_vessel_axis(surface, params.fit);
  return out.fit->axis;
}

// The direction angles are measured from: the scan's +x square to the axis (its +y when the axis
// runs along x).
Vec3 reference_direction(const Vec3& d) {
  Vec3 u = Vec3::UnitX() - d.x() * d;
  if (u.norm() < 0.1) u = Vec3::UnitY() - d.y() * d;
  return u.normalized();
}

// Radius and height of a point about the axis.
Vec2 radius_height(const Vec3& p, const AxisLine& axis) {
  const Vec3 q = p - axis.point;
  const double z = q.dot(axis.direction);
  return Vec2((q - z * axis.direction).norm(), z);
}

// The radius of the outer surface height by height: faces facing outwards (their normal within
// 60 degrees of the radial direction; the other way round if most face inwards) binned by height
// (bins of 2 edges, at most 400), each bin's area-weighted median radius.
std::vector<Vec2> median_radii(const TriMesh& mesh, const AxisLine& axis, double edge, double& bin) {
  struct FaceRZ {
    Vec2 rz;
    double area, facing;
  };
  std::vector<FaceRZ> faces;
  faces.reserve(mesh.faces.size());
  long outwards = 0, inwards = 0;
  double z_min = INFINITY, z_max = -INFINITY;
  for (const auto& t : mesh.faces) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 cross = (b - a).cross(c - a);
    const Vec3 centre = (a + b + c) / 3, q = centre - axis.point;
    const Vec3 radial = q - q.dot(axis.direction) * axis.direction;
    if (!(cross.norm() > 0) || !(radial.norm() > 0)) continue;
    const double facing = radial.normalized().dot(cross.normalized());
    outwards += facing > 0.5, inwards += facing < -0.5;
    faces.push_back({radius_height(centre, axis), cross.norm() / 2, facing});
    z_min = std::min(z_min, faces.back().rz.y()), z_max = std::max(z_max, faces.back().rz.y());
  }
  const double sign = outwards >= inwards ? 1 : -1;
  bin = std::max(2 * edge, (z_max - z_min) / 400);
  const int bins = std::max(1, int(std::ceil((z_max - z_min) / bin)));
  std::vector<std::vector<std::pair<double, double>>> radii(static_cast<size_t>(bins));
  for (const FaceRZ& f : faces)
    if (sign * f.facing > 0.5) radii[size_t(std::clamp(int((f.rz.y() - z_min) / bin), 0, bins - 1))].emplace_back(f.rz.x(), f.area);
  std::vector<Vec2> raw;
  for (int k = 0; k < bins; ++k)
    if (radii[size_t(k)].size() >= 3) raw.emplace_back(weighted_median(radii[size_t(k)]), z_min + (k + 0.5) * bin);
  if (raw.size() < 2)
    throw InputError("no wall to unroll: fewer than two heights along the axis have faces facing away from it (a flat "
                     "piece square to the axis, or an axis that runs through the piece)");
  return raw;
}

// Straight: the Theil-Sen line through the radii (the median of the pairwise slopes), robust to
// bands and grooves on up to about a third of the length.
std::vector<Vec2> straight_profile(const std::vector<Vec2>& raw) {
  std::vector<double> slopes;
  const size_t step = std::max<size_t>(1, raw.size() / 200);
  for (size_t i = 0; i < raw.size(); i += step)
    for (size_t j = i + step; j < raw.size(); j += step) slopes.push_back((raw[j].x() - raw[i].x()) / (raw[j].y() - raw[i].y()));
  const double slope = slopes.empty() ? 0 : percentile(slopes, 0.5);
  std::vector<double> offsets;
  for (const Vec2& q : raw) offsets.push_back(q.x() - slope * q.y());
  const double offset = percentile(offsets, 0.5);
  return {Vec2(offset + slope * raw.front().y(), raw.front().y()), Vec2(offset + slope * raw.back().y(), raw.back().y())};
}


// One pass of local regression: at each height a quadratic fitted to the radii within half the
// window, weighted by the tricube of the distance and by `robustness`.
std::vector<double> lowess_pass(const std::vector<Vec2>& raw, double window, const std::vector<double>& robustness) {
  const size_t n = raw.size();
  std::vector<double> fitted(n);
  for (size_t k = 0; k < n; ++k) {
    Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
    Eigen::Vector3d right = Eigen::Vector3d::Zero();
    for (size_t j = 0; j < n; ++j) {
      const double u = (raw[j].y() - raw[k].y()) / (window / 2);
      if (std::abs(u) >= 1) continue;
      const double w = std::pow(1 - std::pow(std::abs(u), 3), 3) * robustness[j];
      const Eigen::Vector3d basis(1, u, u * u);
      normal += w * basis * basis.transpose(), right += w * raw[j].x() * basis;
    }
    const Eigen::Vector3d c = (normal + 1e-12 * normal.trace() * Eigen::Matrix3d::Identity()).ldlt().solve(right);
    fitted[k] = std::isfinite(c[0]) && normal.trace() > 0 ? c[0] : raw[k].x();
  }
  return fitted;
}

// The residuals' biweight (at 6 median absolute residuals): 1 for a radius on the fit, 0 for one
// well off it (a band, a groove).
std::vector<double> robustness_weights(const std::vector<Vec2>& raw, const std::vector<double>& fitted) {
  std::vector<double> residual(raw.size()), weight(raw.size());
  for (size_t k = 0; k < raw.size(); ++k) residual[k] = std::abs(raw[k].x() - fitted[k]);
  const double scale = 6 * percentile(residual, 0.5);
  for (size_t k = 0; k < raw.size(); ++k) {
    const double u = scale > 0 ? residual[k] / scale : 0;
    weight[k] = u < 1 ? (1 - u * u) * (1 - u * u) : 0;
  }
  return weight;
}

// Smooth: the radii by robust local regression (LOWESS, Cleveland 1979), the robust passes
// started from the straight line through the radii (Theil-Sen) when its median absolute residual
// is within twice the plain local fit's, else from the plain fit: a band round a straight wall
// bends the plain fit (a quadratic over the window follows a band of a third of it) but is an
// outlier of the line; on a curved wall the line fits nothing. A band or groove is then left out
// as relief; on a curved wall only one narrower than about a fifth of the window is.
std::vector<Vec2> smooth_profile(const std::vector<Vec2>& raw, double window) {
  const size_t n = raw.size();
  std::vector<double> fitted = lowess_pass(raw, window, std::vector<double>(n, 1)), line(n), off_fit(n), off_line(n);
  const std::vector<Vec2> straight = straight_profile(raw);
  const double slope = (straight[1].x() - straight[0].x()) / std::max(straight[1].y() - straight[0].y(), 1e-300);
  for (size_t k = 0; k < n; ++k) {
    line[k] = straight[0].x() + slope * (raw[k].y() - straight[0].y());
    off_fit[k] = std::abs(raw[k].x() - fitted[k]), off_line[k] = std::abs(raw[k].x() - line[k]);
  }
  if (percentile(off_line, 0.5) < 2 * percentile(off_fit, 0.5)) fitted = line;
  for (int pass = 0; pass < 3; ++pass) fitted = lowess_pass(raw, window, robustness_weights(raw, fitted));
  std::vector<Vec2> out(n);
  for (size_t k = 0; k < n; ++k) out[k] = Vec2(fitted[k], raw[k].y());
  return out;
}

BaseProfile base_profile(const TriMesh& mesh, const AxisLine& axis, double edge, const UnrollParams& params) {
  double bin = 0;
  const std::vector<Vec2> raw = median_radii(mesh, axis, edge, bin);
  const double length = raw.back().y() - raw.front().y();
  const double window = params.base_window_edges > 0 ? params.base_window_edges * edge : std::max(20 * edge, length / 2);
  BaseProfile base;
  base.rz = params.base == BaseShape::straight ? straight_profile(raw) : smooth_profile(raw, window);
  base.s.assign(base.rz.size(), 0);
  for (size_t k = 1; k < base.rz.size(); ++k) base.s[k] = base.s[k - 1] + (base.rz[k] - base.rz[k - 1]).norm();
  return base;
}

}  // namespace

void UnrollParams::validate() const {
  if (axis_source == AxisSource::given &&
      !(given_axis.direction.allFinite() && given_axis.point.allFinite() && given_axis.direction.norm() > 1e-12))
    throw InputError("Axis direction (given) must be a finite, non-zero vector and Axis point (given) finite");
  if (seam_deg && !std::isfinite(*seam_deg)) throw InputError("Seam angle must be a number of degrees");
  if (!(base_window_edges >= 0 && base_window_edges <= 1e6)) throw InputError("Base window must be 0 (automatic) or a positive number of edge lengths");
  fit.validate();
}

BaseProfile::Foot BaseProfile::foot(const Vec2& p) const {
  Foot best;
  double best_d2 = INFINITY;
  auto try_segment = [&](size_t k) {
    const Vec2 a = rz[k], ab = rz[k + 1] - a;
    const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0;
    const Vec2 q = a + t * ab;
    const double d2 = (p - q).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best.s = s[k] + t * (s[k + 1] - s[k]);
      best.point = q;
      const Vec2 along = ab.norm() > 0 ? Vec2(ab.normalized()) : Vec2::UnitY();
      best.normal = Vec2(along.y(), -along.x());  // heights increase along the profile: right of it is outwards
    }
  };
  // Heights increase along the profile: start at the point's height and widen while a segment
  // could still be nearer than the best.
  const size_t n = rz.size();
  size_t i = size_t(std::lower_bound(rz.begin(), rz.end(), p.y(), [](const Vec2& a, double z) { return a.y() < z; }) - rz.begin());
  i = std::min(i, n - 1);
  for (size_t k = i; k-- > 0;) {
    if ((p.y() - rz[k + 1].y()) * (p.y() - rz[k + 1].y()) > best_d2 && rz[k + 1].y() < p.y()) break;
    try_segment(k);
  }
  for (size_t k = i; k + 1 < n; ++k) {
    if ((rz[k].y() - p.y()) * (rz[k].y() - p.y()) > best_d2 && rz[k].y() > p.y()) break;
    try_segment(k);
  }
  return best;
}

Vec2 BaseProfile::at(double arc_length) const {
  const double t = std::clamp(arc_length, 0.0, s.back());
  const size_t k = std::min(size_t(std::upper_bound(s.begin(), s.end(), t) - s.begin()), s.size() - 1);
  if (k == 0) return rz.front();
  const double span = s[k] - s[k - 1];
  return span > 0 ? Vec2(rz[k - 1] + (t - s[k - 1]) / span * (rz[k] - rz[k - 1])) : rz[k];
}

double BaseProfile::slope_at(double arc_length) const {
  const double h = std::max(s.back() / 20, 1e-12);
  const double a = std::max(arc_length - h, 0.0), b = std::min(arc_length + h, s.back());
  return b > a ? (at(b).x() - at(a).x()) / (b - a) : 0;
}

RolloutMap::RolloutMap(const AxisLine& axis, const Vec3& reference, BaseProfile base, double seam_angle, bool impression)
    : axis_(axis), u_(reference), v_(axis.direction.cross(reference)), base_(std::move(base)), seam_(seam_angle),
      impression_(impression) {
  s0_ = base_.s.back() / 2;
  r0_ = base_.at(s0_).x();
  const double slope = base_.slope_at(s0_);  // d radius / d arc length: the sine of the cone's half-angle
  apex_ = std::abs(slope) > 1e-6 ? r0_ / slope : 0;
}

double RolloutMap::angle_of(const Vec3& p) const {
  const Vec3 q = p - axis_.point;
  return wrapped(std::atan2(q.dot(v_), q.dot(u_)) - seam_ - kPi);
}

// The developed base: the parallel at `arc_length` on an arc of its true length about the common
// centre, `angle` from the middle meridian. A cylinder (no centre): straight parallels.
Vec2 RolloutMap::develop(double angle, double arc_length) const {
  const double r = base_.at(arc_length).x();
  if (apex_ == 0) return Vec2(angle * r, arc_length - s0_);
  const double rho = apex_ + (arc_length - s0_);
  if (std::abs(rho) < 1e-12 * std::max(r0_, 1e-300)) return Vec2(0, -apex_);
  const double beta = angle * r / rho;
  return Vec2(rho * std::sin(beta), rho * std::cos(beta) - apex_);
}

RolloutMap::Point RolloutMap::map(const Vec3& p, int turns) const {
  Point out;
  out.angle = angle_of(p) + 2 * kPi * turns;
  const Vec2 rz = radius_height(p, axis_);
  const BaseProfile::Foot f = base_.foot(rz);
  const double height = (rz - f.point).dot(f.normal);
  const Vec2 xy = develop(out.angle, f.s);
  out.position = impression_ ? Vec3(-xy.x(), xy.y(), -height) : Vec3(xy.x(), xy.y(), height);
  const double theta = out.angle + seam_ + kPi;
  out.base_point = axis_.point + f.point.y() * axis_.direction + f.point.x() * (std::cos(theta) * u_ + std::sin(theta) * v_);
  return out;
}

namespace {

// The seam's angle from the reference direction: the middle of the widest sector without faces
// when there is one of at least 3 degrees (a sherd, an open piece); else the degree whose faces
// rise least off the base (the rms height of its vertices, over three degrees).
double automatic_seam(const TriMesh& mesh, const std::vector<double>& angle, const std::vector<double>& height, Rollout& out) {
  constexpr int kBins = 360;
  std::vector<int> count(kBins, 0);
  std::vector<double> squares(kBins, 0);
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const int b = std::clamp(int((angle[i] + kPi) / (2 * kPi) * kBins), 0, kBins - 1);
    ++count[size_t(b)], squares[size_t(b)] += height[i] * height[i];
  }
  int best_start = -1, best_length = 0;
  for (int start = 0; start < kBins; ++start) {
    if (count[size_t(start)] > 0 || count[size_t((start + kBins - 1) % kBins)] == 0) continue;
    int length = 0;
    while (length < kBins && count[size_t((start + length) % kBins)] == 0) ++length;
    if (length > best_length) best_length = length, best_start = start;
  }
  out.seam_automatic = true;
  if (best_length >= 3) {
    out.seam_in_gap = true;
    return (best_start + best_length / 2.0) / kBins * 2 * kPi - kPi;
  }
  double least = INFINITY;
  int chosen = 0;
  for (int b = 0; b < kBins; ++b) {
    double s = 0;
    int n = 0;
    for (int k = -1; k <= 1; ++k) s += squares[size_t((b + k + kBins) % kBins)], n += count[size_t((b + k + kBins) % kBins)];
    if (n > 0 && s / n < least) least = s / n, chosen = b;
  }
  out.seam_relief = std::sqrt(least);
  return (chosen + 0.5) / kBins * 2 * kPi - kPi;
}

// Faces across the seam: their vertices on the far side (angle below zero, the face reaching over
// +pi) copied past the seam, so that the face lies whole on the sheet's +pi edge.
void cut_seam(const std::vector<double>& angle, Rollout& out) {
  std::map<int, int> copy;
  for (auto& t : out.mesh.faces) {
    double low = INFINITY, high = -INFINITY;
    for (int v : t) low = std::min(low, angle[size_t(v)]), high = std::max(high, angle[size_t(v)]);
    if (high - low <= kPi) continue;
    for (int& v : t) {
      if (angle[size_t(v)] >= 0) continue;
      auto [it, added] = copy.emplace(v, int(out.mesh.vertices.size()));
      if (added) {
        out.copy_of.push_back(v);
        const Vec3 p = out.mesh.vertices[size_t(v)];  // its sheet position is set with the others
        out.mesh.vertices.push_back(p);
      }
      v = it->second;
    }
  }
}

// Each face edge's change of length from the base surface to the developed sheet (0.01: 1 %);
// per vertex the mean over the edges of its faces.
void measure_stretch(const std::vector<Vec3>& base_point, const std::vector<Vec3>& sheet, Rollout& out) {
  std::vector<double> edge_stretch;
  edge_stretch.reserve(3 * out.mesh.faces.size());
  std::vector<double> sum(out.mesh.vertices.size(), 0);
  std::vector<int> n(out.mesh.vertices.size(), 0);
  for (const auto& t : out.mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
      const double on_base = (base_point[size_t(a)] - base_point[size_t(b)]).norm();
      if (!(on_base > 0)) continue;
      const double change = std::abs((sheet[size_t(a)] - sheet[size_t(b)]).head<2>().norm() / on_base - 1);
      edge_stretch.push_back(change);
      sum[size_t(a)] += change, ++n[size_t(a)], sum[size_t(b)] += change, ++n[size_t(b)];
    }
  out.stretch.assign(out.mesh.vertices.size(), 0);
  for (size_t v = 0; v < sum.size(); ++v)
    if (n[v] > 0) out.stretch[v] = sum[v] / n[v];
  if (!edge_stretch.empty()) {
    out.stretch_median = percentile(edge_stretch, 0.5);
    out.stretch_p90 = percentile(edge_stretch, 0.9);
  }
}

// Beyond this rms distance from the base (a share of its radius) a fitted axis is refused: the
// shared scans' coin and ingot, which the vessel fit lets through, lie 40 % and 42 % off at
// defaults; the tests' seal with figures 1 mm high on a 15 mm radius, well under 10 %.
constexpr double kNotTurned = 0.1;

void refuse_if_not_turned(Rollout& out, int input_vertices, AxisSource source) {
  double sum = 0;
  for (int i = 0; i < input_vertices; ++i) sum += out.height[size_t(i)] * out.height[size_t(i)];
  out.relief_rms = input_vertices > 0 ? std::sqrt(sum / input_vertices) : 0;
  const double radius = out.map->reference_radius();
  if (source != AxisSource::fitted || !(out.relief_rms > kNotTurned * radius)) return;
  char what[400];
  std::snprintf(what, sizeof what,
                "the surface does not turn about the fitted axis: it lies %.3g (rms) from its base, %.0f %% of the base's "
                "radius %.3g (a coin's face, an ingot, a figurine); give the axis if it should be unrolled about one",
                out.relief_rms, 100 * out.relief_rms / radius, radius);
  throw InputError(what);
}

}  // namespace

Rollout unroll(const Surface& surface, const UnrollParams& params) {
  params.validate();
  surface.require_triangles();
  Rollout out;
  out.impression = params.impression;
  report(params.progress, 5, "Finding the axis");
  const AxisLine axis = axis_for(surface, params, out);
  const TriMesh& mesh = surface.mesh();
  report(params.progress, 40, "Building the base");
  BaseProfile base = base_profile(mesh, axis, surface.scale().edge, params);
  const Vec3 reference = reference_direction(axis.direction);
  // Angles and heights once with the seam at the reference direction, to place the seam.
  double seam = 0;
  if (params.seam_deg) {
    seam = wrapped(*params.seam_deg / kDeg);
  } else {
    const RolloutMap probe(axis, reference, base, -kPi, false);  // angles measured from the reference direction
    std::vector<double> angle(mesh.vertices.size()), height(mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
      const RolloutMap::Point p = probe.map(mesh.vertices[i]);
      angle[i] = p.angle, height[i] = p.position.z();
    }
    seam = automatic_seam(mesh, angle, height, out);
  }
  report(params.progress, 60, "Unrolling");
  out.map.emplace(axis, reference, std::move(base), seam, params.impression);
  const RolloutMap& map = *out.map;
  out.mesh = mesh;
  std::vector<double> angle(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) angle[i] = map.angle_of(mesh.vertices[i]);
  cut_seam(angle, out);
  std::vector<Vec3> sheet(out.mesh.vertices.size()), base_point(out.mesh.vertices.size());
  out.height.assign(out.mesh.vertices.size(), 0);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(out.mesh.vertices.size()); ++i) {
    const bool copy = size_t(i) >= mesh.vertices.size();
    const RolloutMap::Point p = map.map(mesh.vertices[copy ? size_t(out.copy_of[size_t(i) - mesh.vertices.size()]) : size_t(i)], copy ? 1 : 0);
    sheet[size_t(i)] = p.position, base_point[size_t(i)] = p.base_point, out.height[size_t(i)] = p.position.z();
  }
  report(params.progress, 85, "Measuring the stretch");
  measure_stretch(base_point, sheet, out);
  out.mesh.vertices = std::move(sheet);
  if (params.impression)  // mirrored: each face turned back to face +Z, as the surface faced outwards
    for (auto& t : out.mesh.faces) std::swap(t[1], t[2]);
  out.width = 2 * kPi * map.reference_radius();
  refuse_if_not_turned(out, mesh.n_vertices(), params.axis_source);
  report(params.progress, 100, "Done");
  return out;
}

Polylines unroll_curves(const Polylines& curves, const RolloutMap& map) {
  Polylines out;
  std::vector<RolloutMap::Point> mapped(curves.points.size());
  for (size_t k = 0; k < curves.points.size(); ++k) mapped[k] = map.map(curves.points[k]);
  auto strength = [&](size_t k) { return k < curves.strength.size() ? curves.strength[k] : 0.0; };
  for (size_t k = 0; k < curves.points.size(); ++k) out.points.push_back(mapped[k].position), out.strength.push_back(strength(k));
  for (const auto& seg : curves.segments) {
    const RolloutMap::Point &a = mapped[size_t(seg[0])], &b = mapped[size_t(seg[1])];
    if (std::abs(a.angle - b.angle) <= kPi) {
      out.segments.push_back(seg);
      continue;
    }
    // Across the seam: the crossing on each edge of the sheet.
    const int high = a.angle > b.angle ? seg[0] : seg[1], low = a.angle > b.angle ? seg[1] : seg[0];
    const double ah = mapped[size_t(high)].angle, al = mapped[size_t(low)].angle + 2 * kPi;
    const double t = al > ah ? (kPi - ah) / (al - ah) : 0.5;
    const Vec3 crossing = curves.points[size_t(high)] + t * (curves.points[size_t(low)] - curves.points[size_t(high)]);
    const double c = map.angle_of(crossing);
    const int at_high = int(out.points.size());
    out.points.push_back(map.map(crossing, c < 0 ? 1 : 0).position), out.strength.push_back(strength(size_t(high)));
    out.points.push_back(map.map(crossing, c > 0 ? -1 : 0).position), out.strength.push_back(strength(size_t(low)));
    out.segments.push_back({high, at_high});
    out.segments.push_back({at_high + 1, low});
  }
  return out;
}

std::vector<std::string> rollout_log_lines(const Rollout& r) {
  std::vector<std::string> lines;
  char text[600];
  const RolloutMap& m = *r.map;
  const Vec3 a = m.axis().point, d = m.axis().direction;
  const char* source = r.axis_source == AxisSource::fitted ? "fitted (as Vessel Axis and Profile fits it)"
                       : r.axis_source == AxisSource::oriented_z ? "+Z through the origin (the mesh as Vessel Axis and Profile oriented it)"
                                                                  : "as given";
  std::snprintf(text, sizeof text, "Axis: through (%.6g, %.6g, %.6g), direction (%.6f, %.6f, %.6f), %s.", a.x(), a.y(), a.z(),
                d.x(), d.y(), d.z(), source);
  lines.push_back(text);
  if (r.fit) {
    std::snprintf(text, sizeof text,
                  "Fit: the normals of %.0f %% of the surface meet the axis (rms %.2f degrees); uncertainty of the axis %.2f degrees.",
                  100 * r.fit->wall_share, r.fit->rms_angle_deg, r.fit->angle_uncertainty_deg);
    lines.push_back(text);
  }
  const BaseProfile& b = m.base();
  std::snprintf(text, sizeof text,
                "Base: %s through the outer surface's median radius height by height, %zu heights over %.4g along the axis; "
                "radius %.4g to %.4g; the reference parallel (true along the sheet's width) at radius %.4g, circumference %.5g.",
                b.rz.size() == 2 ? "a cylinder or cone" : "a smooth profile", b.rz.size(), b.rz.back().y() - b.rz.front().y(), std::min_element(b.rz.begin(), b.rz.end(), [](auto& x, auto& y) { return x.x() < y.x(); })->x(),
                std::max_element(b.rz.begin(), b.rz.end(), [](auto& x, auto& y) { return x.x() < y.x(); })->x(), m.reference_radius(), r.width);
  lines.push_back(text);
  if (r.seam_in_gap)
    std::snprintf(text, sizeof text, "Seam: at %.1f degrees, in the middle of the widest sector the piece does not cover (chosen).",
                  m.seam_angle() * kDeg);
  else if (r.seam_automatic)
    std::snprintf(text, sizeof text, "Seam: at %.1f degrees, where the surface rises least off the base (rms %.3g; chosen); %zu vertices copied to cut the faces across it.",
                  m.seam_angle() * kDeg, r.seam_relief, r.copy_of.size());
  else
    std::snprintf(text, sizeof text, "Seam: at %.1f degrees (given); %zu vertices copied to cut the faces across it.", m.seam_angle() * kDeg,
                  r.copy_of.size());
  lines.push_back(text);
  std::snprintf(text, sizeof text,
                "Stretch of the development: median %.2f %%, 90th percentile %.2f %% of an edge's length (0 on cylinders and cones); "
                "vertex quality = each vertex's stretch.",
                100 * r.stretch_median, 100 * r.stretch_p90);
  lines.push_back(text);
  if (r.axis_source != AxisSource::fitted && r.relief_rms > kNotTurned * m.reference_radius()) {
    std::snprintf(text, sizeof text,
                  "Warning: the surface lies %.3g (rms) from its base, %.0f %% of its radius: it does not turn about this axis, "
                  "and the rollout is no flat sheet of a relief.",
                  r.relief_rms, 100 * r.relief_rms / m.reference_radius());
    lines.push_back(text);
  }
  if (r.impression)
    lines.push_back("Seal impression: the rollout mirrored and its relief inverted, as the seal prints it rolled over clay.");
  return lines;
}

}  // namespace reliefkit
