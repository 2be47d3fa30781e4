// ReliefKit — the thin adapter for MeshLab 2022.02 and 2025.07 shared by all ReliefKit plugins
// (FilterPlugin: the same interface in both; the few names that differ are in meshlab_api.h).
//
// The same FilterSpec tables as MeshLab 2020.09's adapter (common/meshlab/rk_plugin.h, chosen at
// configure time: RELIEFKIT_MESHLAB_API) answer the FilterPlugin: parameters
// returned as a list, applyFilter's errors thrown as MLException, the log through
// MeshLabPluginLogger.
#pragma once

#include "meshlab_api.h"

#include <functional>
#include <vector>

#include "filter_spec.h"

namespace reliefkit::ml {

class ReliefKitPlugin : public QObject, public FilterPlugin {
 public:
  explicit ReliefKitPlugin(QString plugin_name, std::vector<FilterSpec> filters);

  QString pluginName() const override { return plugin_name_; }
  QString filterName(ActionIDType id) const override;
  QString filterInfo(ActionIDType id) const override;
  FilterClass getClass(const QAction* a) const override;
  FilterArity filterArity(const QAction*) const override { return SINGLE_MESH; }
  int getPreConditions(const QAction* a) const override;
  int postCondition(const QAction* a) const override;
  RichParameterList initParameterList(const QAction* a, const MeshModel& m) override;
  RichParameterList initParameterList(const QAction* a, const MeshDocument& md) override;
  std::map<std::string, QVariant> applyFilter(const QAction* a, const RichParameterList& par, MeshDocument& md,
                                              unsigned int& postConditionMask, vcg::CallBackPos* cb) override;

 private:
  const FilterSpec& spec(ActionIDType id) const;
  QString plugin_name_;
  std::vector<FilterSpec> filters_;
};

}  // namespace reliefkit::ml

/// In each plugin class, after Q_OBJECT: what makes it a filter plugin of this MeshLab.
#define RELIEFKIT_FILTER_PLUGIN                  \
  MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID) \
  Q_INTERFACES(FilterPlugin)
