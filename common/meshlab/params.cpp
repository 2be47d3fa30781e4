#include "params.h"

#include <cmath>

#include "reliefkit/base/mesh.h"

namespace reliefkit::ml {
namespace {

const RichParameter& parameter(FilterCall& call, const char* name, const QString& label) {
  if (!call.params.hasParameter(name))
    throw InputError(qUtf8Printable(QString("the parameter \"%1\" (%2) is missing from the script.").arg(name, label)));
  return call.params.getParameterByName(name);
}

QString where(const char* name, const QString& label) { return QString("%1 (\"%2\")").arg(label, name); }

}  // namespace

void add_length(RichParameterList& par, const char* name, const Length& default_value, const QString& label,
                const QString& help) {
  par.addParam(RichString(name, QString::fromStdString(format_length(default_value)), label,
                          help + " In edge lengths (the scan's typical edge length), or \"auto\"."));
}

Length read_length(FilterCall& call, const char* name, const QString& label, double lo_edges, double hi_edges) {
  const RichParameter& p = parameter(call, name, label);
  if (p.value().isString())
    return parse_length(p.value().getString().toStdString(), qUtf8Printable(where(name, label)), lo_edges, hi_edges);
  if (p.value().isFloat()) {
    const double v = p.value().getFloat();
    if (!std::isfinite(v) || v < 0)
      throw InputError(qUtf8Printable(
          QString("%1 must be \"auto\" or a non-negative number of edge lengths (got %2).").arg(where(name, label)).arg(v)));
    call.log(QString("%1 is given as an absolute length, %2 mesh units, as scripts of ReliefKit 0.1 stored it: it is "
                     "used as such. For a script that works on scans in any unit, give it as type RichString with "
                     "\"auto\" or a number of edge lengths.")
                 .arg(where(name, label))
                 .arg(v, 0, 'g', 6));
    return Length::in_units(v);
  }
  throw InputError(qUtf8Printable(
      QString("%1 must be \"auto\" or a number of edge lengths (the script gives another type).").arg(where(name, label))));
}

double read_float(FilterCall& call, const char* name, const QString& label, double lo, double hi) {
  const RichParameter& p = parameter(call, name, label);
  if (!p.value().isFloat())
    throw InputError(qUtf8Printable(QString("%1 must be a number (the script gives another type).").arg(where(name, label))));
  const double v = p.value().getFloat();
  require_range(v, qUtf8Printable(where(name, label)), lo, hi);
  return v;
}

int read_int(FilterCall& call, const char* name, const QString& label, int lo, int hi) {
  const RichParameter& p = parameter(call, name, label);
  if (!p.value().isInt())
    throw InputError(qUtf8Printable(QString("%1 must be a whole number (the script gives another type).").arg(where(name, label))));
  const int v = p.value().getInt();
  require_range(v, qUtf8Printable(where(name, label)), lo, hi);
  return v;
}

int read_enum(FilterCall& call, const char* name, const QString& label, int count) {
  const RichParameter& p = parameter(call, name, label);
  if (!p.value().isInt())  // an enum is an int (MeshLab 2020.09: EnumValue derives IntValue)
    throw InputError(qUtf8Printable(QString("%1 must be a choice index (the script gives another type).").arg(where(name, label))));
  const int v = p.value().getInt();
  if (v < 0 || v >= count)
    throw InputError(qUtf8Printable(
        QString("%1 must be a choice between 0 and %2 (got %3).").arg(where(name, label)).arg(count - 1).arg(v)));
  return v;
}

bool read_bool(FilterCall& call, const char* name, const QString& label) {
  const RichParameter& p = parameter(call, name, label);
  if (!p.value().isBool())
    throw InputError(qUtf8Printable(QString("%1 must be true or false (the script gives another type).").arg(where(name, label))));
  return p.value().getBool();
}

}  // namespace reliefkit::ml

namespace reliefkit::ml {

void add_presmoothing(RichParameterList& par) {
  add_length(par, "presmoothing", Length::automatic(), "Pre-smoothing",
             "Removes scanner noise finer than this before curvature is measured (a Gaussian scale). auto: chosen "
             "from the noise level measured on the scan (none on a clean mesh; the log says what was used). 0 "
             "turns it off; larger values keep only broader shapes.");
}

Length read_presmoothing(FilterCall& call) { return read_length(call, "presmoothing", "Pre-smoothing", 0, 100); }

void add_base_scale(RichParameterList& par) {
  add_length(par, "base_scale", Length::automatic(), "Base surface scale",
             "How far normals are averaged to find the smooth surface under the relief: about three times the width "
             "of the relief's features (letters, figures). auto: 15 edge lengths; Relief Edges and the prominent "
             "filters take more where the features they measure on the scan are wider (9 times their width).");
}

Length read_base_scale(FilterCall& call) { return read_length(call, "base_scale", "Base surface scale", 0.5, 10000); }

void add_min_length(RichParameterList& par, double default_edges) {
  par.addParam(RichFloat("min_length", float(default_edges), "Minimum curve length",
                         "Drops curve pieces shorter than this many edge lengths (specks of noise; pieces under 10 "
                         "edge lengths are the dashes the log counts). 0 keeps all."));
}

double read_min_length(FilterCall& call) { return read_float(call, "min_length", "Minimum curve length", 0, 1e6); }

void add_lift(RichParameterList& par) {
  par.addParam(RichFloat("lift", 0.2f, "Lift curves off the surface",
                         "Moves the points of the curve layer this many edge lengths along the surface normal, so "
                         "that MeshLab draws the curves over the surface without flicker. 0 keeps them exactly on "
                         "the surface."));
}

double read_lift(FilterCall& call) { return read_float(call, "lift", "Lift curves off the surface", 0, 10); }

QString scale_summary(const MeshScale& scale, const NoiseEstimate& noise, double presmoothing, const Length& asked) {
  QString parts = scale.parts > 1 ? QString(", %1 connected parts").arg(scale.parts) : QString();
  if (scale.debris_faces > 0)
    parts += QString(" (%1 faces of small parts left out of the statistics)").arg(scale.debris_faces);
  return QString("Edge length %1 (median of the largest part%2); noise %3 = %4 % of the edge length; pre-smoothing "
                 "%5 = %6 edge lengths (%7).")
      .arg(scale.edge, 0, 'g', 4)
      .arg(parts)
      .arg(noise.sigma, 0, 'g', 3)
      .arg(100 * noise.relative, 0, 'f', 1)
      .arg(presmoothing, 0, 'g', 4)
      .arg(scale.edge > 0 ? presmoothing / scale.edge : 0.0, 0, 'f', 2)
      .arg(asked.is_auto() ? QString("automatic, from the noise level") : QString("as given"));
}

}  // namespace reliefkit::ml
