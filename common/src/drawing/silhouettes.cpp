// ReliefKit — views and outlines of the base from silhouettes (thesis sect. 7.5): the views a
// drawing shows, the outlines of its bodies, a mesh's silhouette outline, the circle-distance
// feature and outline distances. See base_library.h.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <numeric>
#include <omp.h>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "reliefkit/drawing/base_library.h"
#include "silhouette_raster.h"

namespace reliefkit {
namespace {
std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}
double polygon_length(const Outline& o) {
  double len = 0;
  for (size_t i = 0; i < o.size(); ++i) len += (o[(i + 1) % o.size()] - o[i]).norm();
  return len;
}
// Fills the holes of a binary mask (every zero region not connected to the border), in place.
// The mask must have a zero border.
void fill_holes(cv::Mat& mask) {
  cv::Mat outside = mask.clone();
  cv::floodFill(outside, cv::Point(0, 0), cv::Scalar(128));
  mask.setTo(255, outside != 128);
}
double signed_axis(const Vec3& p, int axis) { return axis > 0 ? p[axis - 1] : -p[-axis - 1]; }
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

namespace silhouette {
std::array<int, 2> view_axes(ViewKind view) {
  switch (view) {
    case ViewKind::Side: return {-3, 2};
    case ViewKind::Top: return {1, -3};
    default: return {1, 2};
  }
}
std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
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
Outline raster_outline(const Raster& r) {
  return largest_contour(r.mask, [&](double x, double y) { return r.to_world(x, y); });
}
}  // namespace silhouette

using silhouette::densify;
using silhouette::largest_contour;
using silhouette::lower;
using silhouette::view_axes;

// ---- views ---------------------------------------------------------------------------------
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

// ---- outlines and features -----------------------------------------------------------------

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
  const silhouette::Raster r = silhouette::rasterize(mesh, u, v, resolution);
  if (r.mask.empty()) return {};
  return silhouette::raster_outline(r);
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

namespace {

// Q's points bucketed in a uniform grid (about two per cell), for exact nearest-point searches.
struct PointGrid {
  const std::vector<Vec2>& points;
  Vec2 origin;
  double cell = 1;
  int nx = 1, ny = 1;
  std::vector<int> start, order;  // the points of cell c: order[start[c] .. start[c + 1])

  explicit PointGrid(const std::vector<Vec2>& q) : points(q) {
    Vec2 lo = q[0], hi = q[0];
    for (const auto& p : q) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const Vec2 size = (hi - lo).cwiseMax(Vec2(1e-12, 1e-12));
    cell = std::max(std::sqrt(2 * size.x() * size.y() / double(q.size())), std::max(size.x(), size.y()) / 4096);
    origin = lo;
    nx = int(size.x() / cell) + 1, ny = int(size.y() / cell) + 1;
    start.assign(size_t(nx) * size_t(ny) + 1, 0);
    for (const auto& p : q) ++start[size_t(cell_of(p)) + 1];
    for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    order.resize(q.size());
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int i = 0; i < int(q.size()); ++i) order[size_t(fill[size_t(cell_of(q[size_t(i)]))]++)] = i;
  }
  // A cell index, possibly outside the grid (bounded: far points only need the grid's side).
  int index(double t) const { return int(std::floor(std::clamp(t / cell, -double(1 << 24), double(1 << 24)))); }
  int column(double x) const { return index(x - origin.x()); }
  int row(double y) const { return index(y - origin.y()); }
  int cell_of(const Vec2& p) const {
    return std::clamp(row(p.y()), 0, ny - 1) * nx + std::clamp(column(p.x()), 0, nx - 1);
  }

  // Squared distance from p to the nearest point: rings of cells around p's cell, outwards, until
  // no cell farther out can hold a nearer point.
  double nearest_squared(const Vec2& p) const {
    const int cx = column(p.x()), cy = row(p.y());
    const int outside = std::max({0, -cx, cx - (nx - 1), -cy, cy - (ny - 1)});
    const int last = std::max({cx, nx - 1 - cx, cy, ny - 1 - cy});
    double best = std::numeric_limits<double>::infinity();
    auto visit = [&](int x, int y) {
      if (x < 0 || y < 0 || x >= nx || y >= ny) return;
      const size_t c = size_t(y) * size_t(nx) + size_t(x);
      for (int k = start[c]; k < start[c + 1]; ++k)
        best = std::min(best, (points[size_t(order[size_t(k)])] - p).squaredNorm());
    };
    for (int r = outside; r <= last; ++r) {
      for (int x = std::max(0, cx - r); x <= std::min(nx - 1, cx + r); ++x) {  // the ring's top and bottom rows
        visit(x, cy - r);
        if (r > 0) visit(x, cy + r);
      }
      for (int y = std::max(0, cy - r + 1); y <= std::min(ny - 1, cy + r - 1); ++y)  // its sides
        visit(cx - r, y), visit(cx + r, y);
      const double reach = r * cell;  // every cell beyond ring r is at least this far from p
      if (best <= reach * reach) break;
    }
    return best;
  }
};

// The largest distance from a point of P to its nearest point of Q.
double directed_hausdorff(const std::vector<Vec2>& P, const std::vector<Vec2>& Q) {
  const PointGrid grid(Q);
  double worst = 0;
#pragma omp parallel for reduction(max : worst) schedule(static)
  for (long i = 0; i < long(P.size()); ++i) worst = std::max(worst, grid.nearest_squared(P[size_t(i)]));
  return std::sqrt(worst);
}

}  // namespace

double outline_hausdorff(const Outline& a, const Outline& b) {
  if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
  const double step = std::max(outline_diagonal(a), outline_diagonal(b)) / 1500;
  const auto A = densify(a, step), B = densify(b, step);
  return std::max(directed_hausdorff(A, B), directed_hausdorff(B, A));
}

void sort_reading_order(std::vector<DrawingOutline>& outlines) {
  std::sort(outlines.begin(), outlines.end(), [](const DrawingOutline& a, const DrawingOutline& b) {
    const int overlap = std::min(a.box.y + a.box.height, b.box.y + b.box.height) - std::max(a.box.y, b.box.y);
    if (overlap > 0.5 * std::min(a.box.height, b.box.height)) return a.box.x < b.box.x;
    return a.box.y < b.box.y;
  });
}

Outline outline_in_units(const Outline& pixels, double pixel_size) {
  Outline out;
  out.reserve(pixels.size());
  for (const auto& q : pixels) out.push_back(Vec2(q.x() * pixel_size, -q.y() * pixel_size));
  return out;
}

bool touches_frame(const cv::Rect& b, const cv::Rect& frame) {
  const int near = std::max(3, int(0.01 * std::max(frame.width, frame.height)));
  return b.x - frame.x <= near || b.y - frame.y <= near || frame.x + frame.width - (b.x + b.width) <= near ||
         frame.y + frame.height - (b.y + b.height) <= near;
}

std::vector<FoundViewOutline> find_view_outlines(const std::vector<DrawingView>& views,
                                                 const std::function<const ViewImage&(const std::string&)>& image_of,
                                                 const OutlineParams& params) {
  const ViewImage& drawing = image_of("");
  std::vector<FoundViewOutline> found(views.size());
  std::vector<size_t> shared;
  for (size_t i = 0; i < views.size(); ++i)
    if (views[i].image.empty() && views[i].region.area() == 0) shared.push_back(i);
  if (!shared.empty()) {
    auto all = drawing_outlines(drawing.grey, cv::Rect(), int(shared.size()), params);
    if (all.size() < shared.size()) {
      std::string names;
      for (size_t i : shared) names += std::string(names.empty() ? "" : ", ") + view_name(views[i].kind);
      throw InputError("The views " + names + " need " + std::to_string(shared.size()) + " separate outlines, but the "
                       "drawing has " + std::to_string(all.size()) + ": give each view's region (front = x y w h; ...).");
    }
    sort_reading_order(all);
    for (size_t k = 0; k < shared.size(); ++k)
      found[shared[k]] = {all[k], drawing.pixel_size, cv::Rect(0, 0, drawing.grey.cols, drawing.grey.rows)};
  }
  for (size_t i = 0; i < views.size(); ++i) {
    if (views[i].image.empty() && views[i].region.area() == 0) continue;
    const ViewImage& im = image_of(views[i].image);
    const cv::Rect whole(0, 0, im.grey.cols, im.grey.rows);
    found[i] = {drawing_outlines(im.grey, views[i].region, 1, params).front(), im.pixel_size,
                views[i].region.area() > 0 ? (views[i].region & whole) : whole};
  }
  return found;
}

}  // namespace reliefkit
