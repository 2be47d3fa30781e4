// ReliefKit — the MeshLab 2020.09 adapter (MeshFilterInterface). See rk_plugin.h.
#include "rk_plugin.h"

namespace reliefkit::ml {

ReliefKitPlugin::ReliefKitPlugin(QString plugin_name, std::vector<FilterSpec> filters)
    : plugin_name_(std::move(plugin_name)), filters_(std::move(filters)) {
  for (const auto& f : filters_) typeList << f.id;
  for (FilterIDType id : types()) actionList << new QAction(filterName(id), this);
}

const FilterSpec& ReliefKitPlugin::spec(FilterIDType id) const { return spec_of(filters_, id); }

QString ReliefKitPlugin::filterName(FilterIDType id) const { return spec(id).name; }
QString ReliefKitPlugin::filterInfo(FilterIDType id) const { return spec(id).info; }
MeshFilterInterface::FilterClass ReliefKitPlugin::getClass(QAction* a) { return spec(ID(a)).menu; }
int ReliefKitPlugin::getPreConditions(QAction* a) const { return spec(ID(a)).preconditions; }
int ReliefKitPlugin::postCondition(QAction* a) const { return post_conditions(spec(ID(a))); }

void ReliefKitPlugin::initParameterSet(QAction* a, MeshModel& m, RichParameterList& par) {
  const FilterSpec& s = spec(ID(a));
  if (s.parameters) s.parameters(m, par);
}

bool ReliefKitPlugin::applyFilter(QAction* a, MeshDocument& md, const RichParameterList& par,
                                  vcg::CallBackPos* cb) {
  const FilterSpec& s = spec(ID(a));
  FilterCall call{md, md.mm(), par, cb, [this](const QString& line) { Log(qUtf8Printable(log_text(line))); }};
  const QString error = run_filter(s, call);
  if (error.isEmpty()) return true;
  errorMessage = error;
  // meshlabserver does not print errorMsg(): log it as well, so batch users see why.
  Log(GLLogStream::SYSTEM, qUtf8Printable(log_text(s.name + " failed: " + error)));
  return false;
}

}  // namespace reliefkit::ml
