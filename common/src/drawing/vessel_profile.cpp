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

// The drawn axis: the longest vertical line in the middle half of the drawn width (nearer the
// middle preferred), at least 4 % of the drawing's height; else the middle of the drawn width.
void place_axis(const cv::Mat& ink, const InkBox& box, VesselProfile& p) {
  const double mid = 0.5 * (box.x0 + box.x1), reach = 0.25 * box.width();
  const int max_gap = std::max(3, int(0.02 * box.height()));
  VerticalLine best;
  double best_score = 0;
  for (int x = std::max(1, int(mid - reach)); x <= std::min(ink.cols - 2, int(mid + reach)); ++x) {
    const VerticalLine line = vertical_line_at(ink, x, max_gap);
    const double score = line.inked * (1 - std::abs(line.x - mid) / (2 * reach));
    if (score > best_score) best = line, best_score = score;
  }
  if (best.inked >= std::max(10.0, 0.04 * box.height())) {
    p.axis_x = best.x, p.axis_source = VesselAxisSource::DrawnLine;
  } else {
    p.axis_x = mid, p.axis_source = VesselAxisSource::MiddleOfDrawing;
  }
}

// ---- the section -------------------------------------------------------------------------------

struct Candidate {
  cv::Mat mask;  // the region within `box`
  cv::Rect box;  // in the image
  VesselSectionKind kind = VesselSectionKind::Outlined;
  VesselSide side = VesselSide::Left;
  double score = 0;
};

struct SectionScene {
  const cv::Mat& raw_ink;      // as thresholded
  const cv::Mat& ink;          // specks dropped, gaps closed
  cv::Mat paper_dist;          // distance to the paper around the vessel
  double axis_x, pen;
  double min_contact;          // boundary pixels next to the outer paper a wall must have
  VesselSide wanted;
};

// A wall is thin: its thickness at most this share of its boundary along the outer paper (sections
// are thicker at the rim or foot, as the shared bowl's lip; the bowl's exterior sherd and a jar's
// exterior half drawn as a closed region are thicker than this: VesselProfile.* read them so).
constexpr double kMaxThicknessShare = 0.1;

// What a vessel drawing must show (require_vessel_drawing): a profile over at least this share of
// the drawing's height, and (axis found) at least this share of mirrored rows.
constexpr double kMinProfileHeightShare = 0.25;
constexpr double kMinMirrorAgreement = 0.6;

// Scores a region: on one side of the axis, its boundary along the outer paper (contact) over its
// thickness (twice the largest inscribed radius). 0 when it does not qualify.
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
  if (contact >= s.min_contact && 2 * max_radius <= kMaxThicknessShare * contact) c.score = contact / (2 * max_radius);
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

void keep_best(Candidate& c, Candidate& best) {
  if (c.score > best.score) best = c;
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

// ---- is it a vessel? -------------------------------------------------------------------------

// The share of the rows inked on both sides of the axis whose outermost ink lies at the same
// distance from it on the left and on the right (within 5 % of the drawn half-width): a
// half-section's exterior mirrors its section's outer wall.
double mirror_agreement(const cv::Mat& ink, double axis, const InkBox& box) {
  const double tolerance = 0.05 * std::max(axis - box.x0, box.x1 - axis);
  const int a = int(std::lround(axis));
  long rows = 0, agree = 0;
  for (int y = box.y0; y <= box.y1; ++y) {
    const uchar* row = ink.ptr<uchar>(y);
    int left = -1, right = -1;
    for (int x = box.x0; x < a - 2 && left < 0; ++x) if (row[x]) left = x;
    for (int x = box.x1; x > a + 2 && right < 0; --x) if (row[x]) right = x;
    if (left < 0 || right < 0) continue;
    ++rows, agree += std::abs((axis - left) - (right - axis)) <= tolerance;
  }
  return rows ? double(agree) / double(rows) : 0;
}

std::string percent(double share) { return std::to_string(int(std::lround(100 * share))) + " %"; }

// A vessel's profile runs over a good part of its drawing, and a drawing in the half-section
// convention is symmetric about its axis (checked when the axis was found, not given). Throws
// InputError saying what was found otherwise: the drawing is not a pottery profile.
void require_vessel_drawing(VesselProfile& p, const cv::Mat& ink, const InkBox& box, bool axis_given) {
  const double spans = (p.bottom_y - p.top_y) / std::max(1, box.height());
  if (spans < kMinProfileHeightShare)
    throw InputError("The vessel profile found spans " + percent(spans) + " of the drawing's height (" +
                     std::to_string(int(p.bottom_y - p.top_y)) + " of " + std::to_string(box.height()) +
                     " px): the drawing does not look like a vessel's half-section. Crop it to one vessel, or give the "
                     "axis position and the section side.");
  p.mirrored_rows = mirror_agreement(ink, p.axis_x, box);
  const double mirrored = p.mirrored_rows;
  if (axis_given) return;
  if (mirrored < kMinMirrorAgreement)
    throw InputError("The drawing is not symmetric about the axis found (x = " + std::to_string(int(p.axis_x)) +
                     " px): " + percent(mirrored) + " of its rows have their outer edges at the same distance on both "
                     "sides, where a half-section's exterior mirrors its section. Not a pottery profile — or only one "
                     "side is drawn: then give the axis position.");
}

// ---- what was read ---------------------------------------------------------------------------

void measure_profile(VesselProfile& p) {
  double top = 1e300, bottom = -1e300, area = 0, perimeter = 0;
  p.max_radius = 0, p.axis_gap = 1e300;
  for (size_t i = 0; i < p.outline.size(); ++i) {
    const Vec2& a = p.outline[i];
    top = std::min(top, a.y()), bottom = std::max(bottom, a.y());
    p.max_radius = std::max(p.max_radius, std::abs(a.x() - p.axis_x));
    p.axis_gap = std::min(p.axis_gap, std::abs(a.x() - p.axis_x));
    const Vec2& b = p.outline[(i + 1) % p.outline.size()];
    if (i + 1 < p.outline.size() || p.closed) area += a.x() * b.y() - b.x() * a.y(), perimeter += (b - a).norm();
  }
  p.top_y = top, p.bottom_y = bottom;
  if (p.axis_gap <= p.pen_width) p.axis_gap = 0;
  p.wall_thickness = p.closed ? 0.5 * std::abs(area) / std::max(1.0, 0.5 * perimeter) : 0;
  p.rim_radius = 0;
  for (const Vec2& a : p.outline)
    if (a.y() <= top + 0.1 * (bottom - top)) p.rim_radius = std::max(p.rim_radius, std::abs(a.x() - p.axis_x));
}

const char* side_name(VesselSide s) { return s == VesselSide::Right ? "right" : "left"; }

}  // namespace

VesselProfile read_vessel_profile(const cv::Mat& image, const VesselParams& params) {
  params.validate();
  const cv::Mat raw_ink = ink_of(image);
  cv::Mat ink = raw_ink.clone();
  VesselProfile p;
  p.pen_width = pen_width_of(ink);
  drop_specks(ink, int(std::ceil(std::max(3 * p.pen_width, 0.006 * std::max(ink.cols, ink.rows)))));
  cv::morphologyEx(ink, ink, cv::MORPH_CLOSE, disc(0.5 * p.pen_width + 1));
  if (cv::countNonZero(ink) == 0) throw InputError("The drawing holds only specks of ink (dots, dust): no vessel profile in it.");
  const InkBox box = ink_box(ink);
  if (std::isnan(params.axis_x)) place_axis(ink, box, p); else p.axis_x = params.axis_x;
  if (p.axis_x < 0 || p.axis_x > ink.cols - 1)
    throw InputError("Axis position " + std::to_string(int(p.axis_x)) + " px is outside the drawing (0 to " +
                     std::to_string(ink.cols - 1) + " px; -1 finds it).");
  cv::Mat cells, cell_stats, centroids, dist;
  const int n = cv::connectedComponentsWithStats(~ink, cells, cell_stats, centroids, 4, CV_32S);
  std::vector<uchar> outer;
  const cv::Mat paper = outer_paper(cells, n, outer);
  cv::distanceTransform(~paper, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const SectionScene scene{raw_ink, ink, dist, p.axis_x, p.pen_width, 0.2 * std::max(box.height(), box.width() / 2), params.side};
  Candidate best;
  outlined_candidates(scene, cells, cell_stats, outer, best);
  solid_candidates(scene, best);
  if (best.score > 0) {
    p.outline = largest_contour(best.mask), p.closed = true, p.kind = best.kind, p.side = best.side;
    for (Vec2& q : p.outline) q += Vec2(best.box.x, best.box.y);
    for (Vec2& q : p.outline) q.x() = p.side == VesselSide::Left ? std::min(q.x(), p.axis_x) : std::max(q.x(), p.axis_x);
  } else {
    const VesselSide side = params.side == VesselSide::Right ? VesselSide::Right : VesselSide::Left;
    if (!profile_line(ink, side, p))
      throw InputError(std::string("No vessel profile on the ") + side_name(side) + " of the axis (x = " +
                       std::to_string(int(p.axis_x)) + " px): neither a wall's section (a closed, filled or hatched "
                       "region along the outline) nor a profile line. Check the axis position and the section side.");
  }
  measure_profile(p);
  require_vessel_drawing(p, ink, box, !std::isnan(params.axis_x));
  return p;
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
  static const char* sources[] = {"given", "the drawn axis line", "the middle of the drawn width"};
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
