// ReliefKit — rollouts around an axis. See reliefkit/rollout/unroll.h.
#include "reliefkit/base/angles.h"
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


bool report(Progress progress, int percent, const char* what) { return progress ? progress(percent, what) : true; }

// The angle in (-pi, pi].
double wrapped(double angle) {
  const double a = std::remainder(angle, 2 * kPi);
  return a <= -kPi ? a + 2 * kPi : a;
}

// A fitted axis' sign (the fit does not decide it): up the screen as MeshLab first shows the scan
// (+y), or along +x when the axis lies nearly square to y, or +z — so the rollout stands as the
// piece does on the screen.
Vec3 upwards(const Vec3& d) {
  const double along = std::abs(d.y()) >= 0.1 ? d.y() : std::abs(d.x()) >= 0.1 ? d.x() : d.z();
  return along < 0 ? Vec3(-d) : d;
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
  AxisLine a = out.fit->axis;
  a.direction = upwards(a.direction);
  return a;
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
// 60 degrees of the radial direction; the other way round for a mesh oriented inwards — see
// outer_side) binned by height
// (bins of 2 edges, at most 400), each bin's area-weighted median radius.
// Which faces are the outer surface: +1 those facing away from the axis, -1 those facing it (a
// mesh oriented inwards). Of two sides each with at least a quarter of the other's area (a wall
// and its inside, a seal and its bore), the farther from the axis (mean radius); else the larger.
double outer_side(double out_area, double out_radius, double in_area, double in_radius) {
  if (out_area >= 0.25 * in_area && in_area >= 0.25 * out_area) return out_radius >= in_radius ? 1 : -1;
  return out_area >= in_area ? 1 : -1;
}

std::vector<Vec2> median_radii(const TriMesh& mesh, const AxisLine& axis, double edge, double& bin, double& sign) {
  struct FaceRZ {
    Vec2 rz;
    double area, facing;
  };
  std::vector<FaceRZ> faces;
  faces.reserve(mesh.faces.size());
  double out_area = 0, in_area = 0, out_radius = 0, in_radius = 0;
  double z_min = INFINITY, z_max = -INFINITY;
  for (const auto& t : mesh.faces) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Vec3 cross = (b - a).cross(c - a);
    const Vec3 centre = (a + b + c) / 3, q = centre - axis.point;
    const Vec3 radial = q - q.dot(axis.direction) * axis.direction;
    if (!(cross.norm() > 0) || !(radial.norm() > 0)) continue;
    const double facing = radial.normalized().dot(cross.normalized());
    faces.push_back({radius_height(centre, axis), cross.norm() / 2, facing});
    if (facing > 0.5) out_area += faces.back().area, out_radius += faces.back().area * faces.back().rz.x();
    if (facing < -0.5) in_area += faces.back().area, in_radius += faces.back().area * faces.back().rz.x();
    z_min = std::min(z_min, faces.back().rz.y()), z_max = std::max(z_max, faces.back().rz.y());
  }
  sign = outer_side(out_area, out_radius / std::max(out_area, 1e-300), in_area, in_radius / std::max(in_area, 1e-300));
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
  double bin = 0, sign = 1;
  const std::vector<Vec2> raw = median_radii(mesh, axis, edge, bin, sign);
  const double length = raw.back().y() - raw.front().y();
  const double window = params.base_window_edges > 0 ? params.base_window_edges * edge : std::max(20 * edge, length / 2);
  BaseProfile base;
  base.rz = params.base == BaseShape::straight ? straight_profile(raw) : smooth_profile(raw, window);
  base.measure();
  base.facing = sign;
  return base;
}

}  // namespace

void UnrollParams::validate() const {
  if (axis_source == AxisSource::given &&
      !(given_axis.direction.allFinite() && given_axis.point.allFinite() && given_axis.direction.norm() > 1e-12))
    throw InputError("Axis direction (given) must be a finite, non-zero vector and Axis point (given) finite");
  if (seam_deg && !std::isfinite(*seam_deg)) throw InputError("Seam angle must be a number of degrees");
  if (!(base_window_edges >= 0 && base_window_edges <= 1e6)) throw InputError("Base window must be 0 (automatic) or a positive number of edge lengths");
  if (!(repeat_share >= 0 && repeat_share <= 1)) throw InputError("Repeat past the seam must be a share of a turn between 0 and 1");
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

namespace {
// The isothermal coordinate gained along a straight piece of the profile from radius a to b over
// `length`: the integral of ds / r with r linear in s.
double isothermal_step(double a, double b, double length) {
  return std::abs(b - a) > 1e-9 * std::max(a, b) ? length * std::log(b / a) / (b - a) : length / a;
}
}  // namespace

void BaseProfile::measure() {
  double largest = 0;
  for (Vec2& q : rz) largest = std::max(largest, q.x());
  for (Vec2& q : rz) q.x() = std::max(q.x(), 1e-3 * largest);
  s.assign(rz.size(), 0);
  u.assign(rz.size(), 0);
  for (size_t k = 1; k < rz.size(); ++k) {
    s[k] = s[k - 1] + (rz[k] - rz[k - 1]).norm();
    u[k] = u[k - 1] + isothermal_step(rz[k - 1].x(), rz[k].x(), s[k] - s[k - 1]);
  }
}

double BaseProfile::isothermal(double arc_length) const {
  const double t = std::clamp(arc_length, 0.0, s.back());
  const size_t k = std::min(size_t(std::upper_bound(s.begin(), s.end(), t) - s.begin()), s.size() - 1);
  if (k == 0) return 0;
  return u[k - 1] + isothermal_step(rz[k - 1].x(), at(t).x(), t - s[k - 1]);
}

namespace {
// The conformal development's cone: on a cone, log r = log r0 + k u exactly (k its slope); on any
// profile the least-squares k over the surface (weights r ds, 64 samples along the profile) keeps
// the development's scale, r0 exp(k (u - u0)) / r, nearest to constant — a symmetric belly gets a
// cylinder (straight parallels), a shoulder the cone that fits it.
double conformal_cone_slope(const BaseProfile& base) {
  constexpr int kSamples = 64;
  double sw = 0, su = 0, sl = 0, suu = 0, sul = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double s = base.s.back() * (k + 0.5) / kSamples, r = base.at(s).x(), u = base.isothermal(s), l = std::log(r);
    sw += r, su += r * u, sl += r * l, suu += r * u * u, sul += r * u * l;
  }
  const double var = suu / sw - (su / sw) * (su / sw), cov = sul / sw - (su / sw) * (sl / sw);
  return var > 0 ? cov / var : 0;
}
}  // namespace

RolloutMap::RolloutMap(const AxisLine& axis, const Vec3& reference, BaseProfile base, double seam_angle, bool impression,
                       Development development)
    : axis_(axis), u_(reference), v_(axis.direction.cross(reference)), base_(std::move(base)), seam_(seam_angle),
      impression_(impression), development_(development) {
  s0_ = base_.s.back() / 2;
  r0_ = base_.at(s0_).x();
  u0_ = base_.isothermal(s0_);
  // The cone the development is exact on: d radius / d arc length, the sine of its half-angle.
  const double slope = development_ == Development::conformal ? conformal_cone_slope(base_) : base_.slope_at(s0_);
  apex_ = std::abs(slope) > 1e-6 ? r0_ / slope : 0;
}

RolloutMap::Local RolloutMap::local(const Vec3& p) const {
  Local l;
  const Vec3 q = p - axis_.point;
  l.azimuth = std::atan2(q.dot(v_), q.dot(u_));
  const Vec2 rz = radius_height(p, axis_);
  l.foot = base_.foot(rz);
  l.height = (rz - l.foot.point).dot(l.foot.normal);
  return l;
}

double RolloutMap::angle_from_azimuth(double azimuth) const { return wrapped(azimuth - seam_ - kPi); }

double RolloutMap::angle_of(const Vec3& p) const {
  const Vec3 q = p - axis_.point;
  return angle_from_azimuth(std::atan2(q.dot(v_), q.dot(u_)));
}

// The developed base, `angle` from the middle meridian. Both developments put the parallels on
// concentric arcs about the tangent cone's apex at the reference parallel (straight lines when it
// is a cylinder), which makes them exact on cylinders and cones.
// Conformal: the isothermal coordinates (u = the integral of ds / r, angle) mapped by the
// exponential that develops that cone — radius apex * exp(k u), polar angle k * angle with
// k = r0 / apex (a cylinder: x = r0 angle, y = r0 u).
// Equal-area (generalized Bonne): the parallel at its true length on an arc at its arc length.
Vec2 RolloutMap::develop(double angle, double arc_length) const {
  if (development_ == Development::conformal) {
    const double u = base_.isothermal(arc_length) - u0_;
    if (apex_ == 0) return Vec2(r0_ * angle, r0_ * u);
    const double k = r0_ / apex_, rho = apex_ * std::exp(k * u), beta = k * angle;
    return Vec2(rho * std::sin(beta), rho * std::cos(beta) - apex_);
  }
  const double r = base_.at(arc_length).x();
  if (apex_ == 0) return Vec2(angle * r, arc_length - s0_);
  const double rho = apex_ + (arc_length - s0_);
  if (std::abs(rho) < 1e-12 * std::max(r0_, 1e-300)) return Vec2(0, -apex_);
  const double beta = angle * r / rho;
  return Vec2(rho * std::sin(beta), rho * std::cos(beta) - apex_);
}

Vec3 RolloutMap::on_sheet(double angle, double arc_length, double height) const {
  const Vec2 xy = develop(angle, arc_length);
  return impression_ ? Vec3(-xy.x(), xy.y(), -height) : Vec3(xy.x(), xy.y(), height);
}

RolloutMap::Point RolloutMap::place(const Local& l, int turns) const {
  Point out;
  out.angle = angle_from_azimuth(l.azimuth) + 2 * kPi * turns;
  out.position = on_sheet(out.angle, l.foot.s, l.height);
  const Vec2 foot = l.foot.point;
  out.base_point = axis_.point + foot.y() * axis_.direction + foot.x() * (std::cos(l.azimuth) * u_ + std::sin(l.azimuth) * v_);
  return out;
}

std::vector<Vec3> RolloutMap::meridian(double angle) const {
  constexpr int kLeast = 64;  // samples along a straight base; a smooth one's every point besides
  std::vector<double> along(base_.s);
  for (int k = 0; k <= kLeast; ++k) along.push_back(base_.s.back() * k / kLeast);
  std::sort(along.begin(), along.end());
  along.erase(std::unique(along.begin(), along.end()), along.end());
  std::vector<Vec3> line;
  for (double s : along) line.push_back(on_sheet(angle, s, 0));
  return line;
}

namespace {

// The seam's angle from the reference direction: the middle of the widest sector without faces
// when there is one of at least 3 degrees (a sherd, an open piece); else the degree whose faces
// rise least off the base (the rms height of its vertices, over three degrees).
double automatic_seam(const std::vector<RolloutMap::Local>& local, Rollout& out) {
  constexpr int kBins = 360;
  std::vector<int> count(kBins, 0);
  std::vector<double> squares(kBins, 0);
  for (size_t i = 0; i < local.size(); ++i) {
    const int b = std::clamp(int((local[i].azimuth + kPi) / (2 * kPi) * kBins), 0, kBins - 1);
    ++count[size_t(b)], squares[size_t(b)] += local[i].height * local[i].height;
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

// Copies of input vertices one turn on (past the seam), each made once: for the faces across the
// seam and for the faces repeated past it. Their sheet positions are set with the others'.
class TurnCopies {
 public:
  explicit TurnCopies(Rollout& out) : out_(out) {}
  int of(int v) {
    auto [it, added] = copy_.emplace(v, int(out_.source.size()));
    if (added) out_.source.push_back(out_.source[size_t(v)]);
    return it->second;
  }

 private:
  Rollout& out_;
  std::map<int, int> copy_;
};

// Faces across the seam: their vertices on the far side (angle below zero, the face reaching over
// +pi) copied past the seam, so that the face lies whole on the sheet's +pi edge. Then the faces
// within `share` of a turn after the seam (the sheet's -pi edge) repeated past it, on copies.
void cut_seam_and_repeat(const std::vector<double>& angle, double share, Rollout& out) {
  TurnCopies copies(out);
  const size_t faces = out.mesh.faces.size();
  std::vector<char> across(faces, 0);
  for (size_t f = 0; f < faces; ++f) {
    auto& t = out.mesh.faces[f];
    double low = INFINITY, high = -INFINITY;
    for (int v : t) low = std::min(low, angle[size_t(v)]), high = std::max(high, angle[size_t(v)]);
    if (high - low <= kPi) continue;
    across[f] = 1;
    for (int& v : t)
      if (angle[size_t(v)] < 0) v = copies.of(v);
  }
  out.seam_copies = long(out.source.size()) - out.wall_vertices;
  const double until = -kPi + 2 * kPi * share;
  for (size_t f = 0; f < faces && share > 0; ++f) {
    const auto t = out.mesh.faces[f];
    if (across[f] || std::min({angle[size_t(t[0])], angle[size_t(t[1])], angle[size_t(t[2])]}) > until) continue;
    out.mesh.faces.push_back({copies.of(t[0]), copies.of(t[1]), copies.of(t[2])});
    ++out.repeated_faces;
  }
  out.mesh.vertices.resize(out.source.size(), Vec3::Zero());
}

// Each face edge's change of length from the base surface to the developed sheet (0.01: 1 %);
// per vertex the mean over the edges of its faces.
// The percentiles over the faces before the repeated ones (each face counted once).
void measure_stretch(const std::vector<Vec3>& base_point, const std::vector<Vec3>& sheet, Rollout& out) {
  std::vector<double> edge_stretch;
  const size_t counted = out.mesh.faces.size() - size_t(out.repeated_faces);
  edge_stretch.reserve(3 * counted);
  std::vector<double> sum(out.mesh.vertices.size(), 0);
  std::vector<int> n(out.mesh.vertices.size(), 0);
  for (size_t f = 0; f < out.mesh.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto& t = out.mesh.faces[f];
      const int a = t[size_t(k)], b = t[size_t((k + 1) % 3)];
      const double on_base = (base_point[size_t(a)] - base_point[size_t(b)]).norm();
      if (!(on_base > 0)) continue;
      const double change = std::abs((sheet[size_t(a)] - sheet[size_t(b)]).head<2>().norm() / on_base - 1);
      if (f < counted) edge_stretch.push_back(change);
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

// The faces of the outer wall, where the decoration is: not those facing the axis (a seal's bore,
// a pot's inside: the face's normal more than 120 degrees from the base's), nor those lying
// deeper than a quarter of the radius under the base (the ends of a closed seal), nor those beyond
// an end of the profile turned more than 60 degrees from it (an end's ring next to the rim).
std::vector<char> outer_wall(const TriMesh& mesh, const std::vector<RolloutMap::Local>& local, const RolloutMap& map) {
  const BaseProfile& base = map.base();
  const Vec3 d = map.axis().direction;
  const double deep = 0.25 * map.reference_radius(), end = base.s.back();
  std::vector<char> keep(mesh.faces.size(), 1);
#pragma omp parallel for schedule(static)
  for (long f = 0; f < long(mesh.faces.size()); ++f) {
    const auto& t = mesh.faces[size_t(f)];
    const Vec3 &a = mesh.vertices[size_t(t[0])], &b = mesh.vertices[size_t(t[1])], &c = mesh.vertices[size_t(t[2])];
    const Vec3 n = (b - a).cross(c - a), q = (a + b + c) / 3 - map.axis().point, radial = q - q.dot(d) * d;
    if (!(n.norm() > 0) || !(radial.norm() > 0)) continue;
    Vec2 foot_normal = Vec2::Zero();
    double height = 0;
    bool at_end = true;
    for (int v : t) {
      const RolloutMap::Local& l = local[size_t(v)];
      foot_normal += l.foot.normal, height += l.height / 3;
      at_end = at_end && (l.foot.s <= 0 || l.foot.s >= end);
    }
    const Vec3 outward = (foot_normal.x() * radial.normalized() + foot_normal.y() * d).normalized();
    const double facing = base.facing * n.normalized().dot(outward);
    keep[size_t(f)] = facing >= -0.5 && height >= -deep && !(at_end && facing < 0.5);
  }
  return keep;
}

// The input's vertices of the kept faces, in their order, as the rollout's first vertices; the
// kept faces on them. The share of the surface's area left out is logged.
void take_outer_wall(const TriMesh& mesh, const std::vector<char>& keep, Rollout& out) {
  std::vector<int> index(mesh.vertices.size(), -1);
  double kept = 0, total = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    const double area = (mesh.vertices[size_t(t[1])] - mesh.vertices[size_t(t[0])]).cross(mesh.vertices[size_t(t[2])] - mesh.vertices[size_t(t[0])]).norm();
    total += area;
    if (!keep[f]) continue;
    kept += area;
    for (int v : t) index[size_t(v)] = 0;
  }
  for (size_t v = 0; v < mesh.vertices.size(); ++v)
    if (index[v] == 0) index[v] = int(out.source.size()), out.source.push_back(int(v));
  out.wall_vertices = long(out.source.size());
  out.mesh.vertices.assign(out.source.size(), Vec3::Zero());
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    if (keep[f]) {
      const auto& t = mesh.faces[f];
      out.mesh.faces.push_back({index[size_t(t[0])], index[size_t(t[1])], index[size_t(t[2])]});
    }
  out.left_out_faces = long(mesh.faces.size() - out.mesh.faces.size());
  out.left_out_area_share = total > 0 ? 1 - kept / total : 0;
}

// Beyond this rms distance from the base (a share of its radius) a fitted axis is refused: the
// shared scans' coin and ingot, which the vessel fit lets through, lie 40 % and 42 % off at
// defaults; the tests' seal with figures 1 mm high on a 15 mm radius, well under 10 %.
constexpr double kNotTurned = 0.1;

void refuse_if_not_turned(Rollout& out, const std::vector<RolloutMap::Local>& local, AxisSource source) {
  double sum = 0;
  for (long i = 0; i < out.wall_vertices; ++i) sum += local[size_t(out.source[size_t(i)])].height * local[size_t(out.source[size_t(i)])].height;
  out.relief_rms = out.wall_vertices > 0 ? std::sqrt(sum / double(out.wall_vertices)) : 0;
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
  // What does not depend on the seam, once per vertex: angle from the reference, foot, height.
  std::vector<RolloutMap::Local> local(mesh.vertices.size());
  {
    const RolloutMap probe(axis, reference, base, 0, false, params.development);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < long(mesh.vertices.size()); ++i) local[size_t(i)] = probe.local(mesh.vertices[size_t(i)]);
  }
  report(params.progress, 50, "The outer wall");
  {
    const RolloutMap probe(axis, reference, base, 0, false, params.development);
    take_outer_wall(mesh, outer_wall(mesh, local, probe), out);
    out.map.emplace(probe);
  }
  refuse_if_not_turned(out, local, params.axis_source);
  std::vector<RolloutMap::Local> wall_local(size_t(out.wall_vertices));
  for (size_t i = 0; i < wall_local.size(); ++i) wall_local[i] = local[size_t(out.source[i])];
  const double seam = params.seam_deg ? wrapped(*params.seam_deg / kDegreesPerRadian) : automatic_seam(wall_local, out);
  report(params.progress, 60, "Unrolling");
  out.map.emplace(axis, reference, std::move(base), seam, params.impression, params.development);
  const RolloutMap& map = *out.map;
  std::vector<double> angle(wall_local.size());
  for (size_t i = 0; i < wall_local.size(); ++i) angle[i] = map.angle_from_azimuth(wall_local[i].azimuth);
  cut_seam_and_repeat(angle, params.repeat_share, out);
  std::vector<Vec3> sheet(out.mesh.vertices.size()), base_point(out.mesh.vertices.size());
  out.height.assign(out.mesh.vertices.size(), 0);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(out.mesh.vertices.size()); ++i) {
    const RolloutMap::Point p = map.place(local[size_t(out.source[size_t(i)])], i >= out.wall_vertices ? 1 : 0);
    sheet[size_t(i)] = p.position, base_point[size_t(i)] = p.base_point, out.height[size_t(i)] = p.position.z();
  }
  report(params.progress, 85, "Measuring the stretch");
  measure_stretch(base_point, sheet, out);
  out.mesh.vertices = std::move(sheet);
  if (params.impression)  // mirrored: each face turned back to face +Z, as the surface faced outwards
    for (auto& t : out.mesh.faces) std::swap(t[1], t[2]);
  out.width = 2 * kPi * map.reference_radius();
  out.marks = SheetMarks{{map.meridian(-kPi), map.meridian(kPi)}, params.impression, out.width, map.reference_radius(),
                         params.repeat_share};
  report(params.progress, 100, "Done");
  return out;
}

namespace {

// The segments within `share` of a turn after the seam, repeated one turn on (as the faces are).
void repeat_curves(const Polylines& curves, const RolloutMap& map, const std::vector<RolloutMap::Point>& mapped, double share,
                   Polylines& out) {
  const double until = -kPi + 2 * kPi * share;
  std::map<int, int> copy;
  auto copy_of = [&](int k) {
    auto [it, added] = copy.emplace(k, int(out.points.size()));
    if (added) {
      const double strength = out.strength[size_t(k)];
      out.points.push_back(map.map(curves.points[size_t(k)], 1).position);
      out.strength.push_back(strength);
    }
    return it->second;
  };
  const size_t segments = out.segments.size();
  for (size_t k = 0; k < segments && share > 0; ++k) {
    const auto seg = out.segments[k];
    if (size_t(std::max(seg[0], seg[1])) >= mapped.size()) continue;  // a piece cut at the seam
    const double a = mapped[size_t(seg[0])].angle, b = mapped[size_t(seg[1])].angle;
    if (std::min(a, b) <= until && std::abs(a - b) <= kPi) out.segments.push_back({copy_of(seg[0]), copy_of(seg[1])});
  }
}

}  // namespace

Polylines unroll_curves(const Polylines& curves, const RolloutMap& map, double repeat_share) {
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
  repeat_curves(curves, map, mapped, repeat_share, out);
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
                  m.seam_angle() * kDegreesPerRadian);
  else if (r.seam_automatic)
    std::snprintf(text, sizeof text, "Seam: at %.1f degrees, where the surface rises least off the base (rms %.3g; chosen); %ld vertices copied to cut the faces across it.",
                  m.seam_angle() * kDegreesPerRadian, r.seam_relief, r.seam_copies);
  else
    std::snprintf(text, sizeof text, "Seam: at %.1f degrees (given); %ld vertices copied to cut the faces across it.", m.seam_angle() * kDegreesPerRadian,
                  r.seam_copies);
  lines.push_back(text);
  const bool conformal = m.development() == Development::conformal;
  std::snprintf(text, sizeof text,
                "Development: %s; stretch median %.2f %%, 90th percentile %.2f %% of an edge's length (0 on cylinders and cones); "
                "vertex quality = each vertex's stretch.",
                conformal ? "conformal (shapes kept; on a rounded profile each height drawn at a scale that follows its radius)"
                          : "equal-area (parallels at their true length; on a rounded profile the meridians shear away from the middle)",
                100 * r.stretch_median, 100 * r.stretch_p90);
  lines.push_back(text);
  if (r.axis_source != AxisSource::fitted && r.relief_rms > kNotTurned * m.reference_radius()) {
    std::snprintf(text, sizeof text,
                  "Warning: the surface lies %.3g (rms) from its base, %.0f %% of its radius: it does not turn about this axis, "
                  "and the rollout is no flat sheet of a relief.",
                  r.relief_rms, 100 * r.relief_rms / m.reference_radius());
    lines.push_back(text);
  }
  if (r.left_out_faces > 0) {
    std::snprintf(text, sizeof text,
                  "Left out: %ld faces (%.1f %% of the area) that are not the outer wall — facing the axis (a bore, an "
                  "inside), deeper than a quarter of the radius, or turned from the wall beyond its ends (a closed piece's ends).",
                  r.left_out_faces, 100 * r.left_out_area_share);
    lines.push_back(text);
  }
  if (r.impression)
    lines.push_back("Seal impression: the rollout mirrored and its relief inverted, as the seal prints it rolled over clay.");
  if (r.repeated_faces > 0) {
    std::snprintf(text, sizeof text, "Repeat: %.0f %% of a turn after the seam drawn again past it (%ld faces), as seal impressions overlap.",
                  100 * r.marks.repeat_share, r.repeated_faces);
    lines.push_back(text);
  }
  return lines;
}

std::vector<std::string> sheet_labels(const SheetMarks& marks, double unit_mm) {
  char text[300];
  std::vector<std::string> lines{marks.impression ? "Seal impression (rollout mirrored, relief inverted)" : "Rollout"};
  std::snprintf(text, sizeof text, "circumference %.1f mm (radius %.1f mm); seam dash-dot", marks.circumference * unit_mm,
                marks.reference_radius * unit_mm);
  lines.push_back(text);
  if (marks.repeat_share > 0) {
    std::snprintf(text, sizeof text, "%.0f %% of a turn repeated past the seam", 100 * marks.repeat_share);
    lines.push_back(text);
  }
  return lines;
}

}  // namespace reliefkit
