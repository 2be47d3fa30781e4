// ReliefKit — the length scale of a scan, portable length parameters, and the noise level.
//
// Every length a user gives a ReliefKit filter is a multiple of the scan's typical edge length
// (or "auto"), so one .mlx script serves a coin stored in millimetres and a statue in metres.
// The typical edge length is the median edge length of the scan's largest connected part:
// floating debris, a coarse turntable plate or a few huge faces do not move it.
//
// The noise level is estimated from how far the vertices lie from a local quadric fitted to
// their two-ring (see estimate_noise); "auto" pre-smoothing is derived from it, so a clean mesh
// is not smoothed at all and a noisy one enough for curvature derivatives to rise above noise.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/zero_crossings.h"

namespace reliefkit {

/// Connected parts (by shared vertices) and the scale statistics of the largest one.
struct MeshScale {
  double edge = 0;         // median edge length of the largest part (mesh units); the unit of length parameters
  double mean_edge = 0;    // mean edge length of the largest part
  double object_size = 0;  // bounding-box diagonal of the largest part
  /// What one explicit diffusion step spreads by (smoothing.h): a quarter of the mean squared edge
  /// length of the largest part over its edges at most 4 x `edge` long (so a coarse plate or debris
  /// does not cut the number of steps). Mesh units squared, per tangent direction.
  double step_variance = 0;
  int parts = 0;           // connected parts with at least one face
  long long main_faces = 0;  // faces of the largest part
  /// Per vertex: 1 if it belongs to a part that counts for statistics (thresholds, noise): the
  /// parts with at least kMainPartShare of the largest part's faces. Debris does not count.
  std::vector<char> counts;
  long long debris_faces = 0;  // faces of the parts that do not count
};

/// Parts smaller than this share of the largest part's faces are debris for statistics.
constexpr double kMainPartShare = 0.1;

/// The scale of a mesh. A mesh without faces gives edge = 0 (callers reject it first).
MeshScale mesh_scale(const TriMesh& mesh);

/// Values of `per_vertex` at the vertices that count (all of them when `counts` is empty).
std::vector<double> counted_values(const std::vector<double>& per_vertex, const std::vector<char>& counts);

/// A length parameter: automatic, a multiple of the typical edge length (what users give), or
/// an absolute length in mesh units (what scripts of ReliefKit 0.1 stored; still honoured).
struct Length {
  enum class Kind { Auto, Edges, Units };
  Kind kind = Kind::Auto;
  double value = 0;
  static Length automatic() { return Length{}; }
  static Length in_edges(double e) { return Length{Kind::Edges, e}; }
  static Length in_units(double u) { return Length{Kind::Units, u}; }
  bool is_auto() const { return kind == Kind::Auto; }
  /// Mesh units: `automatic_value` when automatic.
  double resolve(double edge, double automatic_value) const {
    return kind == Kind::Auto ? automatic_value : kind == Kind::Edges ? value * edge : value;
  }
  /// Throws InputError unless a given length lies in [lo, hi] edge lengths (checked in edge
  /// lengths whatever the kind, so an absolute length of 1e30 is refused too).
  void check(const std::string& name, double lo, double hi, double edge = 0) const;
};

/// Reads a length parameter as users write it: "auto" (any case, also empty) or a number of edge
/// lengths in [min_edges, max_edges]. Throws InputError naming `name` and the accepted range.
Length parse_length(const std::string& text, const std::string& name, double min_edges, double max_edges);
/// "auto" or the number, as parse_length reads it back.
std::string format_length(const Length& length);

/// Throws InputError "<name> must be between <lo> and <hi> (got <value>)" unless lo <= value <= hi
/// (NaN and infinities are always rejected).
void require_range(double value, const std::string& name, double lo, double hi);

/// Noise along the normal, estimated from the residuals of local quadric fits.
struct NoiseEstimate {
  double sigma = 0;        // standard deviation, mesh units
  double relative = 0;     // sigma / MeshScale::edge
  long long samples = 0;   // vertices used
};

/// At (a subsample of at most `max_samples` of) the vertices that count, a quadric with a
/// constant term is fitted by least squares to the vertex and its two-ring in the frame of the
/// vertex normal; the residual standard deviation (with the degrees of freedom taken into
/// account) is the local noise. The median over the vertices, calibrated on synthetic Gaussian
/// noise (tests/unit/base/test_scale.cpp), is the estimate: relief features and sharp edges occupy a
/// minority of the vertices and do not move it.
constexpr int kNoiseSamples = 50000;
/// `faces`: the mesh's vertex-face adjacency when the caller has it (else built here).
NoiseEstimate estimate_noise(const TriMesh& mesh, const MeshScale& scale, int max_samples = kNoiseSamples,
                             const VertexFaces* faces = nullptr);

/// Relative noise below which a mesh counts as clean (no automatic pre-smoothing): the
/// residual a clean, finely sampled smooth surface leaves is well below it.
constexpr double kCleanNoise = 0.02;

/// Automatic pre-smoothing scale (mesh units) for the noise estimate: 0 on a clean mesh; else
/// the Gaussian scale at which the noise left in curvature derivatives falls below what the
/// object's own shape gives (see docs/parameters.md for the rule and its measurements).
double automatic_presmoothing(const NoiseEstimate& noise, const MeshScale& scale);

}  // namespace reliefkit

namespace reliefkit {

/// A flat, irregularly triangulated square patch (n x n cells, edge length about 1) whose
/// vertices carry Gaussian noise of `relative_noise` edge lengths along the normal: what the
/// estimated noise alone looks like. Curve filters measure on it how strong the curves are that
/// noise alone draws after the same pre-smoothing, and keep their thresholds above that
/// (deterministic: fixed seed).
TriMesh noise_patch(double relative_noise, int n = 100);

/// The noise patch's size for a mesh of `faces` faces: 100 cells (20,000 faces), down to 30 for
/// meshes smaller than that, so that the simulation never costs more than the mesh itself.
int noise_patch_cells(long long faces);

/// The value below which the top `1 - q` of `values` lie (0 if empty).
double percentile(std::vector<double> values, double q);

/// The median of (value, weight) pairs: the smallest value at which the weights below and at it
/// reach half the total (0 if empty).
double weighted_median(std::vector<std::pair<double, double>> value_weight);

}  // namespace reliefkit

namespace reliefkit {

/// The rim of the noise patch, in cells, that its statistics leave out after pre-smoothing of
/// `presmoothing_edges` edge lengths (the smoothing and the fits are one-sided there).
int noise_patch_margin(double presmoothing_edges);

/// Whether vertex `v` of noise_patch(.., n) lies at least `margin` cells inside the patch (its
/// border has one-sided fits and is no model of a scan's interior).
bool inside_noise_patch(int v, int n, int margin);

/// Which segments of `curves` extracted on noise_patch(.., n) lie at least `margin` cells inside it.
std::vector<char> interior_segments(const Polylines& curves, int n, int margin);

/// Strengths (mean of their end points') of the segments of `curves` extracted on
/// noise_patch(.., n) that lie at least `margin` cells inside the patch (its border has
/// one-sided fits and is no model of a scan's interior).
std::vector<double> interior_segment_strengths(const Polylines& curves, int n, int margin);

/// Curves weaker than this multiple of the 99th percentile of what noise alone draws (on the
/// noise patch, at the same pre-smoothing) are taken as noise by the automatic thresholds.
constexpr double kNoiseCurveFactor = 1.0;
constexpr double kNoiseCurvePercentile = 0.99;

}  // namespace reliefkit
