// ReliefKit — base of an object from its drawing's silhouettes (thesis sect. 7.5). See base_library.h.
#include "reliefkit/drawing/base_library.h"

#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <omp.h>
#include <opencv2/imgproc.hpp>
#include <random>
#include <sstream>

#include <vcg/complex/complex.h>
#include <wrap/io_trimesh/import.h>

#include "reliefkit/base/solvers.h"

namespace fs = std::filesystem;

namespace reliefkit {

// ============================================================================================
// views
// ============================================================================================
Vec2 view_coordinates(ViewKind view, const Vec3& p) {
  switch (view) {
    case ViewKind::Side: return Vec2(-p.z(), p.y());
    case ViewKind::Top: return Vec2(p.x(), -p.z());
    default: return Vec2(p.x(), p.y());
  }
}
int view_depth_axis(ViewKind view) { return view == ViewKind::Side ? 0 : view == ViewKind::Top ? 1 : 2; }
const char* view_name(ViewKind view) {
  return view == ViewKind::Side ? "side" : view == ViewKind::Top ? "top" : "front";
}
namespace {
// Signed world axes (+1..+3, -1..-3) of a view's two coordinates.
std::array<int, 2> view_axes(ViewKind view) {
  switch (view) {
    case ViewKind::Side: return {-3, 2};
    case ViewKind::Top: return {1, -3};
    default: return {1, 2};
  }
}

std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}
std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
}  // namespace

std::vector<DrawingView> parse_drawing_views(const std::string& text) {
  std::vector<DrawingView> views;
  std::string all = trim(text);
  if (all.empty()) all = "front";
  std::stringstream ss(all);
  std::string part;
  while (std::getline(ss, part, ';')) {
    part = trim(part);
    if (part.empty()) continue;
    std::string name = part, rest;
    const size_t eq = part.find('=');
    if (eq != std::string::npos) { name = trim(part.substr(0, eq)); rest = trim(part.substr(eq + 1)); }
    DrawingView v;
    const std::string n = lower(name);
    if (n == "front" || n == "elevation") v.kind = ViewKind::Front;
    else if (n == "side" || n == "profile") v.kind = ViewKind::Side;
    else if (n == "top" || n == "plan") v.kind = ViewKind::Top;
    else
      throw InputError("Views: \"" + name + "\" is not a view; use front, side or top (e.g. \"front; top\" or "
                       "\"front = 0 0 1200 900; top = 0 900 1200 800\").");
    for (const auto& w : views)
      if (w.kind == v.kind) throw InputError(std::string("Views: the ") + view_name(v.kind) + " view is named twice.");
    if (!rest.empty()) {
      std::string numbers = rest;
      std::replace(numbers.begin(), numbers.end(), ',', ' ');
      std::istringstream ns(numbers);
      double x, y, w, h;
      std::string extra;
      if (ns >> x >> y >> w >> h && !(ns >> extra)) {
        if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(w) && std::isfinite(h)) || w < 8 || h < 8 || x < 0 || y < 0)
          throw InputError("Views: the region of the " + std::string(view_name(v.kind)) +
                           " view must be \"x y width height\" in pixels, at least 8 x 8 inside the image.");
        v.region = cv::Rect(int(x), int(y), int(w), int(h));
      } else if (std::isdigit(static_cast<unsigned char>(rest[0]))) {
        throw InputError("Views: cannot read the region \"" + rest + "\" of the " + view_name(v.kind) +
                         " view; write it as \"x y width height\" in pixels.");
      } else {
        v.image = rest;
      }
    }
    views.push_back(v);
  }
  if (views.empty()) views.push_back(DrawingView{});
  return views;
}

// ============================================================================================
// outlines
// ============================================================================================
namespace {
double polygon_length(const Outline& o) {
  double len = 0;
  for (size_t i = 0; i < o.size(); ++i) len += (o[(i + 1) % o.size()] - o[i]).norm();
  return len;
}
// Points along the closed polygon at most `step` apart.
std::vector<Vec2> densify(const Outline& o, double step) {
  std::vector<Vec2> out;
  if (o.empty()) return out;
  out.reserve(o.size() * 2);
  for (size_t i = 0; i < o.size(); ++i) {
    const Vec2 a = o[i], b = o[(i + 1) % o.size()];
    const int n = std::max(1, int(std::ceil((b - a).norm() / std::max(step, 1e-300))));
    for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * (double(k) / n));
  }
  return out;
}

// Fills the holes of a binary mask (every zero region not connected to the border), in place.
// The mask must have a zero border.
void fill_holes(cv::Mat& mask) {
  cv::Mat outside = mask.clone();
  cv::floodFill(outside, cv::Point(0, 0), cv::Scalar(128));
  mask.setTo(255, outside != 128);
}

struct Raster {
  cv::Mat mask;       // CV_8U, 255 inside the projection (holes filled), zero border
  double a0 = 0, b1 = 0, scale = 1, pad = 2;
  std::array<int, 2> axes{1, 2};
  Vec2 to_pixel(const Vec2& ab) const { return Vec2(pad + (ab.x() - a0) * scale, pad + (b1 - ab.y()) * scale); }
  Vec2 to_world(double x, double y) const { return Vec2(a0 + (x - pad) / scale, b1 - (y - pad) / scale); }
};
double signed_axis(const Vec3& p, int axis) { return axis > 0 ? p[axis - 1] : -p[-axis - 1]; }

Raster rasterize(const TriMesh& mesh, int u, int v, int resolution) {
  Raster r;
  r.axes = {u, v};
  double a0 = 1e300, a1 = -1e300, b0 = 1e300, b1 = -1e300;
  for (const auto& p : mesh.vertices) {
    if (!p.allFinite()) continue;
    const double a = signed_axis(p, u), b = signed_axis(p, v);
    a0 = std::min(a0, a); a1 = std::max(a1, a); b0 = std::min(b0, b); b1 = std::max(b1, b);
  }
  if (!(a1 >= a0) || !(b1 >= b0)) return r;
  const double extent = std::max(a1 - a0, b1 - b0);
  if (!(extent > 0)) return r;
  resolution = std::max(resolution, 16);
  r.scale = (resolution - 1 - 2 * r.pad) / extent;
  r.a0 = a0; r.b1 = b1;
  const int w = int(std::ceil((a1 - a0) * r.scale + 2 * r.pad)) + 1, h = int(std::ceil((b1 - b0) * r.scale + 2 * r.pad)) + 1;
  r.mask = cv::Mat::zeros(h, w, CV_8U);
  constexpr int kShift = 4;
  constexpr double kOne = 1 << kShift;
  for (const auto& f : mesh.faces) {
    cv::Point pts[3];
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.vertices[f[k]];
      if (!p.allFinite()) { ok = false; break; }
      const Vec2 q = r.to_pixel(Vec2(signed_axis(p, u), signed_axis(p, v)));
      pts[k] = cv::Point(int(std::lround(q.x() * kOne)), int(std::lround(q.y() * kOne)));
    }
    if (ok) cv::fillConvexPoly(r.mask, pts, 3, cv::Scalar(255), cv::LINE_8, kShift);
  }
  fill_holes(r.mask);
  return r;
}

Outline largest_contour(const cv::Mat& mask, const std::function<Vec2(double, double)>& to) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  int best = -1;
  double best_area = -1;
  for (size_t i = 0; i < contours.size(); ++i) {
    const double a = std::abs(cv::contourArea(contours[i])) + contours[i].size();
    if (a > best_area) { best_area = a; best = int(i); }
  }
  Outline out;
  if (best < 0) return out;
  for (const auto& p : contours[best]) out.push_back(to(p.x, p.y));
  return out;
}
// A pixel contour smoothed along itself (Gaussian of `sigma` points, cyclic): the one-pixel
// staircase of a traced outline would otherwise be copied onto a fine model's silhouette.
Outline smooth_closed(const Outline& o, double sigma) {
  const int n = int(o.size()), r = int(std::ceil(3 * sigma));
  if (n < 2 * r + 3) return o;
  std::vector<double> w(size_t(2 * r + 1));
  for (int k = -r; k <= r; ++k) w[size_t(k + r)] = std::exp(-0.5 * k * k / (sigma * sigma));
  const double total = std::accumulate(w.begin(), w.end(), 0.0);
  Outline out(o.size());
  for (int i = 0; i < n; ++i) {
    Vec2 p = Vec2::Zero();
    for (int k = -r; k <= r; ++k) p += w[size_t(k + r)] * o[size_t(((i + k) % n + n) % n)];
    out[size_t(i)] = p / total;
  }
  return out;
}
}  // namespace

std::vector<DrawingOutline> drawing_outlines(const cv::Mat& grey, const cv::Rect& region, int count,
                                             const OutlineParams& params) {
  if (grey.empty() || grey.type() != CV_32F) throw InputError("The drawing image is empty.");
  const cv::Rect full(0, 0, grey.cols, grey.rows);
  const cv::Rect r = region.area() > 0 ? (region & full) : full;
  if (r.width < 8 || r.height < 8)
    throw InputError("The view's region (" + std::to_string(region.x) + ", " + std::to_string(region.y) + ", " +
                     std::to_string(region.width) + " x " + std::to_string(region.height) + ") is outside the " +
                     std::to_string(grey.cols) + " x " + std::to_string(grey.rows) + " px image.");
  if (!(params.gap >= 0) || !(params.ink > 0 && params.ink < 1))
    throw InputError("Outline gap must be zero (automatic) or positive, the ink level between 0 and 1.");
  const double diag = std::hypot(double(r.width), double(r.height));
  const double gap = params.gap > 0 ? std::min(params.gap, 0.25 * diag) : std::max(3.0, 0.015 * diag);
  const int k = 2 * int(std::ceil(gap / 2)) + 1, pad = k + 2;
  cv::Mat ink;
  cv::compare(grey(r), params.ink, ink, cv::CMP_LT);  // 255 where ink
  cv::Mat padded;
  cv::copyMakeBorder(ink, padded, pad, pad, pad, pad, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::Mat body;
  cv::morphologyEx(padded, body, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  fill_holes(body);
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(body, labels, stats, centroids, 8, CV_32S);
  std::vector<long> ink_of(size_t(std::max(n, 1)), 0);
  for (int y = 0; y < padded.rows; ++y) {
    const uchar* in = padded.ptr<uchar>(y);
    const int* lab = labels.ptr<int>(y);
    for (int x = 0; x < padded.cols; ++x)
      if (in[x]) ++ink_of[size_t(lab[x])];
  }
  const double region_area = double(r.width) * r.height;
  std::vector<std::pair<double, int>> bodies;
  int marks = 0;
  for (int i = 1; i < n; ++i) {
    const double area = stats.at<int>(i, cv::CC_STAT_AREA);
    const bool big = area >= std::max(100.0, 0.002 * region_area);
    const bool encloses = area >= 2.0 * double(ink_of[size_t(i)]) || area >= 0.05 * region_area;
    if (big && encloses) bodies.push_back({area, i}); else ++marks;
  }
  if (bodies.empty()) {
    std::ostringstream msg;
    msg << "No closed outline found in the drawing";
    if (region.area() > 0) msg << "'s region " << r.x << " " << r.y << " " << r.width << " " << r.height;
    msg << ": its lines do not enclose an area even with gaps of " << int(std::lround(gap))
        << " px bridged. Draw or close the object's outer line, give the view's region, or raise 'Outline gap'.";
    throw InputError(msg.str());
  }
  std::sort(bodies.begin(), bodies.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<DrawingOutline> out;
  for (size_t b = 0; b < bodies.size() && int(out.size()) < std::max(count, 1); ++b) {
    const int i = bodies[b].second;
    cv::Mat mask = labels == i;
    DrawingOutline d;
    d.outline = smooth_closed(largest_contour(mask, [&](double x, double y) { return Vec2(x - pad + r.x, y - pad + r.y); }), 2.0);
    d.box = cv::Rect(stats.at<int>(i, cv::CC_STAT_LEFT) - pad + r.x, stats.at<int>(i, cv::CC_STAT_TOP) - pad + r.y,
                     stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    d.area = bodies[b].first;
    d.gap = gap;
    d.dropped = marks + int(bodies.size()) - 1;
    out.push_back(std::move(d));
  }
  return out;
}

Outline mesh_outline(const TriMesh& mesh, int u, int v, int resolution) {
  const Raster r = rasterize(mesh, u, v, resolution);
  if (r.mask.empty()) return {};
  return largest_contour(r.mask, [&](double x, double y) { return r.to_world(x, y); });
}
Outline mesh_outline(const TriMesh& mesh, ViewKind view, int resolution) {
  const auto a = view_axes(view);
  return mesh_outline(mesh, a[0], a[1], resolution);
}

SilhouetteFeature circle_feature(const Outline& outline) {
  SilhouetteFeature f;
  f.fill(1.f);
  if (outline.size() < 3) return f;
  std::vector<cv::Point2f> pts;
  pts.reserve(outline.size());
  for (const auto& p : outline) pts.emplace_back(float(p.x()), float(p.y()));
  cv::Point2f cc;
  float radius = 0;
  cv::minEnclosingCircle(pts, cc, radius);
  if (!(radius > 0)) return f;
  const Vec2 c(cc.x, cc.y);
  const double R = std::max(double(radius), (outline[0] - c).norm());
  std::array<double, kFeatureSamples> rmax;
  rmax.fill(-1);
  const double bin = 2 * M_PI / kFeatureSamples;
  for (const Vec2& p : densify(outline, polygon_length(outline) / 4096)) {
    const Vec2 d = p - c;
    double t = std::atan2(d.y(), d.x());
    if (t < 0) t += 2 * M_PI;
    const int k = std::min(kFeatureSamples - 1, int(t / bin));
    rmax[size_t(k)] = std::max(rmax[size_t(k)], d.norm());
  }
  // Directions no outline point falls in (a long thin part): interpolated between their neighbours.
  std::array<double, kFeatureSamples> r = rmax;
  for (int k = 0; k < kFeatureSamples; ++k) {
    if (rmax[size_t(k)] >= 0) continue;
    int a = k, b = k, da = 0, db = 0;
    while (rmax[size_t(a)] < 0 && da < kFeatureSamples) { a = (a + kFeatureSamples - 1) % kFeatureSamples; ++da; }
    while (rmax[size_t(b)] < 0 && db < kFeatureSamples) { b = (b + 1) % kFeatureSamples; ++db; }
    if (rmax[size_t(a)] < 0) return f;
    r[size_t(k)] = (rmax[size_t(a)] * db + rmax[size_t(b)] * da) / (da + db);
  }
  for (int k = 0; k < kFeatureSamples; ++k) f[size_t(k)] = float(std::clamp((R - r[size_t(k)]) / R, 0.0, 1.0));
  return f;
}

SilhouetteFeature transform_feature(const SilhouetteFeature& f, bool transpose, bool flip_u, bool flip_v) {
  constexpr int N = kFeatureSamples;
  auto remap = [](const SilhouetteFeature& in, auto map) {
    SilhouetteFeature out;
    for (int k = 0; k < N; ++k) out[size_t(((map(k) % N) + N) % N)] = in[size_t(k)];
    return out;
  };
  SilhouetteFeature g = f;
  if (transpose) g = remap(g, [](int k) { return N / 4 - 1 - k; });  // angle t -> pi/2 - t
  if (flip_u) g = remap(g, [](int k) { return N / 2 - 1 - k; });     // t -> pi - t
  if (flip_v) g = remap(g, [](int k) { return N - 1 - k; });         // t -> -t
  return g;
}

double feature_distance(const SilhouetteFeature& a, const SilhouetteFeature& b) {
  double s = 0;
  for (int k = 0; k < kFeatureSamples; ++k) s += double(a[size_t(k)] - b[size_t(k)]) * (a[size_t(k)] - b[size_t(k)]);
  return std::sqrt(s / kFeatureSamples);
}

double outline_diagonal(const Outline& a) {
  if (a.empty()) return 0;
  Vec2 lo = a[0], hi = a[0];
  for (const auto& p : a) { lo = lo.cwiseMin(p); hi = hi.cwiseMax(p); }
  return (hi - lo).norm();
}

double outline_hausdorff(const Outline& a, const Outline& b) {
  if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
  const double step = std::max(outline_diagonal(a), outline_diagonal(b)) / 1500;
  const auto A = densify(a, step), B = densify(b, step);
  auto one_way = [](const std::vector<Vec2>& P, const std::vector<Vec2>& Q) {
    double worst = 0;
#pragma omp parallel for reduction(max : worst) schedule(static)
    for (long i = 0; i < long(P.size()); ++i) {
      double best = 1e300;
      for (const auto& q : Q) best = std::min(best, (P[size_t(i)] - q).squaredNorm());
      worst = std::max(worst, best);
    }
    return std::sqrt(worst);
  };
  return std::max(one_way(A, B), one_way(B, A));
}

// ============================================================================================
// models
// ============================================================================================
TriMesh normalize_to_principal_axes(const TriMesh& mesh) {
  // Area-weighted moments of the surface (each face's area at its centroid and vertices).
  double area = 0;
  Vec3 c = Vec3::Zero();
  std::vector<double> face_area(mesh.faces.size(), 0);
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &d = mesh.vertices[t[2]];
    const double ar = 0.5 * (b - a).cross(d - a).norm();
    if (!std::isfinite(ar)) continue;
    face_area[f] = ar;
    area += ar;
    c += ar * (a + b + d) / 3;
  }
  if (!(area > 0)) throw InputError("The model has no surface (all its faces are degenerate).");
  c /= area;
  Mat3 cov = Mat3::Zero();
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    if (face_area[f] == 0) continue;
    const auto& t = mesh.faces[f];
    const Vec3 a = mesh.vertices[t[0]] - c, b = mesh.vertices[t[1]] - c, d = mesh.vertices[t[2]] - c;
    // Second moment of a triangle: A/12 (sum p p^T + (sum p)(sum p)^T).
    const Vec3 s = a + b + d;
    cov += face_area[f] / 12 * (a * a.transpose() + b * b.transpose() + d * d.transpose() + s * s.transpose());
  }
  Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
  Mat3 axes;
  for (int k = 0; k < 3; ++k) axes.col(k) = eig.eigenvectors().col(2 - k);  // decreasing extent
  // Signs: the third moment along each axis positive (a deterministic choice; retrieval tries all).
  for (int k = 0; k < 2; ++k) {
    double m3 = 0;
    for (const auto& p : mesh.vertices)
      if (p.allFinite()) m3 += std::pow((p - c).dot(axes.col(k)), 3);
    if (m3 < 0) axes.col(k) = -axes.col(k);
  }
  axes.col(2) = axes.col(0).cross(axes.col(1));
  TriMesh out = mesh;
  double radius = 0;
  for (auto& p : out.vertices) {
    p = axes.transpose() * (p - c);
    if (p.allFinite()) radius = std::max(radius, p.norm());
  }
  if (radius > 0)
    for (auto& p : out.vertices) p /= radius;
  return out;
}

namespace {
const char* const kClassNames[kBaseClasses] = {"lamp", "bowl", "cup", "krater", "jug", "amphora", "plate", "cylinder", "sphere"};

// A profile (r, z) from the bottom pole to the top pole through knots (z, r) joined by Catmull-Rom
// curves, with flat discs closing the bottom and the top.
std::vector<Vec2> revolution_profile(const std::vector<Vec2>& knots_zr, bool discs = true) {
  std::vector<Vec2> rz;
  const size_t n = knots_zr.size();
  auto at = [&](long i) { return knots_zr[size_t(std::clamp(i, 0L, long(n) - 1))]; };
  if (discs && knots_zr.front().y() > 0)
    for (int k = 0; k < 4; ++k) rz.push_back(Vec2(knots_zr.front().y() * k / 4.0, knots_zr.front().x()));
  for (size_t i = 0; i + 1 < n; ++i) {
    const Vec2 p0 = at(long(i) - 1), p1 = at(long(i)), p2 = at(long(i) + 1), p3 = at(long(i) + 2);
    for (int s = 0; s < 24; ++s) {
      const double t = s / 24.0, t2 = t * t, t3 = t2 * t;
      const Vec2 q = 0.5 * ((2 * p1) + (-p0 + p2) * t + (2 * p0 - 5 * p1 + 4 * p2 - p3) * t2 + (-p0 + 3 * p1 - 3 * p2 + p3) * t3);
      rz.push_back(Vec2(std::max(q.y(), 0.0), q.x()));
    }
  }
  rz.push_back(Vec2(knots_zr.back().y(), knots_zr.back().x()));
  if (discs && knots_zr.back().y() > 0)
    for (int k = 3; k >= 0; --k) rz.push_back(Vec2(knots_zr.back().y() * k / 4.0, knots_zr.back().x()));
  return rz;
}

// Resamples a polyline to `m` points evenly spaced by arc length.
std::vector<Vec2> resample(const std::vector<Vec2>& pts, int m) {
  std::vector<double> s(pts.size(), 0);
  for (size_t i = 1; i < pts.size(); ++i) s[i] = s[i - 1] + (pts[i] - pts[i - 1]).norm();
  std::vector<Vec2> out;
  size_t j = 0;
  for (int k = 0; k < m; ++k) {
    const double t = s.back() * k / (m - 1);
    while (j + 2 < pts.size() && s[j + 1] < t) ++j;
    const double len = s[j + 1] - s[j];
    const double a = len > 0 ? std::clamp((t - s[j]) / len, 0.0, 1.0) : 0;
    out.push_back(pts[j] + a * (pts[j + 1] - pts[j]));
  }
  return out;
}

struct Bump {  // radial bump toward angle `angle`: length, angular width, height centre and half-height
  double angle, length, width, z, half_height;
};

void append(TriMesh& m, const TriMesh& part) {
  const int off = m.n_vertices();
  m.vertices.insert(m.vertices.end(), part.vertices.begin(), part.vertices.end());
  for (auto f : part.faces) m.faces.push_back({f[0] + off, f[1] + off, f[2] + off});
}

TriMesh revolve(const std::vector<Vec2>& profile_rz, int around, const std::vector<Bump>& bumps) {
  double len = 0;
  for (size_t i = 1; i < profile_rz.size(); ++i) len += (profile_rz[i] - profile_rz[i - 1]).norm();
  double rmax = 0;
  for (const auto& p : profile_rz) rmax = std::max(rmax, p.x());
  const int rings = std::max(8, int(std::lround(len / (2 * M_PI * rmax / around))) + 1);
  const auto pr = resample(profile_rz, rings);
  TriMesh m;
  m.vertices.push_back(Vec3(0, 0, pr.front().y()));
  for (int j = 1; j + 1 < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const double t = 2 * M_PI * i / around;
      double r = pr[size_t(j)].x();
      for (const auto& b : bumps) {
        double d = std::remainder(t - b.angle, 2 * M_PI);
        const double dz = (pr[size_t(j)].y() - b.z) / b.half_height;
        r += b.length * std::exp(-(d / b.width) * (d / b.width)) * std::exp(-dz * dz * dz * dz);
      }
      m.vertices.push_back(Vec3(r * std::cos(t), r * std::sin(t), pr[size_t(j)].y()));
    }
  const int top = m.n_vertices();
  m.vertices.push_back(Vec3(0, 0, pr.back().y()));
  auto id = [&](int j, int i) { return 1 + (j - 1) * around + (i % around); };
  for (int i = 0; i < around; ++i) m.faces.push_back({0, id(1, i + 1), id(1, i)});
  for (int j = 1; j + 2 < rings; ++j)
    for (int i = 0; i < around; ++i) {
      m.faces.push_back({id(j, i), id(j, i + 1), id(j + 1, i + 1)});
      m.faces.push_back({id(j, i), id(j + 1, i + 1), id(j + 1, i)});
    }
  for (int i = 0; i < around; ++i) m.faces.push_back({top, id(rings - 2, i), id(rings - 2, i + 1)});
  return m;
}

// A tube of radius `radius` along the cubic Bezier p0..p3; `up` is a direction not along it.
TriMesh tube(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double radius, const Vec3& up) {
  constexpr int kAlong = 28, kAround = 12;
  TriMesh m;
  for (int s = 0; s <= kAlong; ++s) {
    const double t = double(s) / kAlong, u = 1 - t;
    const Vec3 p = u * u * u * p0 + 3 * u * u * t * p1 + 3 * u * t * t * p2 + t * t * t * p3;
    const Vec3 d = (3 * u * u * (p1 - p0) + 6 * u * t * (p2 - p1) + 3 * t * t * (p3 - p2)).normalized();
    const Vec3 n = up.cross(d).normalized(), b = d.cross(n);
    for (int k = 0; k < kAround; ++k) {
      const double a = 2 * M_PI * k / kAround;
      m.vertices.push_back(p + radius * (std::cos(a) * n + std::sin(a) * b));
    }
  }
  for (int s = 0; s < kAlong; ++s)
    for (int k = 0; k < kAround; ++k) {
      const int a = s * kAround + k, b = s * kAround + (k + 1) % kAround, c = a + kAround, d = b + kAround;
      m.faces.push_back({a, b, d});
      m.faces.push_back({a, d, c});
    }
  // Outward: the first face's normal must point away from the path.
  const auto& f = m.faces[0];
  const Vec3 nrm = (m.vertices[f[1]] - m.vertices[f[0]]).cross(m.vertices[f[2]] - m.vertices[f[0]]);
  if (nrm.dot(m.vertices[f[0]] - p0) < 0)
    for (auto& g : m.faces) std::swap(g[1], g[2]);
  return m;
}

// Radius of the profile at height z (the outermost crossing).
double radius_at(const std::vector<Vec2>& rz, double z) {
  double best = 0;
  for (size_t i = 1; i < rz.size(); ++i) {
    const Vec2 a = rz[i - 1], b = rz[i];
    if ((a.y() - z) * (b.y() - z) > 0 || a.y() == b.y()) continue;
    const double t = (z - a.y()) / (b.y() - a.y());
    best = std::max(best, a.x() + t * (b.x() - a.x()));
  }
  return best;
}

// A loop handle in the xz-plane on the side `side` (+1: +x, -1: -x) from height z0 to z1 bulging out by `out`.
TriMesh side_handle(const std::vector<Vec2>& rz, int side, double z0, double z1, double out, double thick) {
  const double r0 = radius_at(rz, z0) - thick, r1 = radius_at(rz, z1) - thick;
  const double rr = std::max(r0, r1) + out;
  return tube(Vec3(side * r0, 0, z0), Vec3(side * (rr + 0.3 * out), 0, z0 + 0.1 * (z1 - z0)),
              Vec3(side * (rr + 0.3 * out), 0, z1 - 0.05 * (z1 - z0)), Vec3(side * r1, 0, z1), thick, Vec3(0, 1, 0));
}
// A horizontal loop handle at height z on the side `side`, spanning +-half_angle around the body.
TriMesh horizontal_handle(const std::vector<Vec2>& rz, int side, double z, double half_angle, double out, double thick) {
  const double r = radius_at(rz, z) - thick;
  const double c = std::cos(half_angle), s = std::sin(half_angle);
  const double x = side * r * c, y = r * s, xo = side * (r * c + out);
  return tube(Vec3(x, -y, z), Vec3(xo, -0.8 * y, z + 0.4 * out), Vec3(xo, 0.8 * y, z + 0.4 * out), Vec3(x, y, z), thick,
              Vec3(0, 0, 1));
}
}  // namespace

const char* base_class_name(int c) { return c >= 0 && c < kBaseClasses ? kClassNames[c] : "model"; }

std::vector<BaseModelSpec> standard_base_specs(int per_class, unsigned seed) {
  std::vector<BaseModelSpec> specs;
  for (int c = 0; c < kBaseClasses; ++c)
    for (int v = 0; v < per_class; ++v) {
      BaseModelSpec s;
      s.kind = c;
      s.variant = v;
      s.seed = seed * 1000003u + unsigned(c) * 7919u + unsigned(v) * 104729u;
      char name[64];
      std::snprintf(name, sizeof name, "%s_%02d", kClassNames[c], v + 1);
      s.name = name;
      specs.push_back(s);
    }
  return specs;
}

TriMesh make_base_model(const BaseModelSpec& spec, int around) {
  std::mt19937 rng(spec.seed);
  auto U = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  around = std::max(around, 16);
  std::vector<Vec2> knots;  // (z, r)
  std::vector<Bump> bumps;
  TriMesh extra;
  std::vector<Vec2> rz;
  switch (spec.kind) {
    case 0: {  // lamp: low lens-shaped body, a nozzle towards +x; ring handle, knob or none at -x
      const double h = U(0.32, 0.5), rb = U(0.45, 0.6), rt = U(0.6, 0.72);
      knots = {{0, rb}, {0.15 * h, rb + 0.1}, {0.45 * h, 1.0}, {0.8 * h, U(0.82, 0.9)}, {h, rt}};
      rz = revolution_profile(knots);
      bumps.push_back({0, U(0.45, 0.95), U(0.22, 0.4), 0.5 * h, 0.4 * h});
      if (spec.variant % 3 == 1) append(extra, side_handle(rz, -1, 0.35 * h, h, U(0.25, 0.4), 0.06));
      if (spec.variant % 3 == 2) bumps.push_back({M_PI, U(0.18, 0.3), 0.18, 0.6 * h, 0.3 * h});
      break;
    }
    case 1: {  // bowl
      const double h = U(0.4, 0.65), e = U(1.7, 2.6), rf = U(0.3, 0.45);
      for (int k = 0; k <= 8; ++k) {
        const double z = h * k / 8;
        knots.push_back({z, std::max(rf, std::pow(1 - std::pow(1 - z / h, e), 1 / e))});
      }
      break;
    }
    case 2: {  // cup: tapering beaker with one handle
      const double rr = U(0.33, 0.45), rb = rr * U(0.55, 0.75), rm = rr * U(0.95, 1.1);
      knots = {{0, rb}, {0.08, rb * 1.05}, {0.4, rm}, {0.85, rr * 0.97}, {1, rr}};
      rz = revolution_profile(knots);
      append(extra, side_handle(rz, -1, U(0.2, 0.3), U(0.75, 0.85), U(0.2, 0.3), 0.035));
      break;
    }
    case 3: {  // krater: bell on a stemmed foot, two horizontal handles
      const double R = U(0.5, 0.7);
      knots = {{0, 0.3 * R}, {0.05, 0.28 * R}, {0.12, 0.12 * R}, {0.2, 0.2 * R}, {0.45, 0.75 * R}, {0.8, 0.95 * R}, {1.0, R}};
      rz = revolution_profile(knots);
      const double z = U(0.4, 0.55);
      append(extra, horizontal_handle(rz, 1, z, 0.45, U(0.12, 0.2), 0.035));
      append(extra, horizontal_handle(rz, -1, z, 0.45, U(0.12, 0.2), 0.035));
      break;
    }
    case 4: {  // jug: bulging body, narrow neck, handle at -x; spout at +x for odd variants
      const double rb = U(0.3, 0.4), rn = rb * U(0.35, 0.5);
      knots = {{0, 0.6 * rb}, {0.1, 0.85 * rb}, {0.35, rb}, {0.6, 0.85 * rb}, {0.75, rn}, {0.88, rn}, {1, rn * 1.25}};
      rz = revolution_profile(knots);
      append(extra, side_handle(rz, -1, U(0.5, 0.6), 0.93, U(0.15, 0.25), 0.035));
      if (spec.variant % 2 == 1) bumps.push_back({0, U(0.12, 0.22), 0.35, 1.0, 0.08});
      break;
    }
    case 5: {  // amphora: tall, pointed toe, two handles from shoulder to neck
      const double rb = U(0.2, 0.27), rn = rb * U(0.35, 0.45);
      knots = {{0, 0.05 * rb}, {0.05, 0.15 * rb}, {0.2, 0.75 * rb}, {0.5, rb}, {0.68, 0.85 * rb}, {0.76, rn}, {0.95, rn}, {1, rn * 1.3}};
      rz = revolution_profile(knots);
      const double out = U(0.1, 0.16);
      append(extra, side_handle(rz, 1, 0.7, 0.92, out, 0.03));
      append(extra, side_handle(rz, -1, 0.7, 0.92, out, 0.03));
      break;
    }
    case 6: {  // plate
      const double h = U(0.1, 0.2), rf = U(0.3, 0.5);
      knots = {{0, rf}, {0.25 * h, rf * 1.05}, {0.6 * h, U(0.7, 0.8)}, {h, 1.0}};
      break;
    }
    case 7: {  // cylinder
      const double r = U(0.15, 1.0);
      knots = {{0, r}, {1, r}};
      break;
    }
    default: {  // sphere (slightly oblate or prolate)
      const double c = U(0.85, 1.15);
      for (int k = 0; k <= 16; ++k) {
        const double a = M_PI * k / 16;
        rz.push_back(Vec2(std::sin(a), c * (1 - std::cos(a))));
      }
      for (auto& p : rz) p.x() = std::max(p.x(), 0.0);
      break;
    }
  }
  if (rz.empty()) rz = revolution_profile(knots);
  TriMesh m = revolve(rz, around, bumps);
  append(m, extra);
  return m;
}

std::array<SilhouetteFeature, 3> model_features(const TriMesh& normalized) {
  return {circle_feature(mesh_outline(normalized, 2, 3)), circle_feature(mesh_outline(normalized, 1, 3)),
          circle_feature(mesh_outline(normalized, 1, 2))};
}

namespace {
namespace vm {
class V;
class F;
struct Used : vcg::UsedTypes<vcg::Use<V>::AsVertexType, vcg::Use<F>::AsFaceType> {};
class V : public vcg::Vertex<Used, vcg::vertex::Coord3f, vcg::vertex::Normal3f, vcg::vertex::Color4b,
                             vcg::vertex::TexCoord2f, vcg::vertex::BitFlags> {};
class F : public vcg::Face<Used, vcg::face::VertexRef, vcg::face::Normal3f, vcg::face::Color4b, vcg::face::BitFlags> {};
class Mesh : public vcg::tri::TriMesh<std::vector<V>, std::vector<F>> {
 public:
  ~Mesh() { ClearAttributes(); }  // vcglib's own destructor leaves the importers' attributes (OBJ materials)
};
}  // namespace vm
}  // namespace

TriMesh read_model_file(const std::string& path) {
  if (!fs::is_regular_file(path)) throw InputError("The model \"" + path + "\" does not exist.");
  vm::Mesh m;
  int mask = 0;
  const int err = vcg::tri::io::Importer<vm::Mesh>::Open(m, path.c_str(), mask);
  if (err != 0 && vcg::tri::io::Importer<vm::Mesh>::ErrorCritical(err))
    throw InputError("The model \"" + path + "\" cannot be read: " + vcg::tri::io::Importer<vm::Mesh>::ErrorMsg(err) + ".");
  TriMesh out;
  std::vector<int> index(m.vert.size(), -1);
  for (size_t i = 0; i < m.vert.size(); ++i) {
    if (m.vert[i].IsD()) continue;
    const auto& p = m.vert[i].cP();
    index[i] = out.n_vertices();
    out.vertices.push_back(Vec3(p[0], p[1], p[2]));
  }
  for (const auto& f : m.face) {
    if (f.IsD()) continue;
    std::array<int, 3> t;
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      const long vi = vcg::tri::Index(m, f.cV(k));
      if (vi < 0 || size_t(vi) >= index.size() || index[size_t(vi)] < 0) { ok = false; break; }
      t[k] = index[size_t(vi)];
    }
    if (ok && t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) out.faces.push_back(t);
  }
  if (out.faces.empty()) throw InputError("The model \"" + path + "\" has no triangles.");
  return out;
}

void write_model_ply(const std::string& path, const TriMesh& mesh) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError("Cannot write \"" + path + "\".");
  out << "ply\nformat binary_little_endian 1.0\ncomment ReliefKit base model\nelement vertex " << mesh.n_vertices()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << mesh.n_faces()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : mesh.vertices) {
    const float xyz[3] = {float(p.x()), float(p.y()), float(p.z())};
    out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  for (const auto& f : mesh.faces) {
    const unsigned char n = 3;
    const int32_t ids[3] = {f[0], f[1], f[2]};
    out.write(reinterpret_cast<const char*>(&n), 1);
    out.write(reinterpret_cast<const char*>(ids), sizeof ids);
  }
  if (!out) throw InputError("Cannot write \"" + path + "\" (disk full?).");
}

namespace {
bool is_model_file(const fs::path& p) {
  const std::string e = lower(p.extension().string());
  return e == ".ply" || e == ".obj" || e == ".stl" || e == ".off";
}
}  // namespace

void add_library_folder(BaseLibrary& library, const std::string& folder, Progress progress) {
  std::error_code ec;
  if (folder.empty() || !fs::is_directory(folder, ec))
    throw InputError("The model folder \"" + folder + "\" does not exist.");
  const fs::path root(folder);
  std::vector<fs::path> files;
  for (auto it = fs::recursive_directory_iterator(root, fs::directory_options::skip_permission_denied, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
    if (it->is_regular_file(ec) && is_model_file(it->path())) files.push_back(it->path());
  std::sort(files.begin(), files.end());
  // Cache: relative path, size, time, class, 3 x kFeatureSamples features.
  struct Cached { uintmax_t size; long long time; std::string kind; std::array<SilhouetteFeature, 3> f; };
  std::map<std::string, Cached> cache;
  const fs::path cache_path = root / kFeatureCache;
  {
    std::ifstream in(cache_path);
    std::string line;
    if (in && std::getline(in, line) && line == "reliefkit-silhouettes 1") {
      while (std::getline(in, line)) {
        std::istringstream ls(line);
        std::string rel;
        Cached c;
        if (!std::getline(ls, rel, '\t')) continue;
        ls >> c.size >> c.time >> c.kind;
        bool ok = bool(ls);
        for (auto& f : c.f)
          for (auto& x : f) ok = ok && bool(ls >> x);
        if (ok) cache[rel] = c;
      }
    }
  }
  auto time_of = [](const fs::path& p) {
    std::error_code e;
    return static_cast<long long>(fs::last_write_time(p, e).time_since_epoch().count());
  };
  std::vector<LibraryModel> models(files.size());
  std::vector<std::string> errors(files.size());
  std::vector<char> fresh(files.size(), 0);
  std::vector<Cached> entries(files.size());
  long done = 0;
#pragma omp parallel for schedule(dynamic)
  for (long i = 0; i < long(files.size()); ++i) {
    const fs::path& p = files[size_t(i)];
    const std::string rel = fs::relative(p, root).generic_string();
    LibraryModel& m = models[size_t(i)];
    m.name = p.stem().string();
    m.path = p.string();
    const fs::path parent = fs::relative(p.parent_path(), root);
    m.kind = (parent.empty() || parent == ".") ? m.name.substr(0, m.name.find('_')) : parent.begin()->string();
    std::error_code e;
    Cached c{fs::file_size(p, e), time_of(p), m.kind, {}};
    const auto hit = cache.find(rel);
    if (hit != cache.end() && hit->second.size == c.size && hit->second.time == c.time) {
      m.feature = hit->second.f;
    } else {
      try {
        m.feature = model_features(normalize_to_principal_axes(read_model_file(p.string())));
        fresh[size_t(i)] = 1;
      } catch (const std::exception& ex) {
        errors[size_t(i)] = ex.what();
      }
    }
    c.f = m.feature;
    entries[size_t(i)] = c;
#pragma omp critical
    {
      ++done;
      if (progress && omp_get_thread_num() == 0) progress(int(100 * done / std::max<long>(1, long(files.size()))), "Reading the model library");
    }
  }
  int skipped = 0, computed = 0;
  for (size_t i = 0; i < files.size(); ++i) {
    if (!errors[i].empty()) {
      ++skipped;
      if (skipped <= 5) library.notes.push_back("Skipped: " + errors[i]);
      continue;
    }
    computed += fresh[i];
    library.models.push_back(models[i]);
  }
  if (skipped > 5) library.notes.push_back("Skipped " + std::to_string(skipped - 5) + " more unreadable models.");
  if (computed > 0 || cache.size() != files.size() - size_t(skipped)) {
    std::ofstream out(cache_path);
    if (out) {
      out << "reliefkit-silhouettes 1\n";
      for (size_t i = 0; i < files.size(); ++i) {
        if (!errors[i].empty()) continue;
        out << fs::relative(files[i], root).generic_string() << '\t' << entries[i].size << ' ' << entries[i].time << ' '
            << entries[i].kind;
        for (const auto& f : entries[i].f)
          for (float x : f) out << ' ' << x;
        out << '\n';
      }
    }
    if (out)
      library.notes.push_back("Silhouette features of " + std::to_string(computed) + " models computed and cached in " +
                              cache_path.string() + ".");
    else
      library.notes.push_back("Silhouette features of " + std::to_string(computed) + " models computed (the folder " +
                              folder + " is not writable: they are not cached).");
  }
}

// ============================================================================================
// retrieval
// ============================================================================================
bool AxisOrientation::mirrors() const {
  const bool odd = (axis[0] > axis[1]) ^ (axis[0] > axis[2]) ^ (axis[1] > axis[2]);
  return odd ^ ((sign[0] * sign[1] * sign[2]) < 0);
}

TriMesh oriented(const TriMesh& mesh, const AxisOrientation& o) {
  TriMesh out = mesh;
  for (auto& p : out.vertices) p = o.apply(p);
  if (o.mirrors())
    for (auto& f : out.faces) std::swap(f[1], f[2]);
  return out;
}

std::vector<AxisOrientation> all_axis_orientations() {
  std::vector<AxisOrientation> out;
  std::array<int, 3> perm{0, 1, 2};
  do {
    for (int s = 0; s < 8; ++s) {
      AxisOrientation o;
      o.axis = perm;
      o.sign = {(s & 1) ? -1 : 1, (s & 2) ? -1 : 1, (s & 4) ? -1 : 1};
      out.push_back(o);
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  return out;
}

SilhouetteFeature oriented_feature(const LibraryModel& model, const AxisOrientation& o, ViewKind view) {
  const auto axes = view_axes(view);  // signed world axes of the view's coordinates
  const int ia = std::abs(axes[0]) - 1, ib = std::abs(axes[1]) - 1;
  const int sa = (axes[0] > 0 ? 1 : -1) * o.sign[size_t(ia)], sb = (axes[1] > 0 ? 1 : -1) * o.sign[size_t(ib)];
  const int p = o.axis[size_t(ia)], q = o.axis[size_t(ib)];
  const int depth = 3 - p - q;
  return transform_feature(model.feature[size_t(depth)], p > q, sa < 0, sb < 0);
}

std::vector<BaseMatch> retrieve_bases(const BaseLibrary& library, const std::vector<ViewFeature>& views, int top) {
  if (views.empty()) throw InputError("No view of the drawing to compare with the library.");
  const auto orientations = all_axis_orientations();
  std::vector<BaseMatch> best(library.models.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(library.models.size()); ++i) {
    BaseMatch b;
    b.model = int(i);
    b.score = 1e300;
    for (const auto& o : orientations) {
      double s = 0;
      for (const auto& v : views) s += feature_distance(v.feature, oriented_feature(library.models[size_t(i)], o, v.kind));
      s /= double(views.size());
      if (s < b.score) { b.score = s; b.orientation = o; }
    }
    best[size_t(i)] = b;
  }
  std::sort(best.begin(), best.end(), [](const BaseMatch& a, const BaseMatch& b) {
    return a.score != b.score ? a.score < b.score : a.model < b.model;
  });
  if (int(best.size()) > top) best.resize(size_t(std::max(top, 1)));
  return best;
}

// ============================================================================================
// deformation
// ============================================================================================
namespace {
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
}  // namespace

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

TriMesh deform_to_outlines(const TriMesh& model, const std::vector<ViewOutline>& views, const DeformParams& params,
                           DeformReport* report) {
  require_triangles(model);
  if (!(params.alpha > 0) || !std::isfinite(params.alpha))
    throw InputError("Shape weight (alpha) must be a positive number.");
  if (params.passes < 1 || params.passes > 20) throw InputError("Passes must be between 1 and 20.");
  for (const auto& p : model.vertices)
    if (!p.allFinite()) throw InputError("The model has vertices without coordinates (NaN).");
  for (const auto& v : views)
    if (v.outline.size() < 3) throw InputError(std::string("The ") + view_name(v.kind) + " view has no outline.");
  const int n = model.n_vertices();
  auto progress = [&](int pc, const char* what) { if (params.progress) params.progress(pc, what); };
  progress(2, "Laplacian coordinates");
  // Uniform Laplacian (eq. 7.7): L = I - D^-1 A over the mesh's edges.
  std::vector<std::vector<int>> nb(static_cast<size_t>(n));
  for (const auto& f : model.faces)
    for (int k = 0; k < 3; ++k) {
      nb[size_t(f[k])].push_back(f[(k + 1) % 3]);
      nb[size_t(f[k])].push_back(f[(k + 2) % 3]);
    }
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < n; ++i) {
    auto& r = nb[size_t(i)];
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    if (r.empty()) continue;
    trip.emplace_back(i, i, 1.0);
    for (int j : r) trip.emplace_back(i, j, -1.0 / double(r.size()));
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(trip.begin(), trip.end());
  const Eigen::SparseMatrix<double> LtL = (L.transpose() * L).pruned();
  Eigen::MatrixXd V0(n, 3);
  for (int i = 0; i < n; ++i) V0.row(i) = model.vertices[size_t(i)].transpose();
  const Eigen::MatrixXd delta = L * V0;
  Eigen::MatrixXd Ltdelta_ref = L.transpose() * delta;
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  // Mean edge length, for the silhouette raster.
  double edge = 0;
  long edges = 0;
  for (const auto& f : model.faces)
    for (int k = 0; k < 3; ++k) { edge += (model.vertices[size_t(f[k])] - model.vertices[size_t(f[(k + 1) % 3])]).norm(); ++edges; }
  edge /= std::max(1L, edges);
  // Dense outline points for the closest-point matches.
  std::vector<std::vector<Vec2>> dense;
  for (const auto& v : views) dense.push_back(densify(v.outline, outline_diagonal(v.outline) / 3000));

  constexpr double kAnchor = 1e-6;  // keeps vertices of parts no view constrains where they are
  TriMesh current = model;
  DeformReport rep;
  rep.hausdorff_before = silhouette_error(model, views);
  // Edge -> faces (count, f0, f1), for the contour generators: the topology is the same in every pass.
  std::map<std::pair<int, int>, std::array<int, 3>> edge_faces;
  for (size_t f = 0; f < model.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      int a = model.faces[f][k], b = model.faces[f][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      auto& e = edge_faces[{a, b}];
      if (e[0] < 2) e[size_t(1 + e[0])] = int(f);
      ++e[0];
    }
  std::vector<double> history;  // silhouette error after each pass
  for (int pass = 0; pass < params.passes; ++pass) {
    const int p0 = 5 + 90 * pass / params.passes, p1 = 5 + 90 * (pass + 1) / params.passes;
    progress(p0, "Silhouette of the model");
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd target = Eigen::MatrixXd::Zero(n, 3);
    // Face normals of the current shape.
    std::vector<Vec3> fn(current.faces.size());
    for (size_t f = 0; f < current.faces.size(); ++f) {
      const auto& t = current.faces[f];
      fn[f] = (current.vertices[size_t(t[1])] - current.vertices[size_t(t[0])])
                  .cross(current.vertices[size_t(t[2])] - current.vertices[size_t(t[0])]);
    }
    int constrained = 0;
    for (size_t vi = 0; vi < views.size(); ++vi) {
      const auto& view = views[vi];
      const int depth = view_depth_axis(view.kind);
      std::vector<char> candidate(size_t(n), 0);
      for (const auto& [e, f] : edge_faces) {
        bool contour = f[0] != 2;
        if (!contour) {  // one face towards the view and the other away (a face seen edge-on is neither)
          const double a = fn[size_t(f[1])][depth], b = fn[size_t(f[2])][depth];
          contour = (a > 0 && b < 0) || (a < 0 && b > 0);
        }
        if (contour) candidate[size_t(e.first)] = candidate[size_t(e.second)] = 1;
      }
      const auto axes = view_axes(view.kind);
      Box2 ext;
      for (const auto& p : current.vertices) ext.add(view_coordinates(view.kind, p));
      const double extent = std::max(ext.size().x(), ext.size().y());
      const int res = params.resolution > 0 ? params.resolution
                                            : std::clamp(int(2 * extent / std::max(edge, 1e-300)), 256, 2048);
      const Raster r = rasterize(current, axes[0], axes[1], res);
      if (r.mask.empty()) continue;
      cv::Mat dist;
      cv::distanceTransform(r.mask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
      const double tol = 1.5 + 0.5 * edge * r.scale;
      std::vector<int> sil;
      for (int i = 0; i < n; ++i) {
        if (!candidate[size_t(i)]) continue;
        const Vec2 px = r.to_pixel(view_coordinates(view.kind, current.vertices[size_t(i)]));
        const int x = std::clamp(int(px.x()), 0, dist.cols - 1), y = std::clamp(int(px.y()), 0, dist.rows - 1);
        if (dist.at<float>(y, x) <= tol) sil.push_back(i);
      }
      // Each silhouette vertex is matched to the drawing's outline along the normal of the model's
      // own outline at the vertex (the nearest crossing either way; the thesis' closest point when
      // the normal crosses no line within a quarter of the outline's size): closest points alone
      // leave a concave part the model lacks (a goblet's stem) unreached. And each outline point
      // pulls its closest silhouette vertex, so parts no normal reaches (a corner) are covered too.
      // A vertex's target is the mean of its own match and of the outline points that chose it.
      std::vector<Vec2> q(sil.size());
      for (size_t s = 0; s < sil.size(); ++s) q[s] = view_coordinates(view.kind, current.vertices[size_t(sil[s])]);
      const auto& D = dense[vi];
      const Outline own = largest_contour(r.mask, [&](double x, double y) { return r.to_world(x, y); });
      const Outline& drawn = view.outline;
      const double reach = 0.25 * outline_diagonal(drawn);
      std::vector<Vec2> match(sil.size());
#pragma omp parallel for schedule(static)
      for (long s = 0; s < long(sil.size()); ++s) {
        const Vec2 p = q[size_t(s)];
        // Normal of the model's outline at its point nearest to the vertex.
        Vec2 normal(0, 0);
        if (own.size() > 8) {
          size_t at = 0;
          double best = 1e300;
          for (size_t k = 0; k < own.size(); ++k) {
            const double dd = (own[k] - p).squaredNorm();
            if (dd < best) { best = dd; at = k; }
          }
          const size_t m = own.size();
          const Vec2 tangent = own[(at + 3) % m] - own[(at + m - 3) % m];
          if (tangent.norm() > 0) normal = Vec2(-tangent.y(), tangent.x()).normalized();
        }
        double tbest = reach;
        bool hit = false;
        if (normal.squaredNorm() > 0)
          for (size_t k = 0; k < drawn.size(); ++k) {
            const Vec2 a = drawn[k], e = drawn[(k + 1) % drawn.size()] - a;
            const double den = normal.x() * e.y() - normal.y() * e.x();  // cross(normal, e)
            if (std::abs(den) < 1e-300) continue;
            const Vec2 w = a - p;
            const double t = (w.x() * e.y() - w.y() * e.x()) / den;   // along the normal
            const double u = (w.x() * normal.y() - w.y() * normal.x()) / den;  // along the segment
            if (u < 0 || u > 1 || std::abs(t) >= std::abs(tbest)) continue;
            tbest = t;
            hit = true;
          }
        if (hit) {
          match[size_t(s)] = p + tbest * normal;
        } else {
          double best = 1e300;
          Vec2 bp = p;
          for (const auto& d : D) {
            const double dd = (d - p).squaredNorm();
            if (dd < best) { best = dd; bp = d; }
          }
          match[size_t(s)] = bp;
        }
      }
      // An outline point pulls its closest silhouette vertex only when that vertex is about as close
      // as the model's outline itself: where the outline runs along faces seen edge-on (a flat lid
      // seen from the side) the nearest silhouette vertex can be far, and must not be dragged along.
      std::vector<int> chosen(D.size(), -1);
      if (!sil.empty()) {
        const double slack = 2 * edge;  // 5 or 10 edges: the goblet closer (2.8 %, 1.2 %), a bowl's one solve worse
#pragma omp parallel for schedule(static)
        for (long j = 0; j < long(D.size()); ++j) {
          double best = 1e300, own_best = 1e300;
          int at = -1;
          for (size_t s = 0; s < sil.size(); ++s) {
            const double dd = (D[size_t(j)] - q[s]).squaredNorm();
            if (dd < best) { best = dd; at = int(s); }
          }
          for (const auto& o : own) own_best = std::min(own_best, (D[size_t(j)] - o).squaredNorm());
          if (own.empty() || std::sqrt(best) <= std::sqrt(own_best) + slack) chosen[size_t(j)] = at;
        }
      }
      std::vector<Vec2> back_sum(sil.size(), Vec2::Zero());
      std::vector<int> back_count(sil.size(), 0);
      for (size_t j = 0; j < D.size(); ++j)
        if (chosen[j] >= 0) { back_sum[size_t(chosen[j])] += D[j]; ++back_count[size_t(chosen[j])]; }
      for (size_t s = 0; s < sil.size(); ++s) {
        const int i = sil[s];
        Vec2 m = match[s];
        if (back_count[s] > 0) m = 0.5 * (m + back_sum[s] / back_count[s]);
        Vec3 t = current.vertices[size_t(i)];  // depth kept
        // Inverse of view_coordinates on the view's two axes.
        for (int k = 0; k < 2; ++k) {
          const int a = std::abs(axes[size_t(k)]) - 1;
          t[a] = axes[size_t(k)] > 0 ? m[k] : -m[k];
        }
        weight[i] += 1;
        target.row(i) += t.transpose();
        ++constrained;
      }
    }
    rep.silhouette_vertices = constrained;
    progress((p0 + p1) / 2, "Least-squares solve (Cholesky)");
    // Normal equations of eq. 7.8: (alpha LtL + W + eps) V = alpha Lt delta + W V' + eps V0, W the
    // number of targets of each vertex, V' their sum. The first pass is the thesis' solve; a
    // further pass keeps the Laplacian coordinates of the pass before (the deformation grows in
    // steps, so that a large change — a cylinder made a goblet — is reached, not just begun).
    Eigen::SparseMatrix<double> A = params.alpha * LtL;
    for (int i = 0; i < n; ++i) A.coeffRef(i, i) += weight[i] + kAnchor;
    const Eigen::MatrixXd B = params.alpha * Ltdelta_ref + target + kAnchor * V0;
    if (pass == 0) {
      // The pattern is the same in every pass: ordered once. For a single pass AMD (measured on a
      // 117 K-face jug: 0.07 s to order, 0.73 s to factor); for several, CHOLMOD's own choice
      // (0.7 s to order, but 0.5 s per factorization).
      if (params.passes == 1) {
        llt.cholmod().nmethods = 1;
        llt.cholmod().method[0].ordering = CHOLMOD_AMD;
      }
      llt.analyzePattern(A);
      if (llt.info() != Eigen::Success) throw InputError("The deformation's system could not be ordered (CHOLMOD).");
    }
    llt.factorize(A);
    Eigen::MatrixXd X;
    if (llt.info() == Eigen::Success) X = llt.solve(B);
    if (llt.info() != Eigen::Success || !X.allFinite())
      throw InputError("The deformation's least-squares solve failed (CHOLMOD: the model may be too large for the memory).");
    const double residual = (A * X - B).norm() / std::max(B.norm(), 1e-300);
    char summary[96];
    std::snprintf(summary, sizeof summary, "Cholesky (CHOLMOD), residual %.1e", residual);
    rep.solver = summary;
    for (int i = 0; i < n; ++i) current.vertices[size_t(i)] = X.row(i).transpose();
    rep.passes = pass + 1;
    if (pass + 1 == params.passes) break;
    // Another pass while the last three brought the silhouette closer by 0.2 % of the outline's
    // size (a large change can get worse for a pass before it gets better).
    history.push_back(silhouette_error(current, views, 512));
    if (history.back() < 2e-3) break;
    if (history.size() >= 4 && history[history.size() - 4] - history.back() < 2e-3) break;
    Ltdelta_ref = L.transpose() * (L * X);
  }
  progress(97, "Measuring the result");
  Eigen::MatrixXd V1(n, 3);
  for (int i = 0; i < n; ++i) V1.row(i) = current.vertices[size_t(i)].transpose();
  const double d0 = delta.norm();
  rep.laplacian_change = d0 > 0 ? (L * V1 - delta).norm() / d0 : 0;
  rep.hausdorff_after = silhouette_error(current, views);
  if (report) *report = rep;
  progress(100, "Deformed");
  return current;
}

}  // namespace reliefkit
