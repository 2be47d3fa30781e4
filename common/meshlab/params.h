// ReliefKit — reading and checking filter parameters (MeshLab's types, 2020.09 or 2022.02).
//
// Every ReliefKit filter declares and reads its parameters through these helpers, so each value
// is checked the same way before anything touches the mesh: a number must be finite and in its
// documented range, an enum index must name a choice, a length is "auto" or a number of edge
// lengths. A violation stops the filter with a message that names the parameter (by the label the
// dialog shows and the name scripts use) and the accepted range.
#pragma once

#include "reliefkit/base/scale.h"
#include <rk_plugin.h>  // the adapter of the MeshLab configured (RELIEFKIT_MESHLAB_API)

namespace reliefkit::ml {

/// A length parameter: a text field holding "auto" or a number of edge lengths (the median edge
/// length of the scan's largest part), so a script works on a scan in any unit.
void add_length(RichParameterList& par, const char* name, const Length& default_value, const QString& label,
                const QString& help);

/// Reads a length parameter. Scripts written for ReliefKit 0.1 stored lengths as absolute values
/// (RichAbsPerc): those are still honoured as mesh units, with a log line saying how many edge
/// lengths they are and how to make the script portable.
Length read_length(FilterCall& call, const char* name, const QString& label, double lo_edges, double hi_edges);

/// A finite number in [lo, hi].
double read_float(FilterCall& call, const char* name, const QString& label, double lo, double hi);
/// A whole number in [lo, hi].
int read_int(FilterCall& call, const char* name, const QString& label, int lo, int hi);
/// An enum index in [0, count).
int read_enum(FilterCall& call, const char* name, const QString& label, int count);
bool read_bool(FilterCall& call, const char* name, const QString& label);

}  // namespace reliefkit::ml

namespace reliefkit::ml {

/// The pre-smoothing parameter every curvature-based filter has ("presmoothing", default auto).
void add_presmoothing(RichParameterList& par);
Length read_presmoothing(FilterCall& call);

/// The base-surface scale of the filters that use base normals ("base_scale", default auto).
void add_base_scale(RichParameterList& par);
Length read_base_scale(FilterCall& call);

/// "lift": how far (edge lengths) curve layers are lifted off the surface for display.
/// "Minimum curve length" (min_length), in edge lengths: the curve filters' dash removal (drop_dashes).
void add_min_length(RichParameterList& par, double default_edges);
double read_min_length(FilterCall& call);
void add_lift(RichParameterList& par);
double read_lift(FilterCall& call);

/// One log line on the scale and noise a filter measured and the pre-smoothing it used.
QString scale_summary(const MeshScale& scale, const NoiseEstimate& noise, double presmoothing, const Length& asked);

}  // namespace reliefkit::ml
