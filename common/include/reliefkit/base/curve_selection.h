// ReliefKit — choosing which zero-crossing curves to keep: the automatic strength threshold,
// hysteresis, bridging small gaps and dropping short fragments. Every curve filter (demarcating
// curves, ridges and valleys, relief edges, and the multi-scale ones) selects its curves with
// these, from the full set of crossings extract_zero_crossings() finds.
#pragma once

#include <vector>

#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {

/// Automatic, scale-free strength threshold for curves (thesis 3.3.2 and 4.3.2 leave it to the
/// user):  max(kNoiseFactor x noise_scale, kTopFactor x 90th percentile of the strength of all
/// zero-crossing segments), with noise_scale the median strength over the vertices.
/// The first term sits above the strength scanner noise gives (noise crossings measured on
/// synthetic reliefs with 10 % noise: median 1.5x, 99th percentile 2.5-3x the median vertex
/// strength). The second matters on clean surfaces, where the first is near zero: it drops
/// curves weaker than a quarter of the strong ones, such as the gentle concave-to-convex
/// transitions at the foot of a relief on a curved base. (A 99th percentile was tried first: on
/// the coin scan the rim then set the scale and the lettering vanished.)
constexpr double kNoiseFactor = 2.0;
constexpr double kTopFactor = 0.25;
constexpr double kTopPercentile = 0.90;
double automatic_curve_threshold(double noise_scale, const Polylines& all_crossings);
/// The same from the strengths of all crossing segments (ZeroCrossingOptions::all_strengths).
double automatic_curve_threshold(double noise_scale, std::vector<double> segment_strengths);

/// Median of the positive finite values (0 if none).
double median_positive(const std::vector<double>& values);

/// Keeps the segments k with keep[k] != 0 (and the points they use).
Polylines select_segments(const Polylines& curves, const std::vector<char>& keep);

/// Keeps the segments whose strength (mean of their end points') reaches `min_strength`.
Polylines keep_strong_segments(const Polylines& curves, double min_strength);

/// Joins curve ends across small gaps: an end of a chain (a point with one segment) is linked by
/// a new segment to the nearest other end within `max_gap` (mesh units) when the link continues
/// both ends' directions within `max_turn` radians (each end's direction taken over its last
/// `max_gap` of curve); pairs are taken nearest first, each end at most once. A chain is not
/// closed onto itself unless it is longer than 4 x max_gap. The new segments take the strength
/// of their ends and the face of the first end's segment. Returns how many links were made.
int link_gaps(Polylines& curves, double max_gap, double max_turn);
/// The curve filters' largest turn (radians) of a gap-bridging link against its ends' directions.
constexpr double kLinkTurn = 0.78539816339744831;

/// Keeps only the chains at least `min_length` long (removes isolated short fragments).
Polylines drop_short_chains(const Polylines& curves, double min_length);

/// Two-threshold hysteresis on segments: the strong segments and every weak (or strong) segment
/// connected to one through shared curve points are kept.
Polylines hysteresis(const Polylines& all, const std::vector<char>& strong, const std::vector<char>& weak);

/// Per segment of `curves`: 1 where its midpoint lies within `radius` (mesh units) of a segment of
/// `others` (both on the same mesh).
std::vector<char> segments_near(const Polylines& curves, const Polylines& others, double radius);

/// Appends `more`'s points and segments to `curves`.
void append_curves(Polylines& curves, const Polylines& more);

/// Pieces shorter than this many edge lengths are dashes: what an illustrator cleans by hand.
constexpr double kDashEdges = 10.0;

/// What a curve layer looks like to an illustrator: its pieces (sets of segments joined through
/// shared points), their length, and the share of it lying in dashes.
struct CurveStatistics {
  long long pieces = 0, dashes = 0;  // dashes: pieces shorter than kDashEdges edge lengths
  double length = 0;                 // mesh units
  double dash_length = 0;            // in the dashes
  double length_per_kface = 0;       // in edge lengths per 1,000 faces of the mesh
  double dash_share() const { return length > 0 ? dash_length / length : 0.0; }
};
/// `edge`: the mesh's typical edge length (MeshScale::edge); `faces`: its face count.
CurveStatistics curve_statistics(const Polylines& curves, double edge, long long faces);

/// Per segment, the piece it belongs to (0, 1, ...), and in `lengths` each piece's length.
std::vector<int> curve_pieces(const Polylines& curves, std::vector<double>& lengths);

}  // namespace reliefkit
