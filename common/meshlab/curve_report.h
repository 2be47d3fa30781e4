// What a curve filter tells its user of each curve layer it made: its pieces, the share of its
// length in dashes and its density, as a log line, a warning when dashes dominate, and a
// "Record:" line that reliefkit-batch keeps in each file's record.
#pragma once

#include <QString>

#include "filter_spec.h"
#include "reliefkit/base/curve_selection.h"

namespace reliefkit::ml {

/// More than this share of a layer's length in dashes is worth a warning: the layer needs cleaning.
constexpr double kDashShareWarning = 0.10;

/// `what`: the layer's curves in words ("relief edges"); `key`: their name in the record
/// ("relief_edges"); `edge`: the mesh's mean edge length; `faces`: its face count.
CurveStatistics log_curve_statistics(FilterCall& call, const QString& what, const QString& key, const Polylines& curves,
                                     double edge, long long faces);

}  // namespace reliefkit::ml
