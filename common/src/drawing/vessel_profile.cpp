#include "reliefkit/drawing/vessel_profile.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "reliefkit/base/scale.h"
#include "reliefkit/drawing/line_drawing.h"

namespace reliefkit {

void VesselParams::validate() const {
  if (!std::isnan(axis_x)) require_range(axis_x, "Axis position (px)", -1e7, 1e7);
  require_range(pixel_size, "Pixel size", 1e-12, 1e12);
  require_range(segments, "Segments around the axis", 0, 100000);
  if (segments > 0 && segments < 8) throw InputError("Segments around the axis: at least 8 (or 0 for automatic).");
}

namespace {

// ---- the ink ---------------------------------------------------------------------------------

// The drawing's ink (drawing_ink), refused when blank or mostly dark.
cv::Mat ink_of(const cv::Mat& image) {
  const cv::Mat ink = drawing_ink(drawing_grey(image));
  const double share = cv::countNonZero(ink) / double(ink.total());
  if (share == 0) throw InputError("The drawing holds no ink: the image is blank (or its lines are as light as the paper).");
  if (share > 0.5)
    throw InputError("More than half of the drawing is dark: a vessel profile is read as dark lines on light paper (invert "
                     "a negative, or crop the drawing to the vessel).");
  return ink;
}

// The pen: the 30th percentile of the stroke widths, so that a filled section does not count as a stroke.
double pen_width_of(const cv::Mat& ink) { return std::max(1.0, stroke_width_percentile(stroke_widths(ink), 0.3)); }

// A dash of a dashed wall (join_dashes) is at most this share of the drawing's larger side (or 15 pens).
constexpr double kMaxDashShare = 0.05;

// Ink blobs smaller than `max_side` both ways (stippling, dust, JPEG specks) taken out.
void drop_specks(cv::Mat& ink, int max_side) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(ink, labels, stats, centroids, 8, CV_32S);
  std::vector<uchar> keep(size_t(n), 0);
  for (int l = 1; l < n; ++l)
    keep[size_t(l)] = std::max(stats.at<int>(l, cv::CC_STAT_WIDTH), stats.at<int>(l, cv::CC_STAT_HEIGHT)) >= max_side;
  for (int y = 0; y < ink.rows; ++y)
    for (int x = 0; x < ink.cols; ++x) ink.at<uchar>(y, x) = keep[size_t(labels.at<int>(y, x))] ? 255 : 0;
}

cv::Mat disc(double radius) {
  const int d = 2 * int(std::ceil(radius)) + 1;
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(d, d));
}

// What a vessel drawing must show (require_vessel_drawing): a profile over at least this share of
// the drawing's height, and (axis found) at least this share of mirrored rows.
constexpr double kMinProfileHeightShare = 0.25;
constexpr double kMinMirrorAgreement = 0.6;
// With a drawn axis line the exterior may be drawn carelessly (warned), but not mirror at all.
constexpr double kMinMirrorWithDrawnAxis = 0.25;

// ---- the axis ----------------------------------------------------------------------------------

struct VerticalLine {
  double x = 0;
  int inked = 0;  // rows with ink
};

// The vertical line in column x (a 3-px band) with the most inked rows, gaps of up to max_gap rows
// bridged (a dash-dot axis).
VerticalLine vertical_line_at(const cv::Mat& ink, int x, int max_gap) {
  VerticalLine best{double(x), 0};
  int inked = 0, gap = 0;
  double sum_x = 0;
  for (int y = 0; y <= ink.rows; ++y) {
    int hit = -1;
    for (int dx = -1; y < ink.rows && dx <= 1; ++dx)
      if (ink.at<uchar>(y, x + dx)) hit = x + dx;
    if (hit >= 0) {
      ++inked, sum_x += hit, gap = 0;
    } else if (++gap > max_gap || y == ink.rows) {
      if (inked > best.inked) best = {sum_x / inked, inked};
      inked = 0, sum_x = 0;
    }
  }
  return best;
}

struct InkBox {
  int x0, x1, y0, y1;
  int width() const { return x1 - x0 + 1; }
  int height() const { return y1 - y0 + 1; }
};

InkBox ink_box(const cv::Mat& ink) {
  const cv::Rect r = cv::boundingRect(ink);
  return {r.x, r.x + r.width - 1, r.y, r.y + r.height - 1};
}

// The longest drawn vertical line with its x within [from, to] (nearer `prefer` scored higher,
// by `bias` of its length at `reach` away).
VerticalLine longest_vertical_line(const cv::Mat& ink, const InkBox& box, double from, double to, double prefer, double reach) {
  const int max_gap = std::max(3, int(0.02 * box.height()));
  VerticalLine best;
  double best_score = 0;
  for (int x = std::max(1, int(std::floor(from))); x <= std::min(ink.cols - 2, int(std::ceil(to))); ++x) {
    const VerticalLine line = vertical_line_at(ink, x, max_gap);
    const double score = line.inked * (1 - std::abs(line.x - prefer) / (2 * reach));
    if (score > best_score) best = line, best_score = score;
  }
  return best;
}

// Each row's outermost ink on the left and on the right (-1: none).
struct RowEdges {
  std::vector<int> left, right;
};

RowEdges row_edges(const cv::Mat& ink, const InkBox& box) {
  RowEdges e{std::vector<int>(size_t(ink.rows), -1), std::vector<int>(size_t(ink.rows), -1)};
  for (int y = box.y0; y <= box.y1; ++y) {
    const uchar* row = ink.ptr<uchar>(y);
    for (int x = box.x0; x <= box.x1 && e.left[size_t(y)] < 0; ++x) if (row[x]) e.left[size_t(y)] = x;
    for (int x = box.x1; x >= box.x0 && e.right[size_t(y)] < 0; --x) if (row[x]) e.right[size_t(y)] = x;
  }
  return e;
}

// Whether row y's outermost inks on the left and the right are one stroke (a section filled
// across, a base): such a row says nothing of where the drawing mirrors.
bool one_stroke_across(const cv::Mat& ink, const RowEdges& e, size_t y) {
  const uchar* row = ink.ptr<uchar>(int(y));
  int x = e.left[y];
  while (x < e.right[y] && row[x + 1]) ++x;
  return x >= e.right[y];
}

// The line about which the rows' outer edges mirror: the most common midpoint of a row's outermost
// ink (rows wider than four pens, not one stroke across), within a window of two pens or 1 % of the width.
double mirror_line(const cv::Mat& ink, const RowEdges& e, const InkBox& box, double pen) {
  const int bins = 2 * box.width();
  std::vector<double> count(size_t(bins), 0);
  for (size_t y = 0; y < e.left.size(); ++y)
    if (e.left[y] >= 0 && e.right[y] - e.left[y] >= 4 * pen && !one_stroke_across(ink, e, y))
      count[size_t(e.left[y] + e.right[y] - 2 * box.x0)] += 1;
  const int window = int(std::ceil(2 * std::max(2 * pen, 0.01 * box.width())));
  double best = -1, sum = 0;
  int mode = bins / 2;
  for (int b = 0; b < bins; ++b) {
    sum = 0;
    for (int k = std::max(0, b - window); k <= std::min(bins - 1, b + window); ++k) sum += count[size_t(k)];
    if (sum > best) best = sum, mode = b;
  }
  double weighted = 0, total = 0;
  for (int k = std::max(0, mode - window); k <= std::min(bins - 1, mode + window); ++k) weighted += k * count[size_t(k)], total += count[size_t(k)];
  return box.x0 + 0.5 * (total > 0 ? weighted / total : mode);
}

double mirror_agreement(const cv::Mat& ink, double axis, const InkBox& box);

// Whether the vertical line at x is a pen line (an axis), not a painted band or a filled wall: in half
// of the rows it is inked (bands painted across it aside), the ink across it is at most three pens
// (+ 2 px) wide.
bool thin_line(const cv::Mat& ink, double x, double pen) {
  const int c = int(std::lround(x)), widest = int(3 * pen + 2);
  long rows = 0, thin = 0;
  for (int y = 0; y < ink.rows; ++y) {
    const uchar* row = ink.ptr<uchar>(y);
    if (c < 0 || c >= ink.cols || !row[c]) continue;
    int a = c, b = c;
    while (a > 0 && row[a - 1] && c - a <= widest) --a;
    while (b + 1 < ink.cols && row[b + 1] && b - c <= widest) ++b;
    ++rows, thin += b - a + 1 <= widest;
  }
  return rows > 0 && thin >= 0.5 * double(rows);
}

// The axis: where the outer edges mirror (at a drawn vertical line there, if any); else the longest
// drawn vertical line in the middle half of the drawn width (nearer the middle preferred), at least
// 4 % of the drawing's height; else that middle. Returns the drawn line's inked rows (0: none).
int place_axis(const cv::Mat& ink, const InkBox& box, VesselProfile& p) {
  const int min_rows = int(std::max(10.0, 0.04 * box.height()));
  const double mirror = mirror_line(ink, row_edges(ink, box), box, p.pen_width);
  if (mirror_agreement(ink, mirror, box) >= kMinMirrorAgreement) {
    const double near = std::max(3 * p.pen_width, 0.015 * box.width());
    const VerticalLine line = longest_vertical_line(ink, box, mirror - near, mirror + near, mirror, 2 * near);
    if (line.inked >= std::max(double(min_rows), 0.1 * box.height()) && thin_line(ink, line.x, p.pen_width)) {
      p.axis_x = line.x, p.axis_source = VesselAxisSource::DrawnLine;
      return line.inked;
    }
    p.axis_x = mirror, p.axis_source = VesselAxisSource::MirroredEdges;
    return 0;
  }
  const double mid = 0.5 * (box.x0 + box.x1), reach = 0.25 * box.width();
  const VerticalLine line = longest_vertical_line(ink, box, mid - reach, mid + reach, mid, reach);
  if (line.inked >= min_rows && thin_line(ink, line.x, p.pen_width)) {
    p.axis_x = line.x, p.axis_source = VesselAxisSource::DrawnLine;
    return line.inked;
  }
  p.axis_x = mid, p.axis_source = VesselAxisSource::MiddleOfDrawing;
  return 0;
}

// ---- the vessel's piece ---------------------------------------------------------------------

// A frame round a figure: a piece spanning at least half the image both ways whose ink lies along
// its box's border.
bool is_frame(const cv::Mat& labels, const cv::Mat& ink, int label, const cv::Rect& box, double pen) {
  if (box.width < 0.5 * labels.cols || box.height < 0.5 * labels.rows) return false;
  const int band = int(std::ceil(2 * pen)) + 1;
  long inked = 0, along = 0;
  for (int y = box.y; y < box.y + box.height; ++y)
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (!ink.at<uchar>(y, x) || labels.at<int>(y, x) != label) continue;
      ++inked;
      along += std::min({x - box.x, box.x + box.width - 1 - x, y - box.y, box.y + box.height - 1 - y}) < band;
    }
  return inked > 0 && along >= 0.9 * double(inked);
}

cv::Rect label_box(const cv::Mat& stats, int l) {
  return {stats.at<int>(l, cv::CC_STAT_LEFT), stats.at<int>(l, cv::CC_STAT_TOP), stats.at<int>(l, cv::CC_STAT_WIDTH),
          stats.at<int>(l, cv::CC_STAT_HEIGHT)};
}

// The drawing's connected pieces (dashes and gaps of two pens joined): labels, ink and box of each.
struct Pieces {
  cv::Mat labels;
  std::vector<long> inked;
  std::vector<cv::Rect> box;
};

Pieces pieces_of(const cv::Mat& ink, double pen) {
  Pieces pc;
  cv::Mat joined, stats, centroids;
  cv::morphologyEx(ink, joined, cv::MORPH_CLOSE, disc(2 * pen + 1));
  const int n = cv::connectedComponentsWithStats(joined, pc.labels, stats, centroids, 8, CV_32S);
  pc.inked.assign(size_t(n), 0);
  for (int y = 0; y < ink.rows; ++y)
    for (int x = 0; x < ink.cols; ++x) pc.inked[size_t(pc.labels.at<int>(y, x))] += ink.at<uchar>(y, x) != 0;
  for (int l = 0; l < n; ++l) pc.box.push_back(label_box(stats, l));
  pc.inked[0] = 0;
  return pc;
}

double quantile_of(std::vector<double> v, double q) {
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

double median_of(const std::vector<double>& v) { return quantile_of(v, 0.5); }

int rows_in_common(const cv::Rect& a, const cv::Rect& b) { return std::min(a.y + a.height, b.y + b.height) - std::max(a.y, b.y); }

// Whether the outer edges of two pieces side by side mirror about one vertical line over their
// common rows (a section drawn apart from the exterior's outline): the midpoints of the left
// piece's leftmost and the right piece's rightmost ink spread (interquartile) by at most two pens
// or 1 % of the width they span, and lie between the two.
bool mirrored_pieces(const Pieces& pc, int a, int b, double pen) {
  if (pc.box[size_t(a)].x > pc.box[size_t(b)].x) std::swap(a, b);
  const cv::Rect &A = pc.box[size_t(a)], &B = pc.box[size_t(b)];
  std::vector<double> mids, inner_a, inner_b;  // per common row: the midpoint, A's rightmost, B's leftmost ink
  for (int y = std::max(A.y, B.y); y < std::min(A.y + A.height, B.y + B.height); ++y) {
    const int* row = pc.labels.ptr<int>(y);
    int a0 = -1, a1 = -1, b0 = -1, b1 = -1;
    for (int x = A.x; x < A.x + A.width; ++x) if (row[x] == a) a1 = x, a0 = a0 < 0 ? x : a0;
    for (int x = B.x; x < B.x + B.width; ++x) if (row[x] == b) b1 = x, b0 = b0 < 0 ? x : b0;
    if (a0 >= 0 && b0 >= 0) mids.push_back(0.5 * (a0 + b1)), inner_a.push_back(a1), inner_b.push_back(b0);
  }
  if (mids.size() < 0.5 * std::min(A.height, B.height) || mids.size() < 10) return false;
  const double line = median_of(mids), spread = quantile_of(mids, 0.75) - quantile_of(mids, 0.25);
  // The axis lies between the two (a section, then its exterior), not inside either.
  const bool between = median_of(inner_a) <= line + 2 * pen && median_of(inner_b) >= line - 2 * pen;
  return between && spread <= std::max(2 * pen, 0.01 * (B.x + B.width - A.x));
}

// A piece with the pieces drawn with it: those lying beside it over half their height (a sherd's
// number, the section touching it), those whose outer edge mirrors its own (a section drawn apart
// from the exterior's outline), then those within the extent so found (sherds drawn inside the
// outline, the axis). `agreement`: how well the group's outer edges mirror (mirror_agreement).
struct PieceGroup {
  int main = 0;
  std::vector<uchar> keep;
  cv::Rect box;
  cv::Mat ink;
  double agreement = 0;
};

PieceGroup group_round(const Pieces& pc, const std::vector<uchar>& skip, int main, const cv::Mat& ink, double pen) {
  const int n = int(pc.box.size());
  PieceGroup g{main, std::vector<uchar>(size_t(n), 0), pc.box[size_t(main)], cv::Mat(), 0};
  g.keep[size_t(main)] = 1;
  const cv::Rect m = pc.box[size_t(main)];
  const int slack = int(0.02 * m.width) + 1;
  const cv::Rect reach(m.x - slack, m.y, m.width + 2 * slack, m.height);
  for (int pass = 0; pass < 2; ++pass)
    for (int l = 1; l < n; ++l) {
      const cv::Rect& b = pc.box[size_t(l)];
      if (skip[size_t(l)] || g.keep[size_t(l)] || rows_in_common(b, m) < 0.5 * b.height) continue;
      const bool partner = b.height >= 0.25 * m.height && mirrored_pieces(pc, main, l, pen);  // not a dash
      const bool attach = pass == 0 ? (b & reach).area() > 0 || partner
                                    : b.x >= g.box.x && b.x + b.width <= g.box.x + g.box.width;
      if (attach) g.keep[size_t(l)] = 1, g.box |= b;
    }
  g.ink = cv::Mat::zeros(ink.size(), CV_8U);
  for (int y = g.box.y; y < g.box.y + g.box.height; ++y)
    for (int x = g.box.x; x < g.box.x + g.box.width; ++x)
      g.ink.at<uchar>(y, x) = g.keep[size_t(pc.labels.at<int>(y, x))] ? ink.at<uchar>(y, x) : 0;
  const InkBox box = ink_box(g.ink);
  g.agreement = mirror_agreement(g.ink, mirror_line(g.ink, row_edges(g.ink, box), box, pen), box);
  return g;
}

// The vessel's piece of the drawing, candidates best first: the groups round the five largest
// pieces (by extent, not ink: a sherd painted black beside its vessel has more), ranked by how well
// their outer edges mirror, weighed by their extent. What each leaves out is counted — a frame, a
// base section drawn apart below, labels, other vessels (a quarter of its height and a tenth of its
// width or more).
struct VesselPiece {
  cv::Mat ink;
  cv::Rect box;
  int left_out = 0, other_vessels = 0;
};

std::vector<VesselPiece> vessel_pieces(const cv::Mat& ink, double pen, bool& frame_left_out) {
  const Pieces pc = pieces_of(ink, pen);
  const int n = int(pc.box.size());
  std::vector<uchar> skip(size_t(n), 0);
  std::vector<int> order;
  for (int l = 1; l < n; ++l) {
    skip[size_t(l)] = pc.inked[size_t(l)] == 0;
    if (!skip[size_t(l)] && is_frame(pc.labels, ink, l, pc.box[size_t(l)], pen)) frame_left_out = true, skip[size_t(l)] = 1;
    if (!skip[size_t(l)]) order.push_back(l);
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) { return pc.box[size_t(a)].area() > pc.box[size_t(b)].area(); });
  std::vector<std::pair<double, VesselPiece>> ranked;
  for (size_t k = 0; k < std::min<size_t>(5, order.size()); ++k) {
    const PieceGroup g = group_round(pc, skip, order[k], ink, pen);
    VesselPiece piece{g.ink, g.box};
    const cv::Rect m = pc.box[size_t(g.main)];
    for (int l = 1; l < n; ++l) {
      if (skip[size_t(l)] || g.keep[size_t(l)]) continue;
      ++piece.left_out;
      if (pc.box[size_t(l)].height >= 0.25 * m.height && pc.box[size_t(l)].width >= 0.1 * m.width) ++piece.other_vessels;
    }
    ranked.emplace_back((g.agreement >= kMinMirrorAgreement ? 1.0 : 0.1) * g.agreement * g.box.area(), std::move(piece));
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<VesselPiece> out;
  for (auto& r : ranked) out.push_back(std::move(r.second));
  return out;
}

// ---- the section -------------------------------------------------------------------------------

struct Candidate {
  cv::Mat mask;  // the region within `box`
  cv::Rect box;  // in the image
  VesselSectionKind kind = VesselSectionKind::Outlined;
  VesselSide side = VesselSide::Left;
  double weight = 1;     // of its rows in the score (a section read row by row weighs less than a region)
  double outer = 0;      // rows in which it is the drawing's outer edge on its side, weighted
  double thinness = 0;   // its boundary along the outer paper over its thickness
  double score = 0;      // > 0: it qualifies
};

struct SectionScene {
  const cv::Mat& raw_ink;      // as thresholded
  const cv::Mat& ink;          // specks dropped, gaps closed
  cv::Mat paper_dist;          // distance to the paper around the vessel
  double axis_x, pen;
  VesselSide wanted;
  RowEdges edges;              // per row: the outermost ink left and right of the axis (-1: none)
  long side_rows[2] = {0, 0};  // rows inked left, right of the axis
  cv::Mat ink_dist;            // distance from within the ink to the paper (half a stroke's thickness)
};

// The outermost ink of each row on either side of the axis (beyond two pixels of it).
RowEdges edges_about(const cv::Mat& ink, double axis) {
  const int a = int(std::lround(axis));
  RowEdges e{std::vector<int>(size_t(ink.rows), -1), std::vector<int>(size_t(ink.rows), -1)};
  for (int y = 0; y < ink.rows; ++y) {
    const uchar* row = ink.ptr<uchar>(y);
    for (int x = 0; x < a - 2 && e.left[size_t(y)] < 0; ++x) if (row[x]) e.left[size_t(y)] = x;
    for (int x = ink.cols - 1; x > a + 2 && e.right[size_t(y)] < 0; --x) if (row[x]) e.right[size_t(y)] = x;
  }
  return e;
}

SectionScene section_scene(const cv::Mat& raw_ink, const cv::Mat& ink, const cv::Mat& paper_dist, double axis, double pen,
                           VesselSide wanted) {
  SectionScene s{raw_ink, ink, paper_dist, axis, pen, wanted, edges_about(ink, axis), {0, 0}, cv::Mat()};
  cv::distanceTransform(ink, s.ink_dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  for (size_t y = 0; y < s.edges.left.size(); ++y) s.side_rows[0] += s.edges.left[y] >= 0, s.side_rows[1] += s.edges.right[y] >= 0;
  return s;
}

// Rows in which the region holds the outermost ink on its side (within a pen): a wall's section
// is the vessel's outer edge on its side of the drawing.
long outer_rows(const SectionScene& s, const Candidate& c) {
  const std::vector<int>& edge = c.side == VesselSide::Left ? s.edges.left : s.edges.right;
  const int reach = int(std::ceil(s.pen)) + 1;
  long rows = 0;
  for (int y = 0; y < c.mask.rows; ++y) {
    const int e = edge[size_t(c.box.y + y)] - c.box.x;
    if (e + reach < 0 || e - reach >= c.mask.cols || edge[size_t(c.box.y + y)] < 0) continue;
    const uchar* row = c.mask.ptr<uchar>(y);
    bool holds = false;
    for (int x = std::max(0, e - reach); x <= std::min(c.mask.cols - 1, e + reach) && !holds; ++x) holds = row[x] != 0;
    rows += holds;
  }
  return rows;
}

// A wall is thin: its thickness at most this share of its boundary along the outer paper (sections
// are thicker at the rim or foot, as the shared bowl's lip; the bowl's exterior sherd and a jar's
// exterior half drawn as a closed region are thicker than this: VesselProfile.* read them so).
constexpr double kMaxThicknessShare = 0.1;
// A section filled black is a section by the drawing's convention (an exterior half is not filled):
// a short thick rim sherd's section is thicker than a wall, up to this share.
constexpr double kMaxFilledThicknessShare = 0.25;


// Scores a region: on one side of the axis, the rows in which it is the drawing's outer edge on
// that side (at least a quarter of the side's inked rows); 0 when it does not qualify (a wall is
// thin: its thickness at most a tenth of its boundary along the outer paper).
void score_candidate(const SectionScene& s, Candidate& c) {
  const cv::Mat& m = c.mask;
  long left = 0, right = 0;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x)
      if (m.at<uchar>(y, x)) (c.box.x + x < s.axis_x ? left : right)++;
  c.side = left >= right ? VesselSide::Left : VesselSide::Right;
  if (std::min(left, right) > 0.05 * double(left + right)) return;
  if (s.wanted != VesselSide::Auto && c.side != s.wanted) return;
  cv::Mat padded, dist, inner;
  cv::copyMakeBorder(m, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, 0);
  cv::distanceTransform(padded, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  double max_radius = 0;
  cv::minMaxLoc(dist, nullptr, &max_radius);
  cv::erode(padded, inner, cv::Mat());
  long contact = 0;
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x)
      if (padded.at<uchar>(y + 1, x + 1) && !inner.at<uchar>(y + 1, x + 1) &&
          s.paper_dist.at<float>(c.box.y + y, c.box.x + x) <= s.pen + 2)
        ++contact;
  const long outer = outer_rows(s, c), side_rows = s.side_rows[c.side == VesselSide::Left ? 0 : 1];
  c.outer = double(outer) * c.weight, c.thinness = contact / std::max(1.0, 2 * max_radius);
  const double max_share = c.kind == VesselSectionKind::Filled ? kMaxFilledThicknessShare : kMaxThicknessShare;
  if (outer >= std::max(10.0, 0.25 * double(side_rows)) && 2 * max_radius <= max_share * contact) c.score = c.outer;
}

// The labelled regions of `labels` (their stats) that are large enough, each as a candidate: the
// region grown by `grow` px (within the image).
template <class Visit>
void for_each_region(const cv::Mat& labels, const cv::Mat& stats, double min_area, double grow, Visit visit) {
  const int g = int(std::ceil(grow)) + 1;
  const cv::Rect image(0, 0, labels.cols, labels.rows);
  for (int l = 1; l < stats.rows; ++l) {
    if (stats.at<int>(l, cv::CC_STAT_AREA) < min_area) continue;
    Candidate c;
    c.box = cv::Rect(stats.at<int>(l, cv::CC_STAT_LEFT) - g, stats.at<int>(l, cv::CC_STAT_TOP) - g,
                     stats.at<int>(l, cv::CC_STAT_WIDTH) + 2 * g, stats.at<int>(l, cv::CC_STAT_HEIGHT) + 2 * g) & image;
    c.mask = labels(c.box) == l;
    if (grow > 0) cv::dilate(c.mask, c.mask, disc(grow));
    visit(c, l);
  }
}

// The better of two qualifying regions: the one that is the outer edge over clearly more rows (5 %),
// else the thinner along the outer paper (a wall's section, not the region round it).
void keep_best(Candidate& c, Candidate& best) {
  if (c.score <= 0) return;
  const bool more_rows = c.outer > 1.05 * best.outer, fewer_rows = best.outer > 1.05 * c.outer;
  if (best.score <= 0 || more_rows || (!fewer_rows && c.thinness > best.thinness)) best = c;
}

// A region whose boundary is the outer edge of its outline moved to the outline's centre: eroded
// by half a pen (which keeps its corners sharp), then 1-px spurs of other strokes opened away.
void to_outline_centre(cv::Mat& mask, double pen) {
  cv::erode(mask, mask, disc(0.5 * pen - 0.5));
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, cv::Mat());
}

// Outlined sections: the closed blank cells (not the outer paper), each with the strokes around it
// (the ink within two pen widths), then brought to the strokes' centres.
void outlined_candidates(const SectionScene& s, const cv::Mat& cells, const cv::Mat& stats, const std::vector<uchar>& outer,
                         Candidate& best) {
  cv::Mat inner_stats = stats.clone();
  for (int l = 1; l < stats.rows; ++l)
    if (outer[size_t(l)]) inner_stats.at<int>(l, cv::CC_STAT_AREA) = 0;
  for_each_region(cells, inner_stats, 9 * s.pen * s.pen, 2 * s.pen + 1, [&](Candidate& c, int label) {
    c.mask &= (cells(c.box) == label) | s.ink(c.box);
    to_outline_centre(c.mask, s.pen);
    score_candidate(s, c);
    keep_best(c, best);
  });
}

// Filled and hatched sections: what stays of the ink, its hatching closed, after an opening wider
// than a pen stroke. Filled when ink covers 80 % of it.
void solid_candidates(const SectionScene& s, Candidate& best) {
  cv::Mat closed, solid, labels, stats, centroids;
  cv::morphologyEx(s.ink, closed, cv::MORPH_CLOSE, disc(2.5 * s.pen));
  cv::morphologyEx(closed, solid, cv::MORPH_OPEN, disc(1.5 * s.pen));
  cv::connectedComponentsWithStats(solid, labels, stats, centroids, 8, CV_32S);
  for_each_region(labels, stats, 9 * s.pen * s.pen, 1.5 * s.pen + 1, [&](Candidate& c, int) {
    c.mask &= closed(c.box);  // the blob with its corners, which the opening rounded
    cv::morphologyEx(c.mask, c.mask, cv::MORPH_OPEN, cv::Mat());
    const double inked = cv::countNonZero(c.mask & s.raw_ink(c.box)) / double(cv::countNonZero(c.mask));
    c.kind = inked >= 0.8 ? VesselSectionKind::Filled : VesselSectionKind::Hatched;
    if (c.kind == VesselSectionKind::Hatched) to_outline_centre(c.mask, s.pen);
    score_candidate(s, c);
    keep_best(c, best);
  });
}

// A section read row by row, for walls whose outline is not closed (a dashed or broken line, a
// section touching its decoration): from the outermost ink on the side inwards, a stroke thicker
// than three pens (+ 2 px) is a filled wall; a thin one followed, within a third of the radius, by a second stroke
// is an outlined wall (to that stroke's inner edge). The longest run of such rows (gaps of two pens
// bridged), its inner edge a running median of five rows, filled as one region.
constexpr double kMinWallPens = 3;  // a wall read row by row is at least this many pens (+ 2 px) thick

struct WallRow {
  int y, outer, inner;
  bool filled;
};

std::vector<WallRow> wall_rows(const SectionScene& s, VesselSide side) {
  const std::vector<int>& edge = side == VesselSide::Left ? s.edges.left : s.edges.right;
  const int dir = side == VesselSide::Left ? 1 : -1, axis = int(std::lround(s.axis_x));
  const double min_wall = kMinWallPens * s.pen + 2;  // the closing of the ink thickens a line by up to 2 px
  std::vector<WallRow> rows;
  for (int y = 0; y < s.ink.rows; ++y) {
    const int e = edge[size_t(y)];
    if (e < 0) continue;
    const uchar* row = s.ink.ptr<uchar>(y);
    auto inside = [&](int x) { return dir * (axis - x) > s.pen && x >= 0 && x < s.ink.cols; };
    int x = e;
    float thickest = 0;  // half the stroke's thickness across it (a slanted line's run is longer)
    for (thickest = s.ink_dist.at<float>(y, x); inside(x + dir) && row[x + dir]; x += dir)
      thickest = std::max(thickest, s.ink_dist.at<float>(y, x + dir));
    if (2 * thickest >= min_wall) { rows.push_back({y, e, x, true}); continue; }
    const int limit = int(std::abs(axis - e) / 3.0);
    int g = x + dir;
    while (inside(g) && !row[g] && std::abs(g - e) <= limit) g += dir;
    if (!inside(g) || !row[g] || std::abs(g - e) > limit) continue;
    while (inside(g + dir) && row[g + dir]) g += dir;
    rows.push_back({y, e, g, false});
  }
  return rows;
}

void scanline_candidate(const SectionScene& s, VesselSide side, Candidate& best) {
  const std::vector<WallRow> all = wall_rows(s, side);
  size_t from = 0, best_from = 0, best_to = 0;  // the longest run, [best_from, best_to)
  for (size_t i = 1; i <= all.size(); ++i)
    if (i == all.size() || all[i].y - all[i - 1].y > 2 * s.pen + 1) {
      if (i - from > best_to - best_from) best_from = from, best_to = i;
      from = i;
    }
  if (best_to - best_from < 10) return;
  std::vector<int> widths;
  for (size_t i = best_from; i < best_to; ++i) widths.push_back(std::abs(all[i].inner - all[i].outer));
  std::nth_element(widths.begin(), widths.begin() + long(widths.size() / 2), widths.end());
  if (widths[widths.size() / 2] < kMinWallPens * s.pen + 2) return;  // a wall, not one line
  std::vector<cv::Point> outline;
  long filled = 0;
  for (size_t i = best_from; i < best_to; ++i) outline.emplace_back(all[i].outer, all[i].y), filled += all[i].filled;
  for (size_t i = best_to; i-- > best_from;) {
    std::vector<int> near;
    for (size_t k = std::max(best_from, i >= 2 ? i - 2 : 0); k < std::min(best_to, i + 3); ++k) near.push_back(all[k].inner);
    std::nth_element(near.begin(), near.begin() + long(near.size() / 2), near.end());
    outline.emplace_back(near[near.size() / 2], all[i].y);
  }
  Candidate c;
  c.box = cv::boundingRect(outline) & cv::Rect(0, 0, s.ink.cols, s.ink.rows);
  c.mask = cv::Mat::zeros(c.box.size(), CV_8U);
  for (cv::Point& q : outline) q -= c.box.tl();
  cv::fillPoly(c.mask, std::vector<std::vector<cv::Point>>{outline}, cv::Scalar(255));
  c.kind = 2 * filled >= long(best_to - best_from) ? VesselSectionKind::Filled : VesselSectionKind::Outlined;
  if (c.kind == VesselSectionKind::Outlined) to_outline_centre(c.mask, s.pen);
  c.weight = 0.95;
  score_candidate(s, c);
  keep_best(c, best);
}

// The paper around the vessel: the blank cells that touch the image's border (flagged in `outer`).
cv::Mat outer_paper(const cv::Mat& cells, int n, std::vector<uchar>& outer) {
  outer.assign(size_t(n), 0);
  for (int x = 0; x < cells.cols; ++x) outer[size_t(cells.at<int>(0, x))] = outer[size_t(cells.at<int>(cells.rows - 1, x))] = 1;
  for (int y = 0; y < cells.rows; ++y) outer[size_t(cells.at<int>(y, 0))] = outer[size_t(cells.at<int>(y, cells.cols - 1))] = 1;
  outer[0] = 0;  // label 0 is the ink
  cv::Mat paper(cells.size(), CV_8U);
  for (int y = 0; y < cells.rows; ++y)
    for (int x = 0; x < cells.cols; ++x) paper.at<uchar>(y, x) = outer[size_t(cells.at<int>(y, x))] ? 255 : 0;
  return paper;
}

std::vector<Vec2> largest_contour(const cv::Mat& mask) {
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  size_t best = 0;
  for (size_t i = 1; i < contours.size(); ++i)
    if (cv::contourArea(contours[i]) > cv::contourArea(contours[best])) best = i;
  std::vector<Vec2> out;
  for (const cv::Point& q : contours.at(best)) out.emplace_back(q.x, q.y);
  return out;
}

// A profile drawn as one line: per row, the outermost ink on the side; the base closed on the axis
// when the lowest row's ink reaches it.
bool profile_line(const cv::Mat& ink, VesselSide side, VesselProfile& p) {
  const int reach = int(std::ceil(p.pen_width)) + 1, axis = int(std::lround(p.axis_x));
  std::vector<Vec2> wall;
  bool base_closed = false;
  for (int y = 0; y < ink.rows; ++y) {
    const uchar* row = ink.ptr<uchar>(y);
    int outer = -1;
    if (side == VesselSide::Left) {
      for (int x = 0; x < axis - reach && outer < 0; ++x) if (row[x]) outer = x;
    } else {
      for (int x = ink.cols - 1; x > axis + reach && outer < 0; --x) if (row[x]) outer = x;
    }
    if (outer < 0) continue;
    wall.emplace_back(outer, y);
    const int from = std::min(outer, axis - reach), to = std::max(outer, axis + reach);
    base_closed = cv::countNonZero(ink.row(y).colRange(std::max(0, from), std::min(ink.cols, to + 1))) >= to - from - reach;
  }
  if (wall.size() < 10) return false;
  if (base_closed) wall.emplace_back(p.axis_x, wall.back().y());
  p.outline = std::move(wall), p.closed = false, p.kind = VesselSectionKind::ProfileLine, p.side = side;
  return true;
}

// The share of ink between a profile line and the axis (beyond two pens from either): a vessel's
// outline encloses blank paper or a band of decoration, a tablet or a figure is dense with lines.
double ink_inside_profile(const cv::Mat& ink, const VesselProfile& p) {
  const double margin = 2 * p.pen_width + 1;
  long inside = 0, inked = 0;
  for (const Vec2& q : p.outline) {
    const int y = int(q.y());
    const double from = std::min(q.x(), p.axis_x) + margin, to = std::max(q.x(), p.axis_x) - margin;
    for (int x = int(std::ceil(from)); x <= int(std::floor(to)); ++x) ++inside, inked += ink.at<uchar>(y, x) != 0;
  }
  return inside ? double(inked) / double(inside) : 0;
}

constexpr double kMaxInkInsideProfile = 0.2;

// ---- is it a vessel? -------------------------------------------------------------------------

// Per row of the drawing: -1 when it is not inked on both sides of the axis, else whether its
// outermost ink lies at the same distance from the axis on the left and on the right (within 5 %
// of the drawn half-width): a half-section's exterior mirrors its section's outer wall.
std::vector<int> mirrored_rows_of(const cv::Mat& ink, double axis, const InkBox& box) {
  const double tolerance = 0.05 * std::max(axis - box.x0, box.x1 - axis);
  const int a = int(std::lround(axis));
  std::vector<int> state(size_t(ink.rows), -1);
  for (int y = box.y0; y <= box.y1; ++y) {
    const uchar* row = ink.ptr<uchar>(y);
    int left = -1, right = -1;
    for (int x = box.x0; x < a - 2 && left < 0; ++x) if (row[x]) left = x;
    for (int x = box.x1; x > a + 2 && right < 0; --x) if (row[x]) right = x;
    if (left >= 0 && right >= 0) state[size_t(y)] = std::abs((axis - left) - (right - axis)) <= tolerance;
  }
  return state;
}

// The share of the rows inked on both sides that mirror about the axis (mirrored_rows_of's states).
double agreement_of(const std::vector<int>& state) {
  long rows = 0, agree = 0;
  for (int s : state) rows += s >= 0, agree += s == 1;
  return rows ? double(agree) / double(rows) : 0;
}

double mirror_agreement(const cv::Mat& ink, double axis, const InkBox& box) {
  return agreement_of(mirrored_rows_of(ink, axis, box));
}

// The share of the mirrored rows (where the exterior is drawn on both sides) the profile spans.
double coverage_of(const std::vector<int>& state, const VesselProfile& p) {
  long mirrored = 0, spanned = 0;
  for (size_t y = 0; y < state.size(); ++y)
    if (state[y] == 1) ++mirrored, spanned += double(y) >= p.top_y - p.pen_width && double(y) <= p.bottom_y + p.pen_width;
  return mirrored ? double(spanned) / double(mirrored) : 1.0;
}

std::string percent(double share) { return std::to_string(int(std::lround(100 * share))) + " %"; }

// Whether a line is drawn across the vessel near the profile's top (the mouth: the rim line of a
// half-section, crossing the axis): in a band of rows (two pens: a line drawn by hand, or broken by a
// sherd's edge, wavers) within the top tenth of the profile, ink over 70 % of the stretch within 30 %
// of the widest radius of the axis, or over 60 % of a stretch across the axis of at least 40 % of
// the widest diameter (a rim line broken by sherds drawn on it).
bool rim_line_across(const cv::Mat& ink, const VesselProfile& p) {
  const int a = int(std::lround(p.axis_x)), near = int(0.3 * p.max_radius), band = int(std::ceil(2 * p.pen_width)) + 2;
  const int y0 = std::max(0, int(p.top_y - 2 * p.pen_width)), y1 = std::min(ink.rows - 1, int(p.top_y + 0.1 * (p.bottom_y - p.top_y)));
  if (near < 2) return false;
  for (int y = y0; y <= y1; ++y) {
    cv::Mat across;
    cv::reduce(ink.rowRange(y, std::min(ink.rows, y + band)), across, 0, cv::REDUCE_MAX);
    const int lo = std::max(0, a - near), hi = std::min(ink.cols - 1, a + near);
    if (cv::countNonZero(across.colRange(lo, hi + 1)) >= 0.7 * (2 * near + 1)) return true;
    int first = -1, last = -1;
    for (int x = 0; x < across.cols; ++x)
      if (across.at<uchar>(0, x)) last = x, first = first < 0 ? x : first;
    if (first < a && last > a && last - first >= 0.8 * p.max_radius &&
        cv::countNonZero(across.colRange(first, last + 1)) >= 0.6 * (last - first + 1))
      return true;
  }
  return false;
}

// A vessel's profile runs over a good part of its drawing, and a drawing in the half-section
// convention is symmetric about its axis and marks it — an axis line, or the rim line across the
// mouth (checked when the axis was found, not given; a drawn axis line over 80 % of the profile's
// height is taken even when the exterior is not drawn to mirror it — vessel_log_lines warns). Throws InputError saying what was found otherwise: the drawing is not a
// pottery profile.
void require_vessel_drawing(VesselProfile& p, const cv::Mat& ink, const InkBox& box, bool axis_given, int drawn_axis_rows) {
  const double spans = (p.bottom_y - p.top_y) / std::max(1, box.height());
  if (spans < kMinProfileHeightShare)
    throw InputError("The vessel profile found spans " + percent(spans) + " of the drawing's height (" +
                     std::to_string(int(p.bottom_y - p.top_y)) + " of " + std::to_string(box.height()) +
                     " px): the drawing does not look like a vessel's half-section. Crop it to one vessel, or give the "
                     "axis position and the section side.");
  const std::vector<int> state = mirrored_rows_of(ink, p.axis_x, box);  // one scan for both figures
  p.mirrored_rows = agreement_of(state);
  p.profile_coverage = coverage_of(state, p);
  const bool drawn_axis = drawn_axis_rows >= 0.8 * (p.bottom_y - p.top_y);
  if (axis_given) return;
  if (drawn_axis) {
    const long both_sides = std::count_if(state.begin(), state.end(), [](int s) { return s >= 0; });
    if (both_sides < 0.25 * (p.bottom_y - p.top_y) || p.mirrored_rows >= kMinMirrorWithDrawnAxis) return;
    throw InputError("The drawing is not symmetric about the vertical line drawn at x = " + std::to_string(int(p.axis_x)) +
                     " px: " + percent(p.mirrored_rows) + " of the rows drawn on both sides of it mirror (an arrow, a "
                     "ridge of a stone tool?). Not a pottery profile — or a careless drawing: then give the axis position.");
  }
  if (p.mirrored_rows >= kMinMirrorAgreement) {
    if (p.axis_source == VesselAxisSource::DrawnLine || rim_line_across(ink, p)) return;
    throw InputError("The drawing does not look like a vessel's half-section: its outer edges mirror about x = " +
                     std::to_string(int(p.axis_x)) + " px, but no axis line is drawn there and no rim line crosses it at "
                     "the top (a symmetric object: a stone tool, a figure?). For a vessel drawn so, give the axis position.");
  }
  throw InputError("The drawing is not symmetric about the axis found (x = " + std::to_string(int(p.axis_x)) +
                   " px): " + percent(p.mirrored_rows) + " of its rows have their outer edges at the same distance on "
                   "both sides, where a half-section's exterior mirrors its section. Not a pottery profile — or only "
                   "one side is drawn: then give the axis position.");
}

// ---- what was read ---------------------------------------------------------------------------

std::vector<cv::Point> to_points(const std::vector<Vec2>& pts) {
  std::vector<cv::Point> out;
  for (const Vec2& q : pts) out.emplace_back(int(std::lround(q.x())), int(std::lround(q.y())));
  return out;
}

// The wall's thickness: twice the median distance from the section's medial axis (the ridge of its
// distance transform) to its boundary — the diameter of the circle that fits in the wall, the
// rim's and foot's thicker parts weighed by their length only.
double median_wall_thickness(const std::vector<Vec2>& outline) {
  const cv::Rect box = cv::boundingRect(to_points(outline));
  const int pad = 2;
  cv::Mat mask(box.height + 2 * pad, box.width + 2 * pad, CV_8U, cv::Scalar(0)), dist;
  std::vector<cv::Point> poly;
  for (const Vec2& q : outline) poly.emplace_back(int(std::lround(q.x())) - box.x + pad, int(std::lround(q.y())) - box.y + pad);
  cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(255));
  cv::distanceTransform(mask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  std::vector<float> ridge;
  for (int y = 1; y + 1 < dist.rows; ++y)
    for (int x = 1; x + 1 < dist.cols; ++x) {
      const float d = dist.at<float>(y, x);
      bool crest = d > 0;  // no neighbour higher (a crest two pixels wide counts both)
      for (int dy = -1; dy <= 1 && crest; ++dy)
        for (int dx = -1; dx <= 1; ++dx) crest = crest && dist.at<float>(y + dy, x + dx) <= d;
      if (crest) ridge.push_back(d);
    }
  if (ridge.empty()) return 0;
  std::nth_element(ridge.begin(), ridge.begin() + long(ridge.size() / 2), ridge.end());
  // A crest pixel's distance runs to the centre of the first pixel outside: a wall of w pixels has
  // its crest at (w + 1) / 2 (odd w) or w / 2 (even w, a crest two pixels wide): w = 2 d - 1/2.
  return 2.0 * ridge[ridge.size() / 2] - 0.5;
}

void measure_profile(VesselProfile& p) {
  double top = 1e300, bottom = -1e300;
  p.max_radius = 0, p.axis_gap = 1e300;
  for (size_t i = 0; i < p.outline.size(); ++i) {
    const Vec2& a = p.outline[i];
    top = std::min(top, a.y()), bottom = std::max(bottom, a.y());
    p.max_radius = std::max(p.max_radius, std::abs(a.x() - p.axis_x));
    p.axis_gap = std::min(p.axis_gap, std::abs(a.x() - p.axis_x));
  }
  p.top_y = top, p.bottom_y = bottom;
  if (p.axis_gap <= p.pen_width) p.axis_gap = 0;
  p.wall_thickness = p.closed ? median_wall_thickness(p.outline) : 0;
  p.rim_radius = 0;
  for (const Vec2& a : p.outline)
    if (a.y() <= top + 0.1 * (bottom - top)) p.rim_radius = std::max(p.rim_radius, std::abs(a.x() - p.axis_x));
}

const char* side_name(VesselSide s) { return s == VesselSide::Right ? "right" : "left"; }

}  // namespace

namespace {

// The section (a closed, filled or hatched region along the outline) or, failing that, the
// profile line, into p.
void read_section(const cv::Mat& raw_ink, const cv::Mat& ink, VesselSide wanted, VesselProfile& p) {
  cv::Mat cells, cell_stats, centroids, dist;
  const int n = cv::connectedComponentsWithStats(~ink, cells, cell_stats, centroids, 4, CV_32S);
  std::vector<uchar> outer;
  const cv::Mat paper = outer_paper(cells, n, outer);
  cv::distanceTransform(~paper, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const SectionScene scene = section_scene(raw_ink, ink, dist, p.axis_x, p.pen_width, wanted);
  Candidate best;
  outlined_candidates(scene, cells, cell_stats, outer, best);
  solid_candidates(scene, best);
  for (VesselSide side : {VesselSide::Left, VesselSide::Right})  // row by row: where no closed region is the whole wall
    if (wanted == VesselSide::Auto || wanted == side) scanline_candidate(scene, side, best);
  if (best.score > 0) {
    p.outline = largest_contour(best.mask), p.closed = true, p.kind = best.kind, p.side = best.side;
    for (Vec2& q : p.outline) q += Vec2(best.box.x, best.box.y);
    for (Vec2& q : p.outline) q.x() = p.side == VesselSide::Left ? std::min(q.x(), p.axis_x) : std::max(q.x(), p.axis_x);
    return;
  }
  const VesselSide side = wanted == VesselSide::Right ? VesselSide::Right : VesselSide::Left;
  if (!profile_line(ink, side, p))
    throw InputError(std::string("No vessel profile on the ") + side_name(side) + " of the axis (x = " +
                     std::to_string(int(p.axis_x)) + " px): neither a wall's section (a closed, filled or hatched "
                     "region along the outline) nor a profile line. Check the axis position and the section side.");
  const double dense = ink_inside_profile(ink, p);
  if (dense > kMaxInkInsideProfile)
    throw InputError("No wall section was found, and " + std::to_string(int(std::lround(100 * dense))) + " % of the "
                     "drawing inside its outline is ink: the drawing does not look like a vessel's half-section (a "
                     "tablet, a figure?). Crop it to one vessel, or give the axis position and the section side.");
}

}  // namespace

namespace {

// The vessel of one piece of the drawing (its ink), or InputError saying why it is none.
VesselProfile read_piece(const cv::Mat& raw_ink, const cv::Mat& ink, const VesselParams& params, VesselProfile p) {
  const bool axis_given = !std::isnan(params.axis_x);
  const InkBox box = ink_box(ink);
  const int drawn_axis_rows = axis_given ? 0 : place_axis(ink, box, p);
  if (axis_given) p.axis_x = params.axis_x;
  if (p.axis_x < 0 || p.axis_x > ink.cols - 1)
    throw InputError("Axis position " + std::to_string(int(p.axis_x)) + " px is outside the drawing (0 to " +
                     std::to_string(ink.cols - 1) + " px; -1 finds it).");
  read_section(raw_ink, ink, params.side, p);
  measure_profile(p);
  require_vessel_drawing(p, ink, box, axis_given, drawn_axis_rows);
  return p;
}

}  // namespace

VesselProfile read_vessel_profile(const cv::Mat& image, const VesselParams& params) {
  params.validate();
  const cv::Mat raw_ink = ink_of(image);
  cv::Mat ink = raw_ink.clone();
  VesselProfile p;
  p.pen_width = pen_width_of(ink);
  drop_specks(ink, int(std::ceil(std::max(3 * p.pen_width, 0.006 * std::max(ink.cols, ink.rows)))));
  cv::morphologyEx(ink, ink, cv::MORPH_CLOSE, disc(0.5 * p.pen_width + 1));
  p.dash_gaps_joined = join_dashes(ink, p.pen_width, std::max(15 * p.pen_width, kMaxDashShare * std::max(ink.cols, ink.rows)));
  if (cv::countNonZero(ink) == 0) throw InputError("The drawing holds only specks of ink (dots, dust): no vessel profile in it.");
  if (!std::isnan(params.axis_x)) {  // the user's axis: the whole drawing
    p.piece = cv::boundingRect(ink);
    return read_piece(raw_ink, ink, params, p);
  }
  const std::vector<VesselPiece> pieces = vessel_pieces(ink, p.pen_width, p.frame_left_out);
  std::string first_error;
  for (size_t k = 0; k < pieces.size(); ++k) {  // the best piece that is a vessel profile (a line alone: the first only)
    VesselProfile candidate = p;
    candidate.piece = pieces[k].box, candidate.pieces_left_out = pieces[k].left_out;
    candidate.other_vessels = pieces[k].other_vessels, candidate.piece_rank = int(k);
    try {
      VesselProfile read = read_piece(raw_ink, pieces[k].ink, params, candidate);
      if (k == 0 || read.kind != VesselSectionKind::ProfileLine) return read;  // a further piece needs a wall's section
    } catch (const InputError& e) {
      if (first_error.empty()) first_error = e.what();
    }
  }
  throw InputError(first_error.empty() ? std::string("The drawing holds no piece to read.") : first_error);
}

std::vector<std::string> vessel_log_lines(const VesselProfile& p) {
  std::vector<std::string> lines;
  const std::string where = "x " + std::to_string(p.piece.x) + "-" + std::to_string(p.piece.x + p.piece.width) + ", y " +
                            std::to_string(p.piece.y) + "-" + std::to_string(p.piece.y + p.piece.height) + " px";
  if (p.other_vessels > 0)
    lines.push_back("Warning: the page holds " + std::to_string(p.other_vessels + 1) + " drawings of about this size; the "
                    "one whose outer edges mirror best was taken (" + where + "). Crop the image to another vessel to make "
                    "that one.");
  if (p.piece_rank > 0)
    lines.push_back("Note: " + std::to_string(p.piece_rank) + " larger drawing(s) on the page are not vessel profiles; the "
                    "vessel was read from the drawing at " + where + ".");
  if (p.pieces_left_out > 0 || p.frame_left_out)
    lines.push_back("Left out: " + std::to_string(p.pieces_left_out) + " separate pieces beside the vessel's drawing (" + where +
                    ": a base drawn apart, labels, dashes)" + (p.frame_left_out ? " and a frame round the figure." : "."));
  if (p.dash_gaps_joined > 0)
    lines.push_back("Note: " + std::to_string(p.dash_gaps_joined) + " gaps between dashes joined: a line drawn dashed (a "
                    "reconstructed wall) is read as a line.");
  if (p.profile_coverage < 0.9)
    lines.push_back("Warning: the vessel covers " + percent(p.profile_coverage) + " of the heights at which the drawing's "
                    "exterior is drawn on both sides of the axis: the section read is shorter than the drawn profile.");
  if (p.axis_source == VesselAxisSource::DrawnLine && p.mirrored_rows < kMinMirrorAgreement)
    lines.push_back("Warning: the exterior does not mirror the section about the drawn axis (" + percent(p.mirrored_rows) +
                    " of the rows): the drawn axis line was taken; check it, or give the axis position.");
  return lines;
}

// ---- the surface of revolution -------------------------------------------------------------

namespace {

// The pixel staircase of a traced outline eased: a [1 2 1] / 4 average along it, `passes` times (a
// corner moves by less than half a pixel); the ends of an open outline stay.
std::vector<Vec2> eased(std::vector<Vec2> pts, bool closed, int passes) {
  const size_t n = pts.size();
  for (int pass = 0; pass < passes && n >= 3; ++pass) {
    std::vector<Vec2> next = pts;
    for (size_t i = closed ? 0 : 1; i < (closed ? n : n - 1); ++i)
      next[i] = 0.25 * pts[(i + n - 1) % n] + 0.5 * pts[i] + 0.25 * pts[(i + 1) % n];
    pts.swap(next);
  }
  return pts;
}

// The outline eased and simplified within 0.5 px (Douglas-Peucker: the corners of rim, foot and
// breaks stay where they are), each piece then cut into pieces at most `spacing` long.
std::vector<Vec2> simplified_and_subdivided(const std::vector<Vec2>& pts, double spacing, bool closed) {
  std::vector<cv::Point2f> in, corners;
  for (const Vec2& q : eased(pts, closed, 2)) in.emplace_back(float(q.x()), float(q.y()));
  cv::approxPolyDP(in, corners, 0.5, closed);
  std::vector<Vec2> out;
  const size_t pieces = closed ? corners.size() : corners.size() - 1;
  for (size_t i = 0; i < pieces; ++i) {
    const Vec2 a(corners[i].x, corners[i].y), b(corners[(i + 1) % corners.size()].x, corners[(i + 1) % corners.size()].y);
    const int n = std::max(1, int(std::ceil((b - a).norm() / spacing)));
    for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * (double(k) / n));
  }
  if (!closed) out.emplace_back(corners.back().x, corners.back().y);
  return out;
}

// About 500 points along the outline, never closer than a pen width (1.5 px at least).
double profile_spacing(const VesselProfile& p) {
  double length = 0;
  for (size_t i = 1; i < p.outline.size(); ++i) length += (p.outline[i] - p.outline[i - 1]).norm();
  return std::max({1.5, p.pen_width, length / 500});
}

// Runs of points on the axis reduced to their ends (an inner point of such a run would be a vertex
// without faces).
std::vector<Vec2> without_inner_axis_points(const std::vector<Vec2>& rh, bool closed) {
  const size_t n = rh.size();
  std::vector<Vec2> out;
  for (size_t i = 0; i < n; ++i) {
    const bool has_prev = closed || i > 0, has_next = closed || i + 1 < n;
    const bool inner = rh[i].x() == 0 && has_prev && has_next && rh[(i + n - 1) % n].x() == 0 && rh[(i + 1) % n].x() == 0;
    if (!inner) out.push_back(rh[i]);
  }
  return out;
}

}  // namespace

std::vector<Vec2> vessel_profile_section(const VesselProfile& p, double pixel_size) {
  if (p.outline.size() < 3) throw InputError("The vessel profile has fewer than 3 points: nothing to revolve.");
  const std::vector<Vec2> path = simplified_and_subdivided(p.outline, profile_spacing(p), p.closed);
  std::vector<Vec2> rh;
  for (const Vec2& q : path) {
    double r = std::abs(q.x() - p.axis_x);
    if (r < 0.5) r = 0;
    rh.emplace_back(r * pixel_size, -q.y() * pixel_size);
  }
  return without_inner_axis_points(rh, p.closed);
}

namespace {

// Signed volume (closed) or outward flux of the radial direction (open): positive when the faces
// face outwards.
double outwardness(const TriMesh& m, const Vec3& axis_point) {
  double sum = 0;
  for (const auto& f : m.faces) {
    const Vec3 &a = m.vertices[size_t(f[0])], &b = m.vertices[size_t(f[1])], &c = m.vertices[size_t(f[2])];
    const Vec3 n = (b - a).cross(c - a), centre = (a + b + c) / 3.0 - axis_point;
    sum += n.dot(Vec3(centre.x(), 0, centre.z()));
  }
  return sum;
}

void add_band(TriMesh& m, int a0, bool a_ring, int b0, bool b_ring, int n) {
  for (int j = 0; j < n; ++j) {
    const int j1 = (j + 1) % n;
    if (a_ring && b_ring) {
      m.faces.push_back({a0 + j, b0 + j, b0 + j1});
      m.faces.push_back({a0 + j, b0 + j1, a0 + j1});
    } else if (a_ring) {
      m.faces.push_back({a0 + j, b0, a0 + j1});
    } else if (b_ring) {
      m.faces.push_back({a0, b0 + j, b0 + j1});
    }
  }
}

}  // namespace

TriMesh revolve_vessel_profile(const VesselProfile& p, const VesselParams& params) {
  params.validate();
  const std::vector<Vec2> rh = vessel_profile_section(p, params.pixel_size);
  double max_r = 0;
  for (const Vec2& q : rh) max_r = std::max(max_r, q.x());
  if (max_r <= 0) throw InputError("The vessel profile lies on its axis: nothing to revolve.");
  const double spacing = profile_spacing(p) * params.pixel_size;
  const int n = params.segments > 0 ? params.segments : std::clamp(int(std::lround(2 * M_PI * max_r / spacing)), 48, 360);
  const double ax = p.axis_x * params.pixel_size;
  TriMesh m;
  std::vector<int> first(rh.size());
  for (size_t i = 0; i < rh.size(); ++i) {
    first[i] = m.n_vertices();
    if (rh[i].x() == 0) { m.vertices.emplace_back(ax, rh[i].y(), 0); continue; }
    for (int j = 0; j < n; ++j) {
      const double t = 2 * M_PI * j / n;
      m.vertices.emplace_back(ax + rh[i].x() * std::cos(t), rh[i].y(), rh[i].x() * std::sin(t));
    }
  }
  const size_t segs = p.closed ? rh.size() : rh.size() - 1;
  for (size_t i = 0; i < segs; ++i) {
    const size_t k = (i + 1) % rh.size();
    add_band(m, first[i], rh[i].x() > 0, first[k], rh[k].x() > 0, n);
  }
  if (outwardness(m, Vec3(ax, 0, 0)) < 0)
    for (auto& f : m.faces) std::swap(f[1], f[2]);
  return m;
}

std::string vessel_summary(const VesselProfile& p, double s, const char* unit) {
  static const char* kinds[] = {"filled section", "hatched section", "outlined section", "profile line (no section)"};
  static const char* sources[] = {"given", "the drawn axis line", "where the outer edges mirror",
                                  "the middle of the drawn width"};
  std::ostringstream o;
  o.precision(3);
  o << kinds[int(p.kind)] << " on the " << side_name(p.side) << " of the axis (x = " << std::lround(p.axis_x)
    << " px, " << sources[int(p.axis_source)] << "); height " << (p.bottom_y - p.top_y) * s << " " << unit
    << ", rim diameter " << 2 * p.rim_radius * s << " " << unit << ", widest " << 2 * p.max_radius * s << " " << unit;
  if (p.closed) o << ", wall about " << p.wall_thickness * s << " " << unit << " thick";
  o << "; pen " << p.pen_width << " px; " << std::lround(100 * p.mirrored_rows) << " % of rows mirrored about the axis; ";
  if (p.axis_gap == 0)
    o << "the base closes on the axis";
  else
    o << "the base is not drawn: the vessel is open there, " << 2 * p.axis_gap * s << " " << unit << " across";
  return o.str();
}

}  // namespace reliefkit
