// reliefkit-batch — one file through MeshLab's filters, with either MeshLab release line
// (meshlab_session.h). See worker.h.
#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <common/filterscript.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>

#include "meshlab_session.h"
#include "worker.h"

namespace fs = std::filesystem;

namespace reliefkit::batch {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The filter being applied, for the progress lines (vcg::CallBackPos is a plain function).
std::string g_filter;
int g_last_percent = -100;
bool print_progress(const int percent, const char* what) {
  if (percent >= g_last_percent + 10 || percent < g_last_percent) {
    std::printf("  %s: %3d %% %s\n", g_filter.c_str(), percent, what ? what : "");
    std::fflush(stdout);
    g_last_percent = percent;
  }
  return true;
}

struct Step {
  QString filter;
  RichParameterList given;  // from the script; the rest at the defaults
};

std::vector<Step> steps_of(const Recipe& recipe) {
  std::vector<Step> steps;
  if (recipe.script.empty()) return {{QString::fromStdString(recipe.filter), RichParameterList()}};
  FilterScript script;
  if (!script.open(QString::fromStdString(recipe.script)))
    throw std::runtime_error("the filter script " + recipe.script + " could not be read");
  for (FilterNameParameterValuesPair& pair : script) steps.push_back({pair.filterName(), pair.second});
  return steps;
}

// The file's outputs folder, <output>/<relative path without extension>, made.
fs::path outputs_folder(const WorkerRequest& request) {
  const fs::path outputs = fs::path(request.output) / fs::path(request.relative).replace_extension();
  fs::create_directories(outputs);
  return outputs;
}

// The parameters of one step: the filter's defaults for this document, the script's values, the
// command line's name=value, "{input}" replaced by the file's path and "{output}" by its outputs' folder.
RichParameterList parameters_of(MeshLabSession& ml, MeshDocument& doc, const Step& step, const WorkerRequest& request) {
  RichParameterList list = ml.default_parameters(step.filter, doc);
  for (RichParameter& p : list)
    if (step.given.hasParameter(p.name())) list.setValue(p.name(), step.given.getParameterByName(p.name()).value());
  if (request.recipe.script.empty())
    for (const auto& [name, text] : request.recipe.parameters) {
      const QString n = QString::fromStdString(name);
      if (!list.hasParameter(n)) throw std::runtime_error("the filter " + step.filter.toStdString() + " has no parameter " + name);
      set_from_text(list, list.getParameterByName(n), QString::fromStdString(text));
    }
  substitute_input(list, QFileInfo(QString::fromStdString(request.file)).absoluteFilePath(),
                   QString::fromStdString(outputs_folder(request).string()));
  return list;
}

// A layer's name as a file name: "coin – demarcating curves" -> "coin-demarcating_curves".
std::string safe_name(QString label) {
  label.replace(QString::fromUtf8(" \u2013 "), "-");
  for (QChar& c : label)
    if (c == ' ') c = '_';
    else if (!(c.isLetterOrNumber() || c == '-' || c == '_' || c == '.')) c = '-';
  return label.isEmpty() ? std::string("layer") : label.toStdString();
}

// Layers a filter made (a relief from a drawing) have no file; each is given one in the outputs
// folder, so that what a later filter writes "beside the mesh's file" goes there too.
void place_unnamed_layers(MeshDocument& doc, const WorkerRequest& request) {
  for (MeshModel* mm : layers(doc))
    if (mm->fullName().isEmpty())
      mm->setFileName(QString::fromStdString((outputs_folder(request) / (safe_name(mm->label()) + ".ply")).string()));
}

// One step applied, its log printed and its warnings kept; false with `error` set when it fails.
bool apply_step(MeshLabSession& ml, MeshDocument& doc, const Step& step, const WorkerRequest& request, FileResult& result) {
  if (!ml.has_filter(step.filter))
    throw std::runtime_error("no filter is called \"" + step.filter.toStdString() + "\" (names are exact; --list-filters)");
  place_unnamed_layers(doc, request);
  const RichParameterList params = parameters_of(ml, doc, step, request);
  g_filter = step.filter.toStdString();
  g_last_percent = -100;
  std::printf("  %s\n", g_filter.c_str());
  std::fflush(stdout);
  const auto t0 = Clock::now();
  QStringList lines;
  std::string error;
  const bool ok = ml.apply(step.filter, doc, params, print_progress, lines, error);
  std::vector<std::string> used;
  for (const RichParameter& p : params) used.push_back(p.name().toStdString() + "=" + parameter_text(p).toStdString());
  result.filters.push_back({g_filter, since(t0), ok, used});
  for (const QString& line : lines) {
    std::printf("  %s: %s\n", g_filter.c_str(), qUtf8Printable(line));
    if (line.contains("warning", Qt::CaseInsensitive)) result.warnings.push_back(g_filter + ": " + line.toStdString());
    if (line.startsWith("Record: "))
      for (const QString& item : line.mid(8).split("; ", Qt::SkipEmptyParts)) result.record.push_back(item.trimmed().toStdString());
  }
  std::fflush(stdout);
  if (!ok) result.error = g_filter + ": " + error;
  return ok;
}

// One layer written beside the others of its file: <output>/<relative path without extension>/<layer>.<ext>.
LayerOutput save_layer(MeshLabSession& ml, MeshModel& mm, const WorkerRequest& request) {
  const std::string ext = mm.cm.fn > 0 ? request.save.mesh_format : mm.cm.en > 0 ? "obj" : "ply";
  const fs::path rel = fs::path(request.relative).replace_extension() / (safe_name(mm.label()) + "." + ext);
  const fs::path path = fs::path(request.output) / rel;
  fs::create_directories(path.parent_path());
  ml.save_mesh(mm, QString::fromStdString(path.string()));
  return {mm.label().toStdString(), rel.generic_string(), long(mm.cm.vn), long(mm.cm.fn), long(mm.cm.en)};
}

void save_layers(MeshLabSession& ml, MeshDocument& doc, size_t layers_before, const WorkerRequest& request, FileResult& result) {
  const std::string& which = request.save.layers;
  const std::vector<MeshModel*> all = layers(doc);
  for (size_t k = 0; k < all.size(); ++k) {
    MeshModel* mm = all[k];
    const bool wanted = which == "all" || (which == "new" && k >= layers_before) || (which == "current" && mm == doc.mm());
    if (!wanted) continue;
    if (mm->cm.vn == 0) {  // a filter that found nothing (its log says why): no empty file
      result.warnings.push_back("layer \"" + mm->label().toStdString() + "\" is empty: not written");
      continue;
    }
    result.outputs.push_back(save_layer(ml, *mm, request));
  }
}

void run_recipe(MeshLabSession& ml, const WorkerRequest& request, FileResult& result) {
  // Files the filters derive from their inputs (a drawing's interpretation file) go to the
  // outputs folder, not beside the input (derived_file_folder in common/meshlab/filter_spec.h).
  setenv("RELIEFKIT_OUTPUT_FOLDER", outputs_folder(request).c_str(), 1);
  MeshDocument doc;
  const QString file = QString::fromStdString(request.file);
  if (ml.can_read(QFileInfo(file).suffix())) {
    MeshModel& mm = ml.import_mesh(doc, file);
    // The layer's file is taken to be in the outputs folder, so that what a filter writes "beside
    // the mesh's file" (a plate) goes there, never into the collection.
    mm.setFileName(QString::fromStdString((outputs_folder(request) / fs::path(request.file).filename()).string()));
    result.vertices = mm.cm.vn;
    result.faces = mm.cm.fn;
  }
  const size_t layers_before = layers(doc).size();
  for (const Step& step : steps_of(request.recipe))
    if (!apply_step(ml, doc, step, request, result)) return;
  save_layers(ml, doc, layers_before, request, result);
  result.status = "ok";
}
}  // namespace

FileResult process_file(const WorkerRequest& request) {
  const auto t0 = Clock::now();
  FileResult result;
  result.file = request.relative;
  result.shard = request.shard;
  result.status = "failed";
  try {
    MeshLabSession ml(request.plugins);
    run_recipe(ml, request, result);
  } catch (const std::exception& e) {
    result.error = e.what();
  }
  // One line: the summary's CSV and the progress lines read better so.
  result.error = QString::fromStdString(result.error).simplified().toStdString();
  result.seconds = since(t0);
  return result;
}

std::string list_filters(const std::string& plugins) {
  MeshLabSession ml(plugins);
  QStringList names = ml.filter_names();
  names.sort();
  std::string out;
  for (const QString& n : names) out += n.toStdString() + "\n";
  return out;
}

std::string default_plugin_folder() {
  start_application();
  const QString mine = QDir::cleanPath(QCoreApplication::applicationDirPath() + "/../lib/x86_64-linux-gnu/meshlab/plugins");
  return QDir(mine).exists() ? mine.toStdString() : std::string(RELIEFKIT_MESHLAB_PLUGINS);
}

}  // namespace reliefkit::batch
