// ReliefKit — the MeshLab 2022.02 and 2025.07 adapter (FilterPlugin). See rk_plugin.h.
#include "rk_plugin.h"

namespace reliefkit::ml {

ReliefKitPlugin::ReliefKitPlugin(QString plugin_name, std::vector<FilterSpec> filters)
    : plugin_name_(std::move(plugin_name)), filters_(std::move(filters)) {
  for (const auto& f : filters_) typeList.push_back(f.id);
  for (ActionIDType id : types()) actionList.push_back(new QAction(filterName(id), this));
}

const FilterSpec& ReliefKitPlugin::spec(ActionIDType id) const { return spec_of(filters_, id); }

QString ReliefKitPlugin::filterName(ActionIDType id) const { return spec(id).name; }
QString ReliefKitPlugin::filterInfo(ActionIDType id) const { return spec(id).info; }
FilterPlugin::FilterClass ReliefKitPlugin::getClass(const QAction* a) const { return spec(ID(a)).menu; }
int ReliefKitPlugin::getPreConditions(const QAction* a) const { return spec(ID(a)).preconditions; }
int ReliefKitPlugin::postCondition(const QAction* a) const { return post_conditions(spec(ID(a))); }

RichParameterList ReliefKitPlugin::initParameterList(const QAction* a, const MeshModel& m) {
  RichParameterList par;
  const FilterSpec& s = spec(ID(a));
  if (s.parameters) s.parameters(m, par);
  return par;
}

// A filter that needs no mesh (a drawing's) is offered in an empty document too: its parameters
// must not depend on a current layer that is not there (FilterPlugin's default would read it).
RichParameterList ReliefKitPlugin::initParameterList(const QAction* a, const MeshDocument& md) {
  if (md.mm()) return initParameterList(a, *md.mm());
  static const MeshModel none(-1, "", "");
  return initParameterList(a, none);
}

std::map<std::string, QVariant> ReliefKitPlugin::applyFilter(const QAction* a, const RichParameterList& par,
                                                             MeshDocument& md, unsigned int& postConditionMask,
                                                             vcg::CallBackPos* cb) {
  const FilterSpec& s = spec(ID(a));
  FilterCall call{md, md.mm(), par, cb, [this](const QString& line) { log(qUtf8Printable(log_text(line))); }};
  const QString error = run_filter(s, call);
  if (!error.isEmpty()) {
    log(GLLogStream::SYSTEM, qUtf8Printable(log_text(s.name + " failed: " + error)));
    throw MLException(error);
  }
  postConditionMask = postCondition(a);
  return {};
}

}  // namespace reliefkit::ml
