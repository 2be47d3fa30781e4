#include "reliefkit/drawing/line_drawing.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <fstream>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "reliefkit/base/scale.h"
#include "reliefkit/drawing/shading.h"

namespace reliefkit {

void LineDetectionParams::validate() const {
  if (sigma != 0) require_range(sigma, "Line scale sigma (px, 0: automatic)", 0.5, 50);
  require_range(min_strength, "Line strength", 0, 10);
  require_range(max_intensity, "Darkest paper", 0, 1);
  require_range(min_length, "Minimum stroke length (px)", 0, 1e6);
  require_range(max_link_gap, "Link gap (px)", 1, 10);
  require_range(max_link_turn, "Link turn (radians)", 0, 3.2);
  require_range(object_gap, "Object outline gap (px)", 0, 1000);
}

double DrawingCurves::total_length() const {
  double len = 0;
  for (const auto& c : curves)
    for (size_t i = 1; i < c.size(); ++i) len += (c[i] - c[i - 1]).norm();
  return len;
}

DrawingCurves curves_where(const DrawingCurves& dc, const std::vector<char>& flag, bool value) {
  DrawingCurves out = dc;
  out.curves.clear(), out.line_width.clear(), out.shading.clear();
  for (size_t k = 0; k < dc.curves.size(); ++k) {
    if ((k < flag.size() && flag[k] != 0) != value) continue;
    out.curves.push_back(dc.curves[k]);
    if (k < dc.line_width.size()) out.line_width.push_back(dc.line_width[k]);
    if (k < dc.shading.size()) out.shading.push_back(dc.shading[k]);
  }
  return out;
}

cv::Mat curve_distance(const DrawingCurves& dc, const std::vector<char>& flag, bool value) {
  cv::Mat paper(dc.height, dc.width, CV_8U, cv::Scalar(255)), dist;
  for (size_t k = 0; k < dc.curves.size(); ++k) {
    if ((k < flag.size() && flag[k] != 0) != value) continue;
    std::vector<cv::Point> pts;
    for (const auto& q : dc.curves[k]) pts.emplace_back(int(std::lround(q.x())), int(std::lround(q.y())));
    cv::polylines(paper, pts, false, cv::Scalar(0), 1, cv::LINE_8);
  }
  cv::distanceTransform(paper, dist, cv::DIST_L2, cv::DIST_MASK_5);
  return dist;
}

std::vector<std::vector<Vec2>> margin_lines(const DrawingCurves& dc, double width) {
  require_range(width, "Margin width (px)", 0, 1e6);
  std::vector<std::vector<Vec2>> out;
  for (const auto& c : dc.curves) {
    if (c.size() < 2) continue;
    std::vector<Vec2> left, right;
    for (size_t i = 0; i < c.size(); ++i) {
      const Vec2 d = c[std::min(i + 1, c.size() - 1)] - c[i > 0 ? i - 1 : 0];
      const double len = d.norm();
      if (!(len > 0)) continue;
      const Vec2 l(d.y() / len, -d.x() / len);  // left of the direction of travel, image y down
      left.push_back(c[i] + width * l);
      right.push_back(c[i] - width * l);
    }
    if (left.size() >= 2) out.push_back(std::move(left)), out.push_back(std::move(right));
  }
  return out;
}

cv::Mat read_drawing_image(const std::string& path, double* reduction) {
  if (reduction) *reduction = 1;
  if (path.empty()) throw InputError("No drawing image was given.");
  if (!std::ifstream(path).good()) throw InputError("The drawing image \"" + path + "\" does not exist or cannot be read.");
  cv::Mat img;
  try {
    img = cv::imread(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw InputError("The drawing image \"" + path + "\" could not be decoded: " + e.what());
  }
  if (img.empty())
    throw InputError("The drawing image \"" + path + "\" is not an image OpenCV can read (PNG, JPEG, TIFF, BMP...), or it is empty.");
  const double px = double(img.rows) * img.cols;
  if (px > kMaxDrawingPixels) {
    const double f = std::sqrt(kMaxDrawingPixels / px);
    cv::Mat small;
    cv::resize(img, small, cv::Size(std::max(1, int(img.cols * f)), std::max(1, int(img.rows * f))), 0, 0, cv::INTER_AREA);
    img = small;
    if (reduction) *reduction = f;
  }
  return img;
}

cv::Mat drawing_grey(const cv::Mat& image) {
  if (image.empty() || image.rows < 1 || image.cols < 1) throw InputError("The drawing image is empty (no pixels).");
  const int ch = image.channels();
  if (ch != 1 && ch != 3 && ch != 4)
    throw InputError("The drawing image has " + std::to_string(ch) + " channels; grey, RGB or RGBA images are read.");
  if (image.depth() == CV_8U) {  // the usual case, in one pass: weights of ITU-R BT.601, alpha over white
    cv::Mat grey(image.rows, image.cols, CV_32F);
#pragma omp parallel for schedule(static)
    for (int y = 0; y < image.rows; ++y) {
      const uchar* in = image.ptr<uchar>(y);
      float* o = grey.ptr<float>(y);
      for (int x = 0; x < image.cols; ++x, in += ch) {
        float v = ch == 1 ? in[0] / 255.f : (0.114f * in[0] + 0.587f * in[1] + 0.299f * in[2]) / 255.f;
        if (ch == 4) {
          const float a = in[3] / 255.f;
          v = a * v + (1 - a);
        }
        o[x] = v;
      }
    }
    return grey;
  }
  cv::Mat f;
  const double scale = image.depth() == CV_8U ? 1.0 / 255 : image.depth() == CV_16U ? 1.0 / 65535 : 1.0;
  image.convertTo(f, CV_32F, scale);
  cv::Mat grey;
  if (ch == 1) {
    grey = f;
  } else {
    std::vector<cv::Mat> planes;
    cv::split(f, planes);  // OpenCV's channel order: B, G, R (, A)
    grey = 0.114f * planes[0] + 0.587f * planes[1] + 0.299f * planes[2];
    if (ch == 4) grey = grey.mul(planes[3]) + (1.0f - planes[3]);  // transparent = white paper
  }
  cv::patchNaNs(grey, 1.0);
  cv::min(cv::max(grey, 0.0), 1.0, grey);
  return grey;
}

cv::Mat drawing_ink(const cv::Mat& grey) {
  cv::Mat grey8, ink;
  grey.convertTo(grey8, CV_8U, 255);
  const double t = cv::threshold(grey8, ink, 0, 255, cv::THRESH_BINARY_INV | cv::THRESH_OTSU);
  if (t > 0.75 * 255) cv::threshold(grey8, ink, 0.75 * 255, 255, cv::THRESH_BINARY_INV);
  return ink;
}

namespace {
// The ink's distance to the paper (Euclidean, per ink pixel).
cv::Mat ink_distance(const cv::Mat& ink) {
  cv::Mat dist;
  cv::distanceTransform(ink, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return dist;
}

// Stroke widths at the strokes' centres (the distance's 3 x 3 maxima): 2 d - 0.5.
std::vector<float> widths_at_centres(const cv::Mat& ink, const cv::Mat& dist) {
  cv::Mat peak;
  cv::dilate(dist, peak, cv::Mat());
  std::vector<float> widths;
  for (int y = 0; y < ink.rows; ++y)
    for (int x = 0; x < ink.cols; ++x)
      if (ink.at<uchar>(y, x) && dist.at<float>(y, x) >= peak.at<float>(y, x)) widths.push_back(2 * dist.at<float>(y, x) - 0.5f);
  return widths;
}

// 1, 2, 4, 8 px up to half the widest strokes' width (the 95th percentile).
std::vector<double> scales_for(const std::vector<float>& widths) {
  const double widest = stroke_width_percentile(widths, 0.95);
  std::vector<double> scales{1};
  while (scales.back() * 2 <= kMaxAutoLineScale && 0.5 * widest > scales.back() * std::sqrt(2.0)) scales.push_back(scales.back() * 2);
  return scales;
}
}  // namespace

std::vector<float> stroke_widths(const cv::Mat& ink) { return widths_at_centres(ink, ink_distance(ink)); }

double stroke_width_percentile(std::vector<float> widths, double share) {
  if (widths.empty()) return 0;
  auto q = widths.begin() + long(std::clamp(share, 0.0, 1.0) * double(widths.size() - 1));
  std::nth_element(widths.begin(), q, widths.end());
  return *q;
}

std::vector<double> auto_line_scales(const cv::Mat& grey) { return scales_for(stroke_widths(drawing_ink(grey))); }

namespace {

// Largest second derivative along a line point's direction, relative to the one across it.
constexpr double kMaxAlongRatio = 0.7;

struct LinePoint {
  float x, y;     // sub-pixel position
  float dx, dy;   // unit direction along the line
  float strength;
  float sigma;    // the scale it was found at
};

// The direction a polyline leaves by at its end `e` (0: front, 1: back), from the last few px.
Vec2 end_direction(const std::vector<Vec2>& c, int e) {
  const size_t n = c.size(), k = std::min<size_t>(n - 1, 4);
  const Vec2 d = e ? c[n - 1] - c[n - 1 - k] : c[0] - c[k];
  const double len = d.norm();
  return len > 0 ? Vec2(d / len) : Vec2(0, 0);
}

// The end of a piece: which piece, which end (0 front, 1 back), where, and its way out.
struct PieceEnd {
  int piece, e;
  Vec2 at, dir;
  double reach;  // px: the gap its line detection leaves at a corner or junction, 2.5 sigma + 1.5
};
// A candidate join of two ends, and its cost (gap plus a penalty for the turn).
struct EndPair {
  double cost;
  int a, b;
};

// Pairs of ends within reach of each other (the smaller of their reaches; through a grid of cell
// `cell`, the largest reach) that face each other and turn by less than ~115 degrees.
std::vector<EndPair> end_pairs(const std::vector<PieceEnd>& ends, const std::vector<std::vector<Vec2>>& pieces, double cell) {
  std::unordered_map<long long, std::vector<int>> grid;
  auto cell_of = [&](double v) { return (long long)std::floor(v / cell); };
  for (size_t k = 0; k < ends.size(); ++k) grid[cell_of(ends[k].at.x()) * 1000003LL + cell_of(ends[k].at.y())].push_back(int(k));
  std::vector<EndPair> cand;
  for (size_t a = 0; a < ends.size(); ++a) {
    const long long gx = cell_of(ends[a].at.x()), gy = cell_of(ends[a].at.y());
    for (long long ox = -1; ox <= 1; ++ox)
      for (long long oy = -1; oy <= 1; ++oy) {
        auto it = grid.find((gx + ox) * 1000003LL + (gy + oy));
        if (it == grid.end()) continue;
        for (int b : it->second) {
          if (b <= int(a)) continue;
          const PieceEnd &A = ends[a], &B = ends[size_t(b)];
          if (A.piece == B.piece && pieces[size_t(A.piece)].size() < 8) continue;  // a speck does not close on itself
          const Vec2 v = B.at - A.at;
          const double gap = v.norm();
          if (gap > std::min(A.reach, B.reach)) continue;
          if (gap > 0.5) {
            const Vec2 u = v / gap;
            if (A.dir.dot(u) < 0.3 || B.dir.dot(-u) < 0.3) continue;  // each end faces the other
          }
          const double turn = std::acos(std::clamp(-A.dir.dot(B.dir), -1.0, 1.0));  // A's way out to B's way in
          if (turn > 2.0) continue;  // sharper than ~115 degrees: not one stroke
          cand.push_back({gap + 2 * turn, int(a), b});
        }
      }
  }
  // Where three or more ends meet (a junction: a T or a Y), the curves end there: the thesis'
  // curves meet at junctions but do not run through them. An end with several candidates keeps
  // the one at most half as costly as its next (a line broken into short pieces, each piece's end
  // facing the next one's across a pixel or two), else it is at a junction.
  std::vector<double> best(ends.size(), 1e300), second(ends.size(), 1e300);
  for (const EndPair& c : cand)
    for (int e : {c.a, c.b}) {
      if (c.cost < best[size_t(e)]) second[size_t(e)] = best[size_t(e)], best[size_t(e)] = c.cost;
      else if (c.cost < second[size_t(e)]) second[size_t(e)] = c.cost;
    }
  auto clear_choice = [&](int e, double cost) { return cost <= best[size_t(e)] && second[size_t(e)] >= 2 * cost; };
  cand.erase(std::remove_if(cand.begin(), cand.end(),
                            [&](const EndPair& c) { return !clear_choice(c.a, c.cost) || !clear_choice(c.b, c.cost); }),
             cand.end());
  std::sort(cand.begin(), cand.end(), [](const EndPair& x, const EndPair& y) { return x.cost < y.cost; });
  return cand;
}

// Line detection fades where lines meet or turn sharply (a corner's profile is no line's), so a
// drawn stroke comes out in pieces whose ends face each other across a gap of about 2 sigma.
// Ends are joined greedily, the cheapest pair first, when the gap is within `join` px and each end
// points towards the other; a piece whose two ends meet is closed. Pieces are concatenated in
// place; `pieces` keeps only the joined results.
void join_pieces(std::vector<std::vector<Vec2>>& pieces, std::vector<float>& sigma) {
  std::vector<PieceEnd> ends;
  double cell = 0;
  for (size_t i = 0; i < pieces.size(); ++i)
    for (int e = 0; e < 2; ++e) {
      ends.push_back({int(i), e, e ? pieces[i].back() : pieces[i].front(), end_direction(pieces[i], e), 2.5 * sigma[i] + 1.5});
      cell = std::max(cell, ends.back().reach);
    }
  const std::vector<EndPair> cand = end_pairs(ends, pieces, cell);
  // Union of pieces: each piece's current owner. Joined ends are interior and never reused, so an
  // unused end of piece i is still an end of the polyline held by find(i), at the same point.
  std::vector<char> used(ends.size(), 0), closed(pieces.size(), 0);
  std::vector<int> owner(pieces.size());
  std::iota(owner.begin(), owner.end(), 0);
  auto find = [&](int i) {
    while (owner[size_t(i)] != i) i = owner[size_t(i)] = owner[size_t(owner[size_t(i)])];
    return i;
  };
  for (const EndPair& c : cand) {
    if (used[size_t(c.a)] || used[size_t(c.b)]) continue;
    const PieceEnd &A = ends[size_t(c.a)], &B = ends[size_t(c.b)];
    const int ra = find(A.piece), rb = find(B.piece);
    auto& pa = pieces[size_t(ra)];
    if (closed[size_t(ra)] || closed[size_t(rb)]) continue;
    const bool a_back = (pa.back() - A.at).norm() < 1e-9, a_front = (pa.front() - A.at).norm() < 1e-9;
    if (ra == rb) {  // both ends of one polyline: close it
      if (!(a_back || a_front)) continue;
      pa.push_back(pa.front());
      closed[size_t(ra)] = 1;
      used[size_t(c.a)] = used[size_t(c.b)] = 1;
      continue;
    }
    auto& pb = pieces[size_t(rb)];
    const bool b_front = (pb.front() - B.at).norm() < 1e-9, b_back = (pb.back() - B.at).norm() < 1e-9;
    if (!(a_back || a_front) || !(b_front || b_back)) continue;
    if (!a_back) std::reverse(pa.begin(), pa.end());  // A's end last
    if (!b_front) std::reverse(pb.begin(), pb.end());  // B's end first
    pa.insert(pa.end(), pb.begin(), pb.end());
    pb.clear();
    sigma[size_t(ra)] = std::max(sigma[size_t(ra)], sigma[size_t(rb)]);
    owner[size_t(rb)] = ra;
    used[size_t(c.a)] = used[size_t(c.b)] = 1;
  }
  size_t kept = 0;
  for (size_t i = 0; i < pieces.size(); ++i)
    if (pieces[i].size() >= 2) {
      if (kept != i) pieces[kept] = std::move(pieces[i]), sigma[kept] = sigma[i];
      ++kept;
    }
  pieces.resize(kept), sigma.resize(kept);
}

// The smoothed image's derivatives (Sobel 3x3, normalised: central differences).
struct Derivatives {
  cv::Mat g, rx, ry, rxx, rxy, ryy;
};
Derivatives derivatives(const cv::Mat& grey, double sigma) {
  Derivatives d;
  cv::GaussianBlur(grey, d.g, cv::Size(0, 0), sigma, sigma, cv::BORDER_REPLICATE);
  cv::Sobel(d.g, d.rx, CV_32F, 1, 0, 3, 1.0 / 8, 0, cv::BORDER_REPLICATE);
  cv::Sobel(d.g, d.ry, CV_32F, 0, 1, 3, 1.0 / 8, 0, cv::BORDER_REPLICATE);
  cv::Sobel(d.g, d.rxx, CV_32F, 2, 0, 3, 1.0 / 4, 0, cv::BORDER_REPLICATE);
  cv::Sobel(d.g, d.ryy, CV_32F, 0, 2, 3, 1.0 / 4, 0, cv::BORDER_REPLICATE);
  cv::Sobel(d.g, d.rxy, CV_32F, 1, 1, 3, 1.0 / 16, 0, cv::BORDER_REPLICATE);
  return d;
}

// Steger's test at pixel (x, y): dark enough, strongly curved across and flat along, with the
// profile's minimum within the pixel. False when (x, y) is not a line point.
bool line_point_at(const Derivatives& d, int x, int y, const LineDetectionParams& p, LinePoint& out) {
  if (d.g.at<float>(y, x) > p.max_intensity) return false;
  // Largest eigenvalue of the Hessian and its eigenvector n (across the line).
  const double a = d.rxx.at<float>(y, x), b = d.rxy.at<float>(y, x), c = d.ryy.at<float>(y, x);
  const double mean = 0.5 * (a + c), disc = std::sqrt(0.25 * (a - c) * (a - c) + b * b);
  const double lambda = mean + disc;
  if (lambda < p.min_strength) return false;
  // Along a line the profile is flat: a dot of stippling (or a blot) curves both ways.
  if (mean - disc > kMaxAlongRatio * lambda) return false;
  double nx, ny;
  if (std::abs(b) > 1e-12)
    nx = b, ny = lambda - a;
  else if (a >= c)
    nx = 1, ny = 0;
  else
    nx = 0, ny = 1;
  const double nn = std::hypot(nx, ny);
  nx /= nn, ny /= nn;
  const double t = -(d.rx.at<float>(y, x) * nx + d.ry.at<float>(y, x) * ny) / lambda;  // to the profile's minimum along n
  if (std::abs(t * nx) > 0.5 || std::abs(t * ny) > 0.5) return false;
  out = {float(x + t * nx), float(y + t * ny), float(-ny), float(nx), float(lambda), float(p.sigma)};
  return true;
}

// The line points, numbered in row order, and the pixel each was found at.
struct LinePoints {
  std::vector<LinePoint> pts;
  std::vector<int> at;  // pixel -> line point index (-1: none)
  int W = 0, H = 0;
};

// The line points of one scale, row by row with their pixel's x, at the pixels whose scale it is
// (`scale_of`: the scale's index per pixel; empty: everywhere).
using RowPoints = std::vector<std::vector<std::pair<int, LinePoint>>>;
void add_line_points(const cv::Mat& grey, const LineDetectionParams& p, const cv::Mat& scale_of, int index, RowPoints& rows) {
  const Derivatives d = derivatives(grey, p.sigma);
#pragma omp parallel for schedule(dynamic, 16)
  for (int y = 0; y < d.g.rows; ++y) {
    LinePoint q;
    for (int x = 0; x < d.g.cols; ++x)
      if ((scale_of.empty() || scale_of.at<uchar>(y, x) == index) && line_point_at(d, x, y, p, q)) rows[size_t(y)].emplace_back(x, q);
  }
}

// Each pixel's scale: the one nearest (in ratio) half the width of the strokes within 2 px of it
// (the ink distance's largest value there), so that a stroke keeps one scale along itself.
cv::Mat scale_index_map(const cv::Mat& dist, const std::vector<double>& scales) {
  cv::Mat width;
  cv::dilate(dist, width, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
  cv::Mat index(dist.size(), CV_8U);
#pragma omp parallel for schedule(static)
  for (int y = 0; y < dist.rows; ++y)
    for (int x = 0; x < dist.cols; ++x) {
      const double half_width = std::max(0.5, width.at<float>(y, x) - 0.25);  // (2 d - 0.5) / 2
      const int k = int(std::lround(std::log2(half_width / scales.front())));
      index.at<uchar>(y, x) = uchar(std::clamp(k, 0, int(scales.size()) - 1));
    }
  return index;
}

// The drawing's ink, its distance to the paper and its stroke widths, computed once for the line
// scales, the shading and the objects' outlines.
struct InkStrokes {
  cv::Mat ink, dist;
  std::vector<float> widths;
};

InkStrokes ink_strokes(const cv::Mat& grey) {
  InkStrokes s{drawing_ink(grey), cv::Mat(), {}};
  s.dist = ink_distance(s.ink);
  s.widths = widths_at_centres(s.ink, s.dist);
  return s;
}

LinePoints detect_line_points(const cv::Mat& grey, const InkStrokes& strokes, const LineDetectionParams& p) {
  std::vector<double> scales{p.sigma};
  cv::Mat scale_of;  // empty: one scale everywhere
  if (p.sigma == 0) {  // automatic: the strokes' widths give the scales and each pixel's
    scales = scales_for(strokes.widths);
    if (scales.size() > 1) scale_of = scale_index_map(strokes.dist, scales);
  }
  RowPoints rows(static_cast<size_t>(grey.rows));
  for (size_t k = 0; k < scales.size(); ++k) {
    LineDetectionParams at = p;
    at.sigma = scales[k];
    at.min_strength = p.min_strength * (kReferenceScale / scales[k]) * (kReferenceScale / scales[k]);  // scale-normalised
    add_line_points(grey, at, scale_of, int(k), rows);
  }
  LinePoints lp;
  lp.W = grey.cols, lp.H = grey.rows;
  lp.at.assign(size_t(lp.W) * lp.H, -1);
  for (int y = 0; y < lp.H; ++y) {
    std::sort(rows[size_t(y)].begin(), rows[size_t(y)].end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [x, q] : rows[size_t(y)]) {
      lp.at[size_t(y) * lp.W + x] = int(lp.pts.size());
      lp.pts.push_back(q);
    }
  }
  return lp;
}

// Linking: from the strongest unused point, the line is followed both ways to the best neighbouring
// point ahead (within the 8-neighbourhood, along the direction, close and turning little).
class Linker {
 public:
  Linker(const LinePoints& lp, const LineDetectionParams& p)
      : lp_(lp), p_(p), chain_of_(lp.pts.size(), -1), cos_turn_(std::cos(p.max_link_turn)) {}

  // The pieces linked from every point, strongest first, and each one's scale (its first point's);
  // junctions met are appended to `junctions`.
  std::vector<std::vector<Vec2>> pieces(std::vector<Vec2>& junctions, std::vector<float>& sigma) {
    const auto& pts = lp_.pts;
    std::vector<int> order(pts.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int i, int j) { return pts[i].strength > pts[j].strength; });
    std::vector<std::vector<Vec2>> out;
    int chains = 0;
    for (int s : order) {
      if (chain_of_[size_t(s)] >= 0) continue;
      const int id = chains++;
      chain_of_[size_t(s)] = id;
      const std::vector<int> ahead = follow(s, 1, id, junctions), behind = follow(s, -1, id, junctions);
      std::vector<Vec2> poly;
      poly.reserve(ahead.size() + behind.size() + 1);
      for (auto it = behind.rbegin(); it != behind.rend(); ++it) poly.push_back(Vec2(pts[*it].x, pts[*it].y));
      poly.push_back(Vec2(pts[s].x, pts[s].y));
      for (int i : ahead) poly.push_back(Vec2(pts[i].x, pts[i].y));
      if (poly.size() >= 2) out.push_back(std::move(poly)), sigma.push_back(pts[size_t(s)].sigma);
    }
    return out;
  }

 private:
  // The points linked from s along `sign` x its direction, in order; a junction ends the way.
  std::vector<int> follow(int s, int sign, int id, std::vector<Vec2>& junctions) {
    const auto& pts = lp_.pts;
    std::vector<int> ext;
    int cur = s;
    double dirx = sign * pts[size_t(s)].dx, diry = sign * pts[size_t(s)].dy;
    for (;;) {
      bool other = false;
      const int n = next_point(cur, dirx, diry, id, other);
      if (n < 0) break;
      if (other) {  // ran into another curve: a junction, this curve ends there
        junctions.push_back(Vec2(pts[size_t(n)].x, pts[size_t(n)].y));
        ext.push_back(n);
        break;
      }
      chain_of_[size_t(n)] = id;
      ext.push_back(n);
      const double ndx = pts[size_t(n)].dx, ndy = pts[size_t(n)].dy;  // keep the orientation continuous
      if (ndx * dirx + ndy * diry >= 0)
        dirx = ndx, diry = ndy;
      else
        dirx = -ndx, diry = -ndy;
      cur = n;
    }
    return ext;
  }

  // The best point ahead of point i along (dirx, diry): unused points first; when only points of
  // other chains are ahead, the nearest of them is returned with `other` set (a junction).
  int next_point(int i, double dirx, double diry, int chain, bool& other) const {
    const LinePoint& q = lp_.pts[size_t(i)];
    const int cx = int(std::lround(q.x)), cy = int(std::lround(q.y));
    int best = -1, best_other = -1;
    double best_cost = 1e300, best_other_cost = 1e300;
    for (int oy = -1; oy <= 1; ++oy)
      for (int ox = -1; ox <= 1; ++ox) {
        const int x = cx + ox, y = cy + oy;
        if ((!ox && !oy) || x < 0 || y < 0 || x >= lp_.W || y >= lp_.H) continue;
        const int j = lp_.at[size_t(y) * lp_.W + x];
        if (j < 0 || j == i || chain_of_[size_t(j)] == chain) continue;
        const LinePoint& r = lp_.pts[size_t(j)];
        const double vx = r.x - q.x, vy = r.y - q.y, dist = std::hypot(vx, vy);
        if (dist > p_.max_link_gap || dist < 1e-6) continue;
        if ((vx * dirx + vy * diry) / dist < 0.5) continue;  // ahead, within 60 degrees
        const double turn = std::abs(r.dx * dirx + r.dy * diry);
        if (turn < cos_turn_) continue;
        const double cost = dist + 2 * (1 - turn);
        if (chain_of_[size_t(j)] < 0) {
          if (cost < best_cost) best_cost = cost, best = j;
        } else if (cost < best_other_cost) {
          best_other_cost = cost, best_other = j;
        }
      }
    other = best < 0 && best_other >= 0;
    return best >= 0 ? best : best_other;
  }

  const LinePoints& lp_;
  const LineDetectionParams& p_;
  std::vector<int> chain_of_;  // which chain a point was linked into
  double cos_turn_;
};

}  // namespace

DrawingCurves extract_drawing_curves(const cv::Mat& image, const LineDetectionParams& p) {
  p.validate();
  DrawingCurves out;
  const cv::Mat grey = drawing_grey(image);
  out.width = grey.cols, out.height = grey.rows;
  const InkStrokes strokes = ink_strokes(grey);
  const LinePoints lp = detect_line_points(grey, strokes, p);
  out.line_points = static_cast<long long>(lp.pts.size());
  std::vector<float> sigma;
  std::vector<std::vector<Vec2>> pieces = Linker(lp, p).pieces(out.junctions, sigma);
  join_pieces(pieces, sigma);
  for (size_t k = 0; k < pieces.size(); ++k) {
    double len = 0;
    for (size_t i = 1; i < pieces[k].size(); ++i) len += (pieces[k][i] - pieces[k][i - 1]).norm();
    if (len < p.min_length) {
      ++out.dropped_short;
      continue;
    }
    out.curves.push_back(std::move(pieces[k]));
    out.line_width.push_back(2.0 * sigma[k]);
  }
  out.shading = p.recognise_shading ? shading_strokes(grey, strokes.ink, out) : std::vector<char>(out.curves.size(), 0);
  out.outline_pieces = close_object_outlines(out, strokes.ink, p.object_gap, stroke_width_percentile(strokes.widths, 0.9));
  return out;
}

}  // namespace reliefkit
