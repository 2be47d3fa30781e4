// reliefkit-batch — the parts of the MeshLab session that read the same on both release lines
// (the application object, the export mask, parameter values as text and from text; the few
// value types only MeshLab 2020.09 has are under RELIEFKIT_MESHLAB_API == 2020). See
// meshlab_session.h.
#include <QApplication>

#include <cstdio>
#include <stdexcept>

#include "meshlab_session.h"

namespace reliefkit::batch {
namespace {

// Qt's and MeshLab's own messages: debugging output (the plugin folder, each log line again)
// dropped, warnings kept on stderr.
void quiet_messages(QtMsgType type, const QMessageLogContext&, const QString& message) {
  if (type == QtDebugMsg || type == QtInfoMsg || message.startsWith("QStandardPaths:")) return;
  std::fprintf(stderr, "%s\n", qUtf8Printable(message));
}

bool is_enum(const RichParameter& p) { return dynamic_cast<const RichEnum*>(&p) != nullptr; }
}  // namespace

void start_application() {
  static int argc = 1;
  static char name[] = "reliefkit-batch";
  static char* argv[] = {name, nullptr};
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  qInstallMessageHandler(quiet_messages);
  static QApplication app(argc, argv);
}

std::vector<MeshModel*> layers(MeshDocument& doc) { return ml::document_layers(doc); }

int export_mask(const MeshModel& mm) {
  int mask = vcg::tri::io::Mask::IOM_VERTNORMAL;
  if (mm.hasDataMask(MeshModel::MM_VERTQUALITY)) mask |= vcg::tri::io::Mask::IOM_VERTQUALITY;
  if (mm.hasDataMask(MeshModel::MM_VERTCOLOR)) mask |= vcg::tri::io::Mask::IOM_VERTCOLOR;
  if (mm.hasDataMask(MeshModel::MM_FACECOLOR)) mask |= vcg::tri::io::Mask::IOM_FACECOLOR;
  if (mm.hasDataMask(MeshModel::MM_FACEQUALITY)) mask |= vcg::tri::io::Mask::IOM_FACEQUALITY;
  if (mm.cm.en > 0) mask |= vcg::tri::io::Mask::IOM_EDGEINDEX;
  return mask;
}

// The number types: an enum's index or label, a float, an int. False when `p` is none of them.
bool set_number(RichParameterList& list, const RichParameter& p, const QString& text, bool& ok) {
  const Value& v = p.value();
  const QString name = p.name();
  if (is_enum(p)) {
    int index = text.toInt(&ok);
    if (!ok) ok = (index = static_cast<const RichEnum&>(p).enumvalues.indexOf(text)) >= 0;
#if RELIEFKIT_MESHLAB_API == 2020
    list.setValue(name, EnumValue(index));
  } else if (v.isAbsPerc()) {
    list.setValue(name, AbsPercValue(text.toFloat(&ok)));
  } else if (v.isDynamicFloat()) {
    list.setValue(name, DynamicFloatValue(text.toFloat(&ok)));
#else
    list.setValue(name, IntValue(index));
#endif
  } else if (v.isFloat()) {
    list.setValue(name, FloatValue(text.toFloat(&ok)));
  } else if (v.isInt()) {
    list.setValue(name, IntValue(text.toInt(&ok)));
  } else {
    return false;
  }
  return true;
}

void set_from_text(RichParameterList& list, const RichParameter& p, const QString& text) {
  const Value& v = p.value();
  bool ok = true;
  const QString name = p.name();
  if (v.isBool()) {
    const QString t = text.toLower();
    ok = t == "true" || t == "false" || t == "1" || t == "0";
    list.setValue(name, BoolValue(t == "true" || t == "1"));
  } else if (set_number(list, p, text, ok)) {
  } else if (v.isString()) {  // text (and, in 2022.02, file names)
    list.setValue(name, StringValue(text));
#if RELIEFKIT_MESHLAB_API == 2020
  } else if (v.isFileName()) {
    list.setValue(name, FileValue(text));
#endif
  } else if (v.isColor()) {
    ok = QColor(text).isValid();
    list.setValue(name, ColorValue(QColor(text)));
  } else if (ml::is_point3(v)) {
    const QStringList xyz = text.split(',');
    ok = xyz.size() == 3;
    if (ok) list.setValue(name, ml::Point3Value(Point3m(xyz[0].toFloat(), xyz[1].toFloat(), xyz[2].toFloat())));
  } else {
    throw std::runtime_error("parameter " + name.toStdString() + " cannot be given on the command line: use an .mlx script");
  }
  if (!ok) throw std::runtime_error("parameter " + name.toStdString() + ": \"" + text.toStdString() + "\" is not a valid value for it");
}

QString parameter_text(const RichParameter& p) {
  const Value& v = p.value();
  if (v.isBool()) return v.getBool() ? "true" : "false";
  if (v.isInt()) return QString::number(v.getInt());
  if (v.isFloat()) return QString::number(double(v.getFloat()), 'g', 7);
  if (v.isString()) return v.getString();
#if RELIEFKIT_MESHLAB_API == 2020
  if (v.isFileName()) return v.getFileName();
#endif
  if (v.isColor()) return v.getColor().name();
  if (ml::is_point3(v)) {
    const Point3m q = ml::point3_of(v);
    return QString("%1,%2,%3").arg(double(q[0]), 0, 'g', 7).arg(double(q[1]), 0, 'g', 7).arg(double(q[2]), 0, 'g', 7);
  }
  return "(" + p.name() + ")";
}

void substitute_input(RichParameterList& list, const QString& input, const QString& output) {
  auto filled = [&](QString text) { return text.replace("{input}", input).replace("{output}", output); };
  for (RichParameter& p : list) {
    if (p.value().isString() && p.value().getString().contains('{'))
      list.setValue(p.name(), StringValue(filled(p.value().getString())));
#if RELIEFKIT_MESHLAB_API == 2020
    if (p.value().isFileName() && p.value().getFileName().contains('{'))
      list.setValue(p.name(), FileValue(filled(p.value().getFileName())));
#endif
  }
}

}  // namespace reliefkit::batch
