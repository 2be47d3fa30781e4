// ReliefKit — what a filter is for both MeshLab adapters (2020.09: common/meshlab/rk_plugin.h,
// 2022.02 and 2025.07: common/meshlab_filterplugin/rk_plugin.h):
// the FilterSpec table entry, the call an apply function gets, and the run every filter shares
// (work counts, the heap reserved for it, its exceptions turned into a message).
#pragma once

#include <QString>
#include <chrono>
#include <functional>
#include <vector>

#include <meshlab_api.h>  // the MeshLab configured (RELIEFKIT_MESHLAB_API)

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

/// The seconds since t0, for a filter's log line.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct FilterSpec {
  int id;
  QString name;  // exact name: users' .mlx scripts call filters by it
  QString info;  // HTML help shown in the filter dialog
  FilterInterface::FilterClass menu;
  int preconditions;   // MeshModel::MM_* the filter needs
  int postconditions;  // MeshModel::MM_* the filter changes
  std::function<void(const MeshModel&, RichParameterList&)> parameters;
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

/// The entry with this id (MeshLab asks only for ids it got from the plugin: else the first).
const FilterSpec& spec_of(const std::vector<FilterSpec>& filters, int id);

/// What the filter tells MeshLab it changes: its post-conditions, and for a filter that adds
/// layers the vertex and face counts too (MeshLab's dialog offers Preview unless those change).
int post_conditions(const FilterSpec& s);

/// Runs `s` on `call`; empty on success, else the message for the user (the filter's InputError
/// verbatim, "not enough memory for this mesh.", or "internal error: ..." for anything else).
QString run_filter(const FilterSpec& s, FilterCall& call);

/// The folder for a file a filter derives from its input file (a drawing's interpretation file):
/// the input's own, or $RELIEFKIT_OUTPUT_FOLDER when set — reliefkit-batch sets it to each file's
/// outputs folder, so that a collection is never written to.
QString derived_file_folder(const QString& input);

}  // namespace reliefkit::ml
