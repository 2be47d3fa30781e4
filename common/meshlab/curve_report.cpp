#include "curve_report.h"

#include "mesh_bridge.h"

namespace reliefkit::ml {

CurveStatistics log_curve_statistics(FilterCall& call, const QString& what, const QString& key, const Polylines& curves,
                                     double edge, long long faces) {
  const CurveStatistics st = curve_statistics(curves, edge, faces);
  call.log(QString("%1: %2 pieces, %3 edge lengths per 1,000 faces; %4 % of the length in dashes (pieces shorter "
                   "than %5 edge lengths).")
               .arg(what.left(1).toUpper() + what.mid(1))
               .arg(thousands(st.pieces))
               .arg(st.length_per_kface, 0, 'f', 1)
               .arg(100 * st.dash_share(), 0, 'f', 1)
               .arg(kDashEdges, 0, 'g', 3));
  if (st.dash_share() > kDashShareWarning)
    call.log(QString("Warning: %1 % of the %2' length lies in %3 dashes: the layer needs cleaning by hand. Raise "
                     "\"Minimum curve length\" or the strength threshold, or pre-smooth more, to keep the long lines.")
                 .arg(100 * st.dash_share(), 0, 'f', 0)
                 .arg(what)
                 .arg(thousands(st.dashes)));
  call.log(QString("Record: %1_pieces=%2; %1_dash_share=%3; %1_length_per_kface=%4")
               .arg(key)
               .arg(st.pieces)
               .arg(st.dash_share(), 0, 'f', 4)
               .arg(st.length_per_kface, 0, 'f', 2));
  return st;
}

}  // namespace reliefkit::ml
