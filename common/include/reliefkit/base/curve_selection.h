// ReliefKit — choosing which zero-crossing curves to keep: the automatic strength threshold,
// hysteresis, bridging small gaps and dropping short fragments. Every curve filter (demarcating
// curves, ridges and valleys, relief edges, and the multi-scale ones) selects its curves with
// these, from the full set of crossings extract_zero_crossings() finds.
#pragma once

#include <algorithm>
#include <vector>

#include "reliefkit/base/surface.h"
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
/// a new segment to the nearest other end within `max_gap` (mesh units) when the two ends face
/// each other within `max_turn` radians and the link continues both ends' directions within it
/// or is a jog (kJogShare) (each end's direction taken over its last `max_gap` of curve); pairs are taken nearest first, each end at most once. A chain is not
/// closed onto itself unless it is longer than 4 x max_gap. The new segments take the strength
/// of their ends and the face of the first end's segment. Returns how many links were made.
int link_gaps(Polylines& curves, double max_gap, double max_turn);
/// The curve filters' largest turn (radians) of a gap-bridging link against its ends' directions.
constexpr double kLinkTurn = 0.78539816339744831;
/// A bridge may also be a jog: a sideways step of at most this share of the gap (a line broken and
/// shifted by a triangle, its two ends side by side).
constexpr double kJogShare = 0.35;

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
/// `edge`: the mesh's mean edge length; `faces`: its face count.
CurveStatistics curve_statistics(const Polylines& curves, double edge, long long faces);

/// How lines are connected after the threshold: segments at least weak_ratio x the threshold are
/// kept where they join one above it (hysteresis along the line), and line ends facing each other
/// across up to gap_edges edge lengths are joined.
struct LineLinking {
  double weak_ratio = 1.0;
  double gap_edges = 0;
};
/// The curve filters' linking: a line stays drawn where it weakens to half the threshold, and
/// gaps of up to 3 edge lengths along it are bridged.
constexpr LineLinking kLineLinking{0.5, 3.0};

/// Per segment, the piece it belongs to (0, 1, ...), and in `lengths` each piece's length.
std::vector<int> curve_pieces(const Polylines& curves, std::vector<double>& lengths);

/// Keeps the pieces at least `min_length` long (mesh units): the dashes an illustrator would clean
/// away go, whatever their strength (a short strong piece on a scan is a pit or a scratch far more
/// often than a feature; users who want the fine ones lower the length). A piece is all the
/// segments joined through shared points, branches included (drop_short_chains cuts at branches).
Polylines drop_dashes(const Polylines& curves, double min_length);

/// The lines of `all` as every curve filter connects them: the `strong` segments with the `weak`
/// ones joined to them (hysteresis), gaps up to `max_gap` bridged (link_gaps, kLinkTurn; the
/// number of links in `links` when given), pieces shorter than `min_length` dropped (drop_dashes).
Polylines connect_lines(const Polylines& all, const std::vector<char>& strong, const std::vector<char>& weak,
                        double max_gap, double min_length, int* links = nullptr);

/// Per vertex, how far `values` stands above its surroundings in units of their own spread:
/// (x − m) / s, with m the values diffused to `radius` (mesh units) and s the absolute deviations
/// |x − m| diffused to it. A crease on a smooth surface stands many spreads above its
/// surroundings; a bump of a rough surface (a cast ingot, a flake's cortex, a scar's ripples) a
/// few. 0 where the spread is 0.
std::vector<double> local_contrast(const Surface& surface, const std::vector<double>& values, double radius);

/// A line point stands out from a rough surface when its contrast is at least this.
constexpr double kLineContrast = 3.0;
/// The radius of the surroundings: 8 edge lengths, and at least 4 x the pre-smoothing the
/// strengths were read at (features that wide are several times wider than the edge).
constexpr double kContrastRadiusEdges = 8.0;
constexpr double kContrastRadiusScales = 4.0;
inline double contrast_radius(double edge, double presmoothing) {
  return std::max(kContrastRadiusEdges * edge, kContrastRadiusScales * presmoothing);
}

/// Per point of `curves`, how far it stands out of the surface's roughness: min(1, contrast /
/// kLineContrast) in [0, 1], the contrast (local_contrast) interpolated at the points.
std::vector<double> contrast_weights(const Polylines& curves, const std::vector<double>& contrast);

/// Lines from candidate crossings (strength per point): the segments at least `threshold` strong,
/// with those joined to them down to linking.weak_ratio x it (hysteresis along the line); gaps
/// bridged (linking.gap_edges x `edge`); dashes dropped (drop_dashes, `min_length` in mesh units).
/// With `contrast` (per vertex, local_contrast of the values the strengths come from), a line
/// starts only where it stands out of the surface's roughness (its strength x contrast_weights
/// reaches the threshold); once started it goes on by its plain strength.
Polylines select_lines(const Polylines& candidates, double threshold, const LineLinking& linking, double edge,
                       double min_length, const std::vector<double>& contrast = {});

}  // namespace reliefkit
