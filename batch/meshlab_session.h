// reliefkit-batch — what the worker needs of the installed MeshLab, in the same words for both
// release lines: MeshLab 2020.09 (meshlab_session_2020.cpp: PluginManager, MeshFilterInterface)
// and 2022.02 / 2025.07 (meshlab_session_filterplugin.cpp: the plugin manager singleton,
// FilterPlugin, MLException).
// RELIEFKIT_MESHLAB_API chooses the file; worker_meshlab.cpp uses only this.
#pragma once

#include <QStringList>
#include <memory>
#include <string>
#include <vector>

#include <meshlab_api.h>  // MeshDocument, MeshModel, RichParameterList of the MeshLab configured

namespace reliefkit::batch {

/// The application object MeshLab's plugins expect (offscreen: no X display), made once; Qt's
/// debugging output dropped.
void start_application();

/// MeshLab's plugins (ours among them) loaded from `folder`, once per process.
class MeshLabSession {
 public:
  explicit MeshLabSession(const std::string& folder);
  ~MeshLabSession();

  bool can_read(const QString& extension) const;
  bool can_write(const QString& extension) const;
  /// The file as a new layer (normals and bounding box updated); throws with MeshLab's reason.
  MeshModel& import_mesh(MeshDocument& doc, const QString& path);
  /// Writes the layer with its vertex colours, quality and normals (and edges, where the format
  /// has them); throws with MeshLab's reason.
  void save_mesh(MeshModel& mesh, const QString& path);

  /// True when a filter has this exact name.
  bool has_filter(const QString& name) const;
  /// The filter's parameters at their defaults for this document.
  RichParameterList default_parameters(const QString& name, MeshDocument& doc);
  /// Applies the filter; false with `error` set when it fails. Its log lines go to `log`.
  bool apply(const QString& name, MeshDocument& doc, const RichParameterList& params, vcg::CallBackPos* progress,
             QStringList& log, std::string& error);

  /// Every filter's name, sorted.
  QStringList filter_names() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The vcglib export mask for a layer: normals, and its vertex colours and quality, face colours
/// and quality, edges where it has them.
int export_mask(const MeshModel& mesh);

/// The document's layers in order.
std::vector<MeshModel*> layers(MeshDocument& doc);

/// Sets parameter `p` of `list` from its text (a number, true/false, an enum's index or label,
/// "x,y,z", a colour name or #rrggbb, a path); throws with the reason when the text does not fit
/// its type.
void set_from_text(RichParameterList& list, const RichParameter& p, const QString& text);

/// The parameter's value as text, the same for both release lines ("true", "3", "0.25", "auto",
/// "1,0,0", "#ff0000"): the records say with what values each filter ran.
QString parameter_text(const RichParameter& p);

/// Replaces "{input}" in the text and file parameters by the input file's path and "{output}" by
/// the folder of its outputs.
void substitute_input(RichParameterList& list, const QString& input, const QString& output);

}  // namespace reliefkit::batch
