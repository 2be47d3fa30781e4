// ReliefKit — the pottery record of a scanned vessel or sherd. See reliefkit/pottery/vessel_record.h.
#include "reliefkit/base/angles.h"
#include "reliefkit/pottery/vessel_record.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <unordered_map>

#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {
namespace {


std::string format(const char* pattern, double a, double b = 0, double c = 0, double d = 0) {
  char text[400];
  std::snprintf(text, sizeof text, pattern, a, b, c, d);
  return text;
}

double percentile(std::vector<double> values, double share) {
  if (values.empty()) return 0;
  const size_t k = std::min(values.size() - 1, size_t(share * double(values.size())));
  std::nth_element(values.begin(), values.begin() + long(k), values.end());
  return values[k];
}

// How rough the piece's ends are against its wall: per face the angle between the normal of the
// surface smoothed over one edge length (scanner noise gone, a break's jags kept) and over the
// fit's smoothing (jags gone too); the median over each end's faces (near
// the highest or lowest point of their meridian, facing up or down) and over the wall's (facing
// more across the axis than along it). A rim or a base made on the wheel is about as smooth as the wall; a
// break is rougher. Infinite for an end with fewer than 8 such faces.
struct EndRoughness {
  double top = INFINITY, bottom = INFINITY;  // median angles (degrees)
  double wall = 0;
  std::vector<signed char> end;  // per face: +1 the top end, -1 the bottom end, 0 neither
  bool smooth(double end) const { return end <= kSmoothEndDeg; }
  // An end whose faces turn at most this much is a rim or a base: measured (bench_pottery, the
  // pottery drawings' vessels) rims 1-2 degrees rounded, up to 9 with square corners; jagged
  // breaks 15-25. The wall's own figure is logged beside it (a strongly curved wall reaches 10).
  static constexpr double kSmoothEndDeg = 10;
};

EndRoughness end_roughness(const TriMesh& mesh, const std::vector<Vec3>& p, const std::vector<Vec3>& fine_normal,
                           const std::vector<Vec3>& smoothed_normal, const std::vector<char>& wall, double edge) {
  // Per meridian (bins one edge long at the piece's median radius) its highest and lowest point:
  // an end's faces lie within 1.5 edge lengths of them, facing that way.
  std::vector<double> radii;
  for (size_t k = 0; k < p.size(); k += std::max<size_t>(1, p.size() / 2000)) radii.push_back(p[k].head<2>().norm());
  const double radius = std::max(percentile(radii, 0.5), 4 * edge);
  auto bin_of = [&](const Vec3& q) { return std::lround(std::atan2(q.y(), q.x()) * radius / edge); };
  std::unordered_map<long, std::pair<double, double>> extent;  // meridian -> (lowest, highest)
  for (const Vec3& q : p) {
    auto [it, added] = extent.try_emplace(bin_of(q), q.z(), q.z());
    it->second.first = std::min(it->second.first, q.z()), it->second.second = std::max(it->second.second, q.z());
  }
  std::vector<double> top, bottom, side;
  std::vector<signed char> end(mesh.faces.size(), 0);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    const Vec3 &fine = fine_normal[f], &n = smoothed_normal[f];
    if (fine.isZero() || n.isZero()) continue;
    const double angle = std::acos(std::clamp(fine.dot(n), -1.0, 1.0));
    const Vec3 c = (p[t[0]] + p[t[1]] + p[t[2]]) / 3;
    const Vec2 radial = c.head<2>().norm() > 0 ? Vec2(c.head<2>().normalized()) : Vec2(1, 0);
    const double across = std::abs(n.head<2>().dot(radial));
    if (across > std::abs(n.z()) && wall[f]) side.push_back(angle);
    const auto it = extent.find(bin_of(c));
    if (it == extent.end()) continue;
    // facing within 37 degrees of up (down): a rim's or base's faces, not a sloping wall's
    if (n.z() > 0.8 && c.z() > it->second.second - 1.5 * edge) top.push_back(angle), end[f] = 1;
    if (n.z() < -0.8 && c.z() < it->second.first + 1.5 * edge) bottom.push_back(angle), end[f] = -1;
  }
  EndRoughness r;
  r.end = std::move(end);
  r.wall = percentile(side, 0.5) * kDegreesPerRadian;
  if (top.size() >= 8) r.top = percentile(top, 0.5) * kDegreesPerRadian;
  if (bottom.size() >= 8) r.bottom = percentile(bottom, 0.5) * kDegreesPerRadian;
  return r;
}

// The rotation taking `d` to +Z and the piece's middle meridian to +x (before the flip).
Mat3 rotation_onto_axis(const Vec3& d) { return Eigen::Quaterniond::FromTwoVectors(d, Vec3::UnitZ()).toRotationMatrix(); }

std::vector<Vec3> moved(const std::vector<Vec3>& points, const Mat3& rotation, const Vec3& translation) {
  std::vector<Vec3> out(points.size());
  for (size_t i = 0; i < points.size(); ++i) out[i] = rotation * points[i] + translation;
  return out;
}

// Decides which end is up (see the header) on the piece turned onto +Z; true: turn it over.
bool decide_up(const TriMesh& mesh, const std::vector<Vec3>& p, const EndRoughness& ends, const Vec3& input_y,
               VesselRecord& record) {
  double r_max = 0, z_min = INFINITY, z_max = -INFINITY;
  for (const Vec3& q : p) r_max = std::max(r_max, q.head<2>().norm()), z_min = std::min(z_min, q.z()), z_max = std::max(z_max, q.z());
  // The base: a floor across the axis (faces within 15 % of the largest radius of it, facing along
  // it; a bottle's narrow mouth has its walls there, facing across).
  double floor_z = 0, floor_area = 0;
  for (const auto& t : mesh.faces) {
    const Vec3 c = (p[t[0]] + p[t[1]] + p[t[2]]) / 3, n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    const double area = n.norm();
    if (c.head<2>().norm() < 0.15 * r_max && area > 0 && std::abs(n.z()) > 0.9 * area) floor_z += area * c.z(), floor_area += area;
  }
  const double middle = (z_min + z_max) / 2;
  if (floor_area > 0 && std::abs(floor_z / floor_area - middle) > 0.1 * (z_max - z_min)) {
    record.up_rule = UpRule::base;
    record.up_reason = format("the base: a floor across the axis, %.3g of area within 15 %% of the largest radius", floor_area / 2);
    return floor_z / floor_area > middle;
  }
  const double top = ends.top, bottom = ends.bottom;
  if (ends.smooth(top) != ends.smooth(bottom)) {
    record.up_rule = UpRule::rim;
    record.up_reason = format("the rim: one end is about as smooth as the wall (its faces turn %.1f degrees from the surface "
                              "smoothed over an edge length, the wall's %.1f), the other a break (%.1f)",
                              std::min(top, bottom), ends.wall, std::max(top, bottom));
    return bottom < top;
  }
  // Nothing on the piece decides: its up on screen (MeshLab shows +y up), when the axis runs
  // within 30 degrees of it (a vessel made from a drawing, a scan saved upright).
  if (std::abs(input_y.z()) > std::cos(30 / kDegreesPerRadian)) {
    record.up_rule = UpRule::input_up;
    record.up_reason = format("the scan's own up (its y axis, %.0f degrees from the axis; no base, and the ends' faces turn %.1f "
                              "and %.1f degrees from the smoothed surface: both rims or both breaks): check it, and flip if the "
                              "rim is down",
                              std::acos(std::min(1.0, std::abs(input_y.z()))) * kDegreesPerRadian, ends.top, ends.bottom);
    return input_y.z() < 0;
  }
  double r_top = 0, r_bottom = 0;
  int n_top = 0, n_bottom = 0;
  const double band = 0.1 * (z_max - z_min);
  for (const Vec3& q : p) {
    if (q.z() > z_max - band) r_top += q.head<2>().norm(), ++n_top;
    if (q.z() < z_min + band) r_bottom += q.head<2>().norm(), ++n_bottom;
  }
  r_top /= std::max(1, n_top), r_bottom /= std::max(1, n_bottom);
  record.up_rule = UpRule::wider_end;
  record.up_reason = format("the wider end (no base; the ends' faces turn %.1f and %.1f degrees from the surface smoothed "
                            "over an edge length, the wall's %.1f: both rims or both breaks; ",
                            ends.top, ends.bottom, ends.wall);
  record.up_reason += format("radius %.4g at one end, %.4g at the other): check it, and flip if the rim is down",
                             std::max(r_top, r_bottom), std::min(r_top, r_bottom));
  return r_bottom > r_top;
}

// The angle of the piece's middle meridian (its area-weighted mean direction round the axis).
double middle_meridian(const TriMesh& mesh, const std::vector<Vec3>& p) {
  Vec2 sum = Vec2::Zero();
  for (const auto& t : mesh.faces) {
    const Vec3 c = (p[t[0]] + p[t[1]] + p[t[2]]) / 3;
    const double area = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
    if (c.head<2>().norm() > 0 && std::isfinite(area)) sum += area * c.head<2>().normalized();
  }
  return sum.norm() > 0 ? std::atan2(sum.y(), sum.x()) : 0;
}


// What surface a piece of the section cuts (see the header), from the face's normal in the
// oriented frame at the section (the plane y = 0, x > 0: radial = +x).
struct Ends {
  bool rim = false, base = false;  // the top is a rim, the bottom a base (else breaks)
};
// A face of the section: a break (its normal misses the axis), the top end (a rim if smooth, else
// a break), the bottom end (a base if smooth or on the axis, else a break), or the wall (told
// outer or inner later, by runs).
constexpr int kWallLabel = 5;
int label_of(bool wall, signed char end, const Ends& ends) {
  if (!wall) return int(ProfilePart::break_surface);
  if (end > 0) return int(ends.rim ? ProfilePart::rim : ProfilePart::break_surface);
  if (end < 0) return int(ends.base ? ProfilePart::base : ProfilePart::break_surface);
  return kWallLabel;
}

// A wall run is the inner wall when its normals face up and in on the whole (n_z - n_x > 0 in the
// plane y = 0: the floor, the inside of the body), the outer wall otherwise.
ProfilePart wall_side(const std::vector<Vec3>& normals) {
  double score = 0;
  for (const Vec3& n : normals) score += n.z() - n.x();
  return score > 0 ? ProfilePart::inner_wall : ProfilePart::outer_wall;
}

struct Section {
  std::vector<ProfileCurve> curves;        // at x >= 0, in (radius, height)
  std::vector<std::vector<Vec2>> loops;    // the closed chains of the whole plane, (x, z): the wall's section filled
};
// A chain of the cut, segment by segment: its points in (x, z), each segment's label (label_of;
// -1 on the other half of the plane) and its face's normal; labels made the majority of the five
// around each.
struct LabelledChain {
  std::vector<Vec2> rz;
  std::vector<int> label;
  std::vector<Vec3> normal;
};
LabelledChain label_chain(const Polylines& cut, const std::vector<int>& chain, const std::vector<int>& segment_face,
                          const std::vector<Vec3>& face_normal, const std::vector<char>& wall_face,
                          const std::vector<signed char>& end_face, const Ends& ends) {
  LabelledChain c;
  for (size_t k = 0; k + 1 < chain.size(); ++k) {
    const Vec3 a = cut.points[size_t(chain[k])], b = cut.points[size_t(chain[k + 1])];
    c.rz.emplace_back(a.x(), a.z());
    const int face = segment_face[k];
    const bool other_half = a.x() < 0 || b.x() < 0;
    c.label.push_back(other_half ? -1 : label_of(wall_face[size_t(face)], end_face[size_t(face)], ends));
    c.normal.push_back(other_half ? Vec3::Zero() : face_normal[size_t(face)]);
  }
  if (!chain.empty()) c.rz.emplace_back(cut.points[size_t(chain.back())].x(), cut.points[size_t(chain.back())].z());
  std::vector<int> smooth = c.label;
  for (size_t k = 0; k < c.label.size(); ++k) {
    if (c.label[k] < 0) continue;
    int count[6] = {0, 0, 0, 0, 0, 0};
    for (size_t j = k >= 2 ? k - 2 : 0; j < std::min(c.label.size(), k + 3); ++j)
      if (c.label[j] >= 0) ++count[c.label[j]];
    smooth[k] = int(std::max_element(count, count + 6) - count);
  }
  c.label = std::move(smooth);
  return c;
}

// The chain's runs of one label as profile curves. A wall run over a lip too thin to face up
// (outer wall, lip, inner wall in one) is cut at its highest point, each side told apart on its
// own; slivers where the plane grazes a vertex (under a tenth of an edge) are left out.
void append_runs(const LabelledChain& c, double edge, std::vector<ProfileCurve>& curves) {
  for (size_t k = 0; k < c.label.size();) {
    size_t end = k;
    while (end < c.label.size() && c.label[end] == c.label[k]) ++end;
    if (c.label[k] >= 0) {
      std::vector<std::pair<size_t, size_t>> pieces{{k, end}};
      if (c.label[k] == kWallLabel) {
        size_t top = k;
        for (size_t j = k; j <= end; ++j)
          if (c.rz[j].y() > c.rz[top].y()) top = j;
        if (top >= k + 3 && top + 3 <= end) pieces = {{k, top}, {top, end}};
      }
      for (const auto& [from, to] : pieces) {
        ProfileCurve curve;
        curve.part = c.label[k] == kWallLabel ? wall_side({c.normal.begin() + long(from), c.normal.begin() + long(to)})
                                              : ProfilePart(c.label[k]);
        curve.points.assign(c.rz.begin() + long(from), c.rz.begin() + long(to) + 1);
        double length = 0;
        for (size_t j = 1; j < curve.points.size(); ++j) length += (curve.points[j] - curve.points[j - 1]).norm();
        if (length > 0.1 * edge) curves.push_back(std::move(curve));
      }
    }
    k = end;
  }
}

// The section at +x of the oriented piece, its runs labelled by part. Only the section's own
// chains count: the longest, and any other at least a fifth as long (a handle's section); the
// scraps where the plane grazes a jagged break are left out.
Section section_profile(const TriMesh& oriented, const std::vector<Vec3>& face_normal, const std::vector<char>& wall_face,
                        const std::vector<signed char>& end_face, const Ends& ends, double edge) {
  Section section;
  const Polylines cut = plane_cut(oriented, Vec3::UnitY(), 0);
  std::unordered_map<long long, int> segment_of;  // (smaller point, larger point) -> segment
  auto key = [](int a, int b) { return (long long)std::min(a, b) << 32 | (long long)std::max(a, b); };
  for (size_t k = 0; k < cut.segments.size(); ++k) segment_of[key(cut.segments[k][0], cut.segments[k][1])] = int(k);
  const std::vector<std::vector<int>> chains = cut.chains();
  std::vector<double> length(chains.size(), 0);
  for (size_t c = 0; c < chains.size(); ++c)
    for (size_t k = 1; k < chains[c].size(); ++k) length[c] += (cut.points[size_t(chains[c][k])] - cut.points[size_t(chains[c][k - 1])]).norm();
  const double longest = chains.empty() ? 0 : *std::max_element(length.begin(), length.end());
  for (size_t c = 0; c < chains.size(); ++c) {
    if (length[c] < 0.2 * longest) continue;
    const std::vector<int>& chain = chains[c];
    if (chain.size() > 3 && chain.front() == chain.back()) {
      section.loops.emplace_back();
      for (int i : chain) section.loops.back().emplace_back(cut.points[size_t(i)].x(), cut.points[size_t(i)].z());
    }
    std::vector<int> segment_face;
    for (size_t k = 0; k + 1 < chain.size(); ++k) segment_face.push_back(cut.segment_face[size_t(segment_of.at(key(chain[k], chain[k + 1])))]);
    append_runs(label_chain(cut, chain, segment_face, face_normal, wall_face, end_face, ends), edge, section.curves);
  }
  return section;
}

// The (x, z) plane rasterized for distances: pixels a quarter of an edge (coarser if the piece
// would need more than 4096 along a side).
struct Raster {
  double x0 = 0, z0 = 0, pixel = 1;
  int width = 0, height = 0;
  cv::Point at(const Vec2& q) const { return cv::Point(int(std::lround((q.x() - x0) / pixel)), int(std::lround((q.y() - z0) / pixel))); }
};

// Whether a point lies inside closed loops (even-odd: a ray along +x crosses them an odd number
// of times), with the loops' segments binned by height (about one bin per segment): a point
// meets only the segments of its own bin, not every segment of the section (which cost 0.3 s
// on a 1 M-face sherd).
class LoopCrossings {
 public:
  explicit LoopCrossings(const std::vector<std::vector<Vec2>>& loops) {
    double low = INFINITY, high = -INFINITY;
    size_t count = 0;
    for (const auto& loop : loops)
      for (const Vec2& q : loop) low = std::min(low, q.y()), high = std::max(high, q.y()), ++count;
    if (!(high > low)) return;
    z0_ = low, bins_ = int(std::clamp<size_t>(count, 1, 100000)), dz_ = (high - low) / bins_;
    segments_.resize(size_t(bins_));
    for (const auto& loop : loops)
      for (size_t k = 0; k + 1 < loop.size(); ++k)
        for (int b = bin(std::min(loop[k].y(), loop[k + 1].y())); b <= bin(std::max(loop[k].y(), loop[k + 1].y())); ++b)
          segments_[size_t(b)].push_back({loop[k], loop[k + 1]});
  }
  bool inside(const Vec2& q) const {
    if (segments_.empty() || q.y() < z0_ || q.y() > z0_ + bins_ * dz_) return false;
    bool in = false;
    for (const auto& [a, b] : segments_[size_t(bin(q.y()))])
      if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y())) in = !in;
    return in;
  }

 private:
  int bin(double y) const { return std::clamp(int((y - z0_) / dz_), 0, bins_ - 1); }
  double z0_ = 0, dz_ = 1;
  int bins_ = 0;
  std::vector<std::vector<std::pair<Vec2, Vec2>>> segments_;
};

// Per vertex, its (radius, height)'s distance from the profile (the surface of revolution it
// sweeps), negative inside the wall's section.
std::vector<double> distances_from_profile(const std::vector<Vec3>& p, const Section& section, double edge) {
  double x_min = 0, x_max = 0, z_min = INFINITY, z_max = -INFINITY;
  for (const Vec3& q : p) x_max = std::max(x_max, q.head<2>().norm()), z_min = std::min(z_min, q.z()), z_max = std::max(z_max, q.z());
  for (const auto& loop : section.loops)
    for (const Vec2& q : loop) x_min = std::min(x_min, q.x());
  Raster r;
  r.pixel = std::max(edge / 4, std::max(x_max - x_min, z_max - z_min) / 4000);
  r.x0 = x_min - 4 * r.pixel, r.z0 = z_min - 4 * r.pixel;
  r.width = int((x_max - r.x0) / r.pixel) + 8, r.height = int((z_max - r.z0) / r.pixel) + 8;
  cv::Mat lines(r.height, r.width, CV_8U, cv::Scalar(255)), inside(r.height, r.width, CV_8U, cv::Scalar(0));
  for (const ProfileCurve& c : section.curves)
    for (size_t k = 0; k + 1 < c.points.size(); ++k) cv::line(lines, r.at(c.points[k]), r.at(c.points[k + 1]), cv::Scalar(0));
  std::vector<std::vector<cv::Point>> polygons;
  for (const auto& loop : section.loops) {
    polygons.emplace_back();
    for (const Vec2& q : loop) polygons.back().push_back(r.at(q));
  }
  if (!polygons.empty()) cv::fillPoly(inside, polygons, cv::Scalar(1));
  cv::Mat distance;
  cv::distanceTransform(lines, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const LoopCrossings loops(section.loops);
  std::vector<double> out(p.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(p.size()); ++i) {
    const double fx = (p[size_t(i)].head<2>().norm() - r.x0) / r.pixel, fz = (p[size_t(i)].z() - r.z0) / r.pixel;
    const int x = std::clamp(int(fx), 0, r.width - 2), z = std::clamp(int(fz), 0, r.height - 2);
    const double ax = std::clamp(fx - x, 0.0, 1.0), az = std::clamp(fz - z, 0.0, 1.0);
    const double d = (1 - az) * ((1 - ax) * distance.at<float>(z, x) + ax * distance.at<float>(z, x + 1)) +
                     az * ((1 - ax) * distance.at<float>(z + 1, x) + ax * distance.at<float>(z + 1, x + 1));
    // Inside the wall's section: the raster's fill where the vertex is clearly in or out; the exact
    // test near the outline (the fill's pixels would flip with the last digits of the axis).
    const Vec2 q(p[size_t(i)].head<2>().norm(), p[size_t(i)].z());
    const bool in = d > 3 ? inside.at<uchar>(std::clamp(int(std::lround(fz)), 0, r.height - 1), std::clamp(int(std::lround(fx)), 0, r.width - 1)) != 0
                          : loops.inside(q);
    out[size_t(i)] = (in ? -1 : 1) * d * r.pixel;
  }
  return out;
}

// Distance from q to the polyline.
double distance_to(const Vec2& q, const std::vector<Vec2>& line) {
  double best = INFINITY;
  for (size_t k = 0; k + 1 < line.size(); ++k) {
    const Vec2 a = line[k], ab = line[k + 1] - a;
    const double t = ab.squaredNorm() > 0 ? std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0;
    best = std::min(best, (q - a - t * ab).norm());
  }
  return best;
}

// The wall's thickness: each inner-wall point's distance to the outer wall or the base's underside
// (5th and 95th percentile).
void measure_thickness(VesselRecord& record) {
  std::vector<double> thickness;
  for (const ProfileCurve& inner : record.profile) {
    if (inner.part != ProfilePart::inner_wall) continue;
    for (const Vec2& q : inner.points) {
      double best = INFINITY;
      for (const ProfileCurve& outer : record.profile)
        if (outer.part == ProfilePart::outer_wall || outer.part == ProfilePart::base) best = std::min(best, distance_to(q, outer.points));
      if (std::isfinite(best)) thickness.push_back(best);
    }
  }
  record.thickness_low = percentile(thickness, 0.05), record.thickness_high = percentile(thickness, 0.95);
}

// The rim's diameter as a rim chart reads it: the circle where the rim touches the chart, at its
// highest point (a rounded lip's crest, a flat rim's outer edge); and the share of the circumference the piece keeps (its vertices within two edges of the
// top, by whole degrees round the axis; gaps of 2 degrees closed).
void measure_rim(VesselRecord& record, const std::vector<Vec3>& p, double edge) {
  record.has_rim = record.top_is_rim;
  if (!record.has_rim) return;
  // The lip: the section's part facing up at the top; a lip too thin to face up (a pointed
  // rim) is the section's topmost wall.
  bool faces_up = false;
  for (const ProfileCurve& c : record.profile) faces_up = faces_up || c.part == ProfilePart::rim;
  auto is_lip = [&](ProfilePart part) { return faces_up ? part == ProfilePart::rim : part != ProfilePart::break_surface; };
  double top = -INFINITY;
  for (const ProfileCurve& c : record.profile)
    if (is_lip(c.part))
      for (const Vec2& q : c.points) top = std::max(top, q.y());
  if (!std::isfinite(top)) {
    record.has_rim = false;
    return;
  }
  // The crest: the top of a parabola z(r) through the vertices of every meridian within 1.5 edge
  // lengths of the top, across the section's rim (its part facing up: a near-vertical wall below
  // the lip would skew the parabola); the outer edge of that range when they make no cap (a flat rim).
  double inside = INFINITY, outside = 0;
  for (const ProfileCurve& c : record.profile)
    if (is_lip(c.part))
      for (const Vec2& q : c.points)
        if (q.y() >= top - 1.5 * edge) inside = std::min(inside, q.x()), outside = std::max(outside, q.x());
  Mat3 normal = Mat3::Zero();
  Vec3 right = Vec3::Zero();
  for (const Vec3& q : p) {
    const double r = q.head<2>().norm();
    if (q.z() < top - 1.5 * edge || r < inside || r > outside) continue;
    const Vec3 basis(1, r - inside, (r - inside) * (r - inside));
    normal += basis * basis.transpose(), right += q.z() * basis;
  }
  double radius = outside;  // a flat top: its outer edge, where a rim chart reads it
  if (outside - inside > 0.5 * edge && normal(0, 0) >= 6) {
    const Vec3 parabola = (normal + 1e-12 * normal.trace() * Mat3::Identity()).ldlt().solve(right);
    if (parabola[2] < 0) radius = std::clamp(inside - parabola[1] / (2 * parabola[2]), inside, outside);
  }
  if (radius < 2 * edge) {  // a top on the axis: a closed top (a lid's knob, a dome), no rim
    record.has_rim = false;
    return;
  }
  const double band = 2 * edge;
  record.rim_height = top;
  record.rim_diameter = 2 * radius;
  std::vector<char> degree(360, 0);
  for (const Vec3& q : p)
    if (q.z() >= top - band && q.head<2>().norm() > 0.5 * radius)
      degree[size_t((int(std::floor(std::atan2(q.y(), q.x()) * kDegreesPerRadian)) + 720) % 360)] = 1;
  int covered = 0;
  for (int k = 0; k < 360; ++k) {
    const bool gap_closed = !degree[size_t(k)] && ((degree[size_t((k + 359) % 360)] || degree[size_t((k + 358) % 360)]) &&
                                                    (degree[size_t((k + 1) % 360)] || degree[size_t((k + 2) % 360)]));
    covered += degree[size_t(k)] || gap_closed;
  }
  record.rim_share = covered / 360.0;
}
}  // namespace

const char* up_rule_name(UpRule rule) {
  switch (rule) {
    case UpRule::base: return "base";
    case UpRule::rim: return "rim";
    case UpRule::input_up: return "input up";
    case UpRule::wider_end: return "wider end";
  }
  return "";
}

const char* profile_part_name(ProfilePart part) {
  switch (part) {
    case ProfilePart::outer_wall: return "outer wall";
    case ProfilePart::inner_wall: return "inner wall";
    case ProfilePart::rim: return "rim";
    case ProfilePart::base: return "base";
    case ProfilePart::break_surface: return "break";
  }
  return "";
}

void VesselRecordParams::validate() const {
  fit.validate();
  if (given_axis) {
    const AxisLine& a = *given_axis;
    if (!a.point.allFinite() || !a.direction.allFinite() || a.direction.norm() < 1e-12)
      throw InputError("The given axis needs a point and a direction that is not zero");
  }
}

TriMesh oriented_mesh(const TriMesh& mesh, const VesselRecord& record) {
  TriMesh out = mesh;
  out.vertices = moved(mesh.vertices, record.rotation, record.translation);
  return out;
}

}  // namespace reliefkit

namespace reliefkit {
namespace {

// Faces of the wall: the fit's weight above one half; with a given axis, normals within 5 degrees
// of the planes through the axis.
std::vector<char> wall_faces(const Surface& surface, VesselRecord& record, std::vector<Vec3>& face_normal,
                             const VesselRecordParams& params) {
  std::vector<char> wall(surface.mesh().faces.size());
  if (record.fit) {
    face_normal = record.fit->face_normal;
    for (size_t f = 0; f < wall.size(); ++f) wall[f] = record.fit->face_weight[f] > 0.5;
  } else {
    face_normal = smoothed_face_normals(surface, params.fit.smoothing_edges);
    const std::vector<double> angle = off_axis_angles(surface.mesh(), face_normal, record.axis);
    for (size_t f = 0; f < wall.size(); ++f) wall[f] = angle[f] < 5;
  }
  return wall;
}

// The pose: the axis onto +Z through the origin, up decided (and flipped if asked), the middle
// meridian at +x, the lowest point at z = 0.
void orient(VesselRecord& record, const Surface& surface, const std::vector<Vec3>& face_normal, const std::vector<char>& wall,
            const VesselRecordParams& params, std::vector<signed char>& end_face) {
  const bool flip_asked = params.flip;
  const TriMesh& mesh = surface.mesh();
  const double edge = surface.scale().edge;
  const std::vector<Vec3> fine_normal = smoothed_face_normals(surface, 1.0);
  Mat3 rotation = rotation_onto_axis(record.axis.direction);
  Vec3 translation = -(rotation * record.axis.point);
  translation.z() = 0;
  const std::vector<Vec3> turned = moved(mesh.vertices, rotation, translation);
  std::vector<Vec3> turned_normal(face_normal.size()), turned_fine(face_normal.size());
  for (size_t f = 0; f < face_normal.size(); ++f) turned_normal[f] = rotation * face_normal[f], turned_fine[f] = rotation * fine_normal[f];
  const EndRoughness ends = end_roughness(mesh, turned, turned_fine, turned_normal, wall, edge);
  const bool turn = params.as_oriented ? false : decide_up(mesh, turned, ends, rotation * Vec3::UnitY(), record) != flip_asked;
  if (params.as_oriented) record.up_reason = "as the piece lies (oriented before: +Z up)";
  end_face.resize(ends.end.size());
  for (size_t f = 0; f < ends.end.size(); ++f) end_face[f] = turn ? -ends.end[f] : ends.end[f];
  record.top_roughness = turn ? ends.bottom : ends.top, record.bottom_roughness = turn ? ends.top : ends.bottom;
  record.wall_roughness = ends.wall;
  record.top_is_rim = ends.smooth(turn ? ends.bottom : ends.top);
  record.bottom_is_base = ends.smooth(turn ? ends.top : ends.bottom) || record.up_rule == UpRule::base;
  record.flipped = flip_asked && !params.as_oriented;
  if (params.as_oriented) return;  // the identity: the axis +Z through the origin, as given
  if (turn) rotation = Vec3(1, -1, -1).asDiagonal() * rotation, translation = Vec3(1, -1, -1).asDiagonal() * translation;
  std::vector<Vec3> p = moved(mesh.vertices, rotation, translation);
  const Mat3 spin = Eigen::AngleAxisd(-middle_meridian(mesh, p), Vec3::UnitZ()).toRotationMatrix();
  rotation = spin * rotation, translation = spin * translation;
  double z_min = INFINITY;
  for (const Vec3& v : mesh.vertices) z_min = std::min(z_min, (rotation * v + translation).z());
  translation.z() -= z_min;
  record.rotation = rotation, record.translation = translation;
  record.axis.direction = rotation.transpose() * Vec3::UnitZ();
  record.axis.point = -(rotation.transpose() * translation);
}

// A fitted axis whose surface of revolution the wall leaves far behind: the normals all meet the
// axis (a box's do too) but the piece does not turn about it.
constexpr double kMaxResidual = 0.05;  // of the largest radius
void refuse_if_not_turned(const VesselRecord& record, const std::vector<Vec3>& p) {
  if (!record.fit) return;
  double radius = 0;
  for (const Vec3& q : p) radius = std::max(radius, q.head<2>().norm());
  if (record.residual_rms > kMaxResidual * radius)
    throw InputError(format("this is no piece of a surface of revolution: its wall lies %.3g (rms) from the surface its "
                            "profile sweeps about the best axis, %.0f %% of its largest radius (a wheel-made pot: under "
                            "2 %%); give the axis if it is known",
                            record.residual_rms, 100 * record.residual_rms / radius));
}

}  // namespace

VesselRecord record_vessel(const Surface& surface, const VesselRecordParams& params) {
  params.validate();
  surface.require_triangles();
  require_usable_scale(surface.scale());
  const TriMesh& mesh = surface.mesh();
  const double edge = surface.scale().edge;
  auto report = [&](int percent, const char* what) { return !params.progress || params.progress(percent, what); };
  VesselRecord record;
  report(5, "Fitting the axis");
  if (params.as_oriented) {
    record.axis = AxisLine{Vec3::Zero(), Vec3::UnitZ()};
  } else if (params.given_axis) {
    record.axis = *params.given_axis;
    record.axis.direction.normalize();
  } else {
    record.fit = fit_vessel_axis(surface, params.fit);
    record.axis = record.fit->axis;
  }
  report(60, "Orienting the piece");
  std::vector<Vec3> face_normal;
  const std::vector<char> wall = wall_faces(surface, record, face_normal, params);
  std::vector<signed char> end_face;
  orient(record, surface, face_normal, wall, params, end_face);
  const TriMesh oriented = oriented_mesh(mesh, record);
  for (Vec3& n : face_normal) n = record.rotation * n;
  report(75, "Cutting the profile");
  Ends ends;
  ends.rim = record.top_is_rim;
  ends.base = record.bottom_is_base;
  const Section section = section_profile(oriented, face_normal, wall, end_face, ends, edge);
  record.profile = section.curves;
  record.section_loops = section.loops;
  if (record.profile.empty())
    throw InputError("The plane through the axis and the piece's middle misses the piece: the axis runs outside what "
                     "this surface could turn about (a given axis far from the piece?)");
  measure_thickness(record);
  measure_rim(record, oriented.vertices, edge);
  record.has_base = false;
  for (const ProfileCurve& c : record.profile) record.has_base = record.has_base || c.part == ProfilePart::base;
  report(85, "Measuring the distances from the surface of revolution");
  record.distance = distances_from_profile(oriented.vertices, section, edge);
  double sum = 0;
  long n = 0;
  for (size_t f = 0; f < mesh.faces.size(); ++f)
    if (wall[f])
      for (int v : mesh.faces[f]) sum += record.distance[size_t(v)] * record.distance[size_t(v)], ++n;
  record.residual_rms = n > 0 ? std::sqrt(sum / double(n)) : 0;
  refuse_if_not_turned(record, oriented.vertices);
  if (record.fit) {
    record.angle_uncertainty_deg = record.fit->angle_uncertainty_deg;
    // The jackknife's offset is where the axis crosses the plane through the piece's centre; at
    // the rim a tilt adds its height above that centre times the angle.
    Vec3 centre = Vec3::Zero();
    for (const Vec3& v : oriented.vertices) centre += v / double(oriented.vertices.size());
    const double lever = record.has_rim ? record.rim_height - centre.z() : 0;
    // The crest itself is read to about an eighth of an edge (a parabola through many vertices).
    record.diameter_uncertainty =
        record.has_rim ? 2 * std::hypot(std::hypot(record.fit->offset_uncertainty, lever * std::tan(record.angle_uncertainty_deg / kDegreesPerRadian)),
                                        edge / 8)
                       : 0;
  }
  report(100, "Done");
  return record;
}

namespace {
// The polygon's part at x >= 0 (Sutherland-Hodgman against the axis), closed along it.
std::vector<Vec2> right_half(const std::vector<Vec2>& loop) {
  std::vector<Vec2> out;
  for (size_t k = 0; k + 1 < loop.size(); ++k) {
    const Vec2 &a = loop[k], &b = loop[k + 1];
    if (a.x() >= 0) out.push_back(a);
    if ((a.x() >= 0) != (b.x() >= 0)) {
      const double t = a.x() / (a.x() - b.x());
      out.push_back(Vec2(0, a.y() + t * (b.y() - a.y())));
    }
  }
  if (out.size() >= 3) out.push_back(out.front());
  return out.size() >= 4 ? out : std::vector<Vec2>{};
}
}  // namespace

PotterySheet pottery_sheet(const VesselRecord& r) {
  PotterySheet sheet;
  for (const auto& loop : r.section_loops) {
    std::vector<Vec2> half = right_half(loop);
    if (!half.empty()) sheet.section.push_back(std::move(half));
  }
  if (sheet.section.empty())
    for (const ProfileCurve& c : r.profile) sheet.lines.push_back(c.points);
  sheet.has_rim = r.has_rim;
  sheet.rim_height = r.rim_height, sheet.rim_radius = r.rim_diameter / 2, sheet.rim_share = r.rim_share;
  return sheet;
}

// Beyond this uncertainty of the fitted axis (degrees) the log warns: the tilt the small
// body sherd allows, and about where the profile's shape starts to follow the axis' error visibly.
constexpr double kLooseAxisDeg = 1;

std::vector<std::string> record_log_lines(const VesselRecord& r) {
  std::vector<std::string> lines;
  const Vec3 a = r.axis.point, d = r.axis.direction;
  char text[600];
  std::snprintf(text, sizeof text, "Axis (in the input's frame): through (%.6g, %.6g, %.6g), direction (%.6f, %.6f, %.6f), %s.",
                a.x(), a.y(), a.z(), d.x(), d.y(), d.z(), r.fit ? "fitted" : "as given");
  lines.push_back(text);
  if (r.fit) {
    std::snprintf(text, sizeof text,
                  "Fit: the normals of %.0f %% of the surface meet the axis (rms %.2f degrees; the rest, breaks and "
                  "decoration, left out beyond %.1f degrees); uncertainty of the axis %.2f degrees, of its position %.3g.",
                  100 * r.fit->wall_share, r.fit->rms_angle_deg, r.fit->cutoff_deg, r.fit->angle_uncertainty_deg,
                  r.fit->offset_uncertainty);
    lines.push_back(text);
    if (r.fit->angle_uncertainty_deg > kLooseAxisDeg) {
      std::snprintf(text, sizeof text,
                    "Warning: this piece holds its axis only loosely (uncertainty %.1f degrees): a small sherd of an evenly "
                    "rounded wall fits axes some degrees apart about equally well, and the profile, diameter and pose "
                    "follow the axis. Check the orientation against a rim chart, or give the axis (Axis: Given).",
                    r.fit->angle_uncertainty_deg);
      lines.push_back(text);
    }
  }
  lines.push_back("Up: " + r.up_reason + (r.flipped ? "; then turned over, as asked (Flip)." : "."));
  if (r.has_rim && (r.up_rule == UpRule::input_up || r.up_rule == UpRule::wider_end))
    lines.push_back("Warning: the piece does not show which end is its rim (no floor, and both ends as smooth or as rough as "
                    "each other): the rim measured is the top end as the piece now lies. Check it; if the rim is at the "
                    "bottom, run again with Turn over.");
  if (r.has_rim) {
    std::snprintf(text, sizeof text, "Rim diameter %.4g (uncertainty %.2g); preserved rim %.1f %% of the circumference (EVE %.2f).",
                  r.rim_diameter, r.diameter_uncertainty, 100 * r.rim_share, r.rim_share);
  } else {
    std::snprintf(text, sizeof text, "No rim on the piece (its top is a break, or closed over the axis): no rim diameter or EVE.");
  }
  lines.push_back(text);
  if (r.thickness_high > 0)
    std::snprintf(text, sizeof text, "Wall thickness %.3g to %.3g (5th to 95th percentile along the profile).", r.thickness_low, r.thickness_high);
  else
    std::snprintf(text, sizeof text, "Wall thickness not measured: the profile has only one wall.");
  lines.push_back(text);
  std::snprintf(text, sizeof text,
                "Residual: the wall lies %.3g (rms) from the surface of revolution of its profile; vertex quality = each "
                "vertex's distance from it (+ outside the wall, - inside).",
                r.residual_rms);
  lines.push_back(text);
  // One line of name=value for tables (reliefkit-batch puts it in its summary's record column).
  std::snprintf(text, sizeof text,
                "Record: rim_diameter=%.6g; rim_diameter_uncertainty=%.3g; eve=%.4f; thickness_low=%.4g; thickness_high=%.4g; "
                "residual_rms=%.4g; axis_uncertainty_deg=%.3g; up=%s",
                r.rim_diameter, r.diameter_uncertainty, r.rim_share, r.thickness_low, r.thickness_high, r.residual_rms,
                r.angle_uncertainty_deg, up_rule_name(r.up_rule));
  lines.push_back(text);
  return lines;
}

}  // namespace reliefkit
