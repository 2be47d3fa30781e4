// ReliefKit — the thin MeshLab 2020.09 adapter shared by all ReliefKit plugins.
//
// A plugin is one table of FilterSpec entries (name, help, menu class, parameters, apply);
// this base class answers every MeshFilterInterface call from the table, so adding a filter
// touches one place. Everything that depends on MeshLab's plugin interface lives in this folder:
// a later MeshLab release line (FilterPlugin, new applyFilter signature, exceptions) needs a new
// version of these two files only.
#pragma once

#include <common/interfaces.h>

#include <functional>
#include <vector>

namespace reliefkit::ml {

/// What an apply function gets. Errors are reported by throwing (reliefkit::InputError or any
/// std::exception); the adapter turns them into MeshLab's error message and a log line.
struct FilterCall {
  MeshDocument& doc;
  MeshModel* current;  // the current layer; null only for a filter that needs none (needs_mesh false)
  MeshModel& mesh() const { return *current; }
  const RichParameterList& params;
  vcg::CallBackPos* progress;
  std::function<void(const QString&)> log;
};

struct FilterSpec {
  int id;
  QString name;  // exact name: users' .mlx scripts call filters by it
  QString info;  // HTML help shown in the filter dialog
  MeshFilterInterface::FilterClass menu;
  int preconditions;   // MeshModel::MM_* the filter needs
  int postconditions;  // MeshModel::MM_* the filter changes
  std::function<void(MeshModel&, RichParameterList&)> parameters;
  std::function<void(FilterCall&)> apply;
  /// The filter adds layers (curves, a smoothed copy). MeshLab 2020.09 cannot take back the
  /// layers a Preview adds, so such filters are not previewable.
  bool adds_layers = false;
  /// False for a filter that makes its layers from other input (a drawing): it runs in an empty
  /// document too (MeshLab's Create menu), with `current` null.
  bool needs_mesh = true;
};

/// A log line as MeshLab's log window shows it unchanged (no character read as markup).
QString log_text(QString line);

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
