// reliefkit-batch — MeshLab 2022.02 and 2025.07 for the worker (the plugin manager singleton, FilterPlugin,
// its IO plugins and load/save utilities, errors as MLException; no OpenGL context). See
// meshlab_session.h.
#include <QApplication>
#include <QDir>
#include <QFileInfo>
#include <common/GLLogStream.h>
#include <common/globals.h>
#include <common/mlexception.h>
#include <common/plugins/plugin_manager.h>
#include <common/utilities/load_save.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "meshlab_session.h"

namespace reliefkit::batch {
namespace {

PluginManager& plugins() { return meshlab::pluginManagerInstance(); }

QAction* action(const QString& name) {
  QAction* a = plugins().filterAction(name);
  if (!a) throw std::runtime_error("no filter is called \"" + name.toStdString() + "\" (names are exact; --list-filters)");
  return a;
}
}  // namespace

struct MeshLabSession::Impl {};

MeshLabSession::MeshLabSession(const std::string& folder) : impl_(std::make_unique<Impl>()) {
  start_application();
  if (!QDir(QString::fromStdString(folder)).exists())
    throw std::runtime_error("MeshLab's plugin folder " + folder + " does not exist (--plugins)");
  try {
    plugins().loadPlugins(QDir(QString::fromStdString(folder)));
  } catch (const MLException& e) {
    // MeshLab 2022.02 and 2025.07 load every plugin they can and then reports those it could not (a library of
    // theirs missing): the filters of the others work, as in its GUI after the same message.
    std::fprintf(stderr, "%s\n", QString::fromUtf8(e.what()).simplified().toUtf8().constData());
  }
}
MeshLabSession::~MeshLabSession() = default;

bool MeshLabSession::can_read(const QString& ext) const { return plugins().isInputMeshFormatSupported(ext.toLower()); }
bool MeshLabSession::can_write(const QString& ext) const { return plugins().isOutputMeshFormatSupported(ext.toLower()); }

MeshModel& MeshLabSession::import_mesh(MeshDocument& doc, const QString& path) {
  try {
    const std::list<MeshModel*> read = meshlab::loadMeshWithStandardParameters(QFileInfo(path).absoluteFilePath(), doc);
    if (read.empty()) throw std::runtime_error("MeshLab read no mesh from the file");
    // Named as MeshLab's GUI and 2020.09 name it (the file's name without its extension): the
    // filters name their layers after it.
    read.front()->setLabel(QFileInfo(path).completeBaseName());
    read.front()->updateDataMask(MeshModel::MM_VERTNORMAL);
    return *read.front();
  } catch (const MLException& e) {
    throw std::runtime_error(std::string("MeshLab could not read the file (") + e.what() + ")");
  }
}

void MeshLabSession::save_mesh(MeshModel& mm, const QString& path) {
  const QString format = QFileInfo(path).suffix().toLower();
  IOPlugin* io = plugins().outputMeshPlugin(format);
  if (!io) throw std::runtime_error("MeshLab has no writer for ." + format.toStdString() + " files");
  RichParameterList save = io->initSaveParameter(format, mm);
  if (save.hasParameter("Binary")) save.setValue("Binary", BoolValue(true));
  int capability = 0, defaults = 0;
  io->exportMaskCapability(format, capability, defaults);
  try {
    io->save(format, path, mm, export_mask(mm) & capability, save, nullptr);
  } catch (const MLException& e) {
    throw std::runtime_error("writing " + path.toStdString() + " failed (" + e.what() + ")");
  }
}

bool MeshLabSession::has_filter(const QString& name) const { return plugins().filterAction(name) != nullptr; }

RichParameterList MeshLabSession::default_parameters(const QString& name, MeshDocument& doc) {
  QAction* a = action(name);
  return plugins().getFilterPluginFromAction(a)->initParameterList(a, doc);
}

bool MeshLabSession::apply(const QString& name, MeshDocument& doc, const RichParameterList& params,
                           vcg::CallBackPos* progress, QStringList& log, std::string& error) {
  QAction* a = action(name);
  FilterPlugin* f = plugins().getFilterPluginFromAction(a);
  GLLogStream stream;
  f->setLog(&stream);
  if (doc.mm()) doc.mm()->updateDataMask(f->getRequirements(a));
  bool ok = true;
  unsigned int post = 0;
  doc.setBusy(true);
  try {
    f->applyFilter(a, params, doc, post, progress);
  } catch (const std::exception& e) {  // MLException, and what a filter of MeshLab's lets through
    ok = false;
    error = e.what();
  }
  doc.setBusy(false);
  stream.print(log);
  f->setLog(nullptr);
  return ok;
}

QStringList MeshLabSession::filter_names() const {
  QStringList names;
  for (FilterPlugin* f : plugins().filterPluginIterator())
    for (QAction* a : f->actions()) names << a->text();
  return names;
}


}  // namespace reliefkit::batch
