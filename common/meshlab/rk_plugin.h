// ReliefKit — the thin MeshLab 2020.09 adapter shared by all ReliefKit plugins (MeshFilterInterface).
//
// A plugin is one table of FilterSpec entries (name, help, menu class, parameters, apply);
// this base class answers every MeshFilterInterface call from the table, so adding a filter
// touches one place. Everything that depends on MeshLab's plugin interface lives in these two
// files; common/meshlab_filterplugin/rk_plugin.h is the same for the FilterPlugin of MeshLab
// 2022.02 and 2025.07 (chosen at configure time: RELIEFKIT_MESHLAB_API).
#pragma once

#include "meshlab_api.h"

#include <functional>
#include <vector>

#include "filter_spec.h"

namespace reliefkit::ml {

class ReliefKitPlugin : public QObject, public MeshFilterInterface {
 public:
  explicit ReliefKitPlugin(QString plugin_name, std::vector<FilterSpec> filters);

  QString pluginName() const override { return plugin_name_; }
  QString filterName(FilterIDType id) const override;
  QString filterInfo(FilterIDType id) const override;
  FilterClass getClass(QAction* a) override;
  FILTER_ARITY filterArity(QAction*) const override { return SINGLE_MESH; }
  int getPreConditions(QAction* a) const override;
  int postCondition(QAction* a) const override;
  void initParameterSet(QAction* a, MeshModel& m, RichParameterList& par) override;
  bool applyFilter(QAction* a, MeshDocument& md, const RichParameterList& par, vcg::CallBackPos* cb) override;

 private:
  const FilterSpec& spec(FilterIDType id) const;
  QString plugin_name_;
  std::vector<FilterSpec> filters_;
};

}  // namespace reliefkit::ml

/// In each plugin class, after Q_OBJECT: what makes it a filter plugin of this MeshLab.
#define RELIEFKIT_FILTER_PLUGIN                           \
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID) \
  Q_INTERFACES(MeshFilterInterface)
