// reliefkit-batch — MeshLab 2020.09 for the worker (PluginManager, MeshFilterInterface, its IO
// plugins, as meshlabserver uses them, without an OpenGL context). See meshlab_session.h.
#include <QApplication>
#include <QDir>
#include <QFileInfo>
#include <common/GLLogStream.h>
#include <common/pluginmanager.h>

#include <cstdio>
#include <stdexcept>

#include "meshlab_session.h"

namespace reliefkit::batch {

struct MeshLabSession::Impl {
  RichParameterList globals;
  PluginManager plugins;
  QAction* action(const QString& name) const {
    QAction* a = plugins.actionFilterMap.value(name, nullptr);
    if (!a) throw std::runtime_error("no filter is called \"" + name.toStdString() + "\" (names are exact; --list-filters)");
    return a;
  }
};

MeshLabSession::MeshLabSession(const std::string& folder) : impl_(std::make_unique<Impl>()) {
  start_application();
  if (!QDir(QString::fromStdString(folder)).exists())
    throw std::runtime_error("MeshLab's plugin folder " + folder + " does not exist (--plugins)");
  impl_->plugins.loadPlugins(impl_->globals, QDir(QString::fromStdString(folder)));
}
MeshLabSession::~MeshLabSession() = default;

bool MeshLabSession::can_read(const QString& ext) const { return impl_->plugins.allKnowInputFormats.contains(ext.toLower()); }
bool MeshLabSession::can_write(const QString& ext) const { return impl_->plugins.allKnowOutputFormats.contains(ext.toLower()); }

MeshModel& MeshLabSession::import_mesh(MeshDocument& doc, const QString& path) {
  const QFileInfo fi(path);
  MeshIOInterface* io = impl_->plugins.allKnowInputFormats[fi.suffix().toLower()];
  MeshModel* mm = doc.addNewMesh(fi.absoluteFilePath(), fi.completeBaseName());
  RichParameterList pre;
  io->initPreOpenParameter(fi.suffix(), fi.absoluteFilePath(), pre);
  pre.join(impl_->globals);
  int mask = 0;
  const QString cwd = QDir::currentPath();
  QDir::setCurrent(fi.absolutePath());  // textures and materials beside the file
  const bool ok = io->open(fi.suffix(), fi.absoluteFilePath(), *mm, mask, pre);
  QDir::setCurrent(cwd);
  if (!ok) throw std::runtime_error("MeshLab could not read the file (" + io->errorMsg().toStdString() + ")");
  if (mask & vcg::tri::io::Mask::IOM_VERTNORMAL) {
    vcg::tri::UpdateNormal<CMeshO>::PerFace(mm->cm);
    vcg::tri::UpdateBounding<CMeshO>::Box(mm->cm);
  } else {
    mm->UpdateBoxAndNormals();
  }
  mm->updateDataMask(MeshModel::MM_VERTNORMAL);
  return *mm;
}

void MeshLabSession::save_mesh(MeshModel& mm, const QString& path) {
  QString format = QFileInfo(path).suffix().toLower();
  MeshIOInterface* io = impl_->plugins.allKnowOutputFormats.value(format, nullptr);
  if (!io) throw std::runtime_error("MeshLab has no writer for ." + format.toStdString() + " files");
  RichParameterList save;
  io->initSaveParameter(format, mm, save);
  if (save.hasParameter("Binary")) save.setValue("Binary", BoolValue(true));
  int capability = 0, defaults = 0;
  io->GetExportMaskCapability(format, capability, defaults);
  if (!io->save(format, path, mm, export_mask(mm) & capability, save))
    throw std::runtime_error("writing " + path.toStdString() + " failed (" + io->errorMsg().toStdString() + ")");
}

bool MeshLabSession::has_filter(const QString& name) const { return impl_->plugins.actionFilterMap.contains(name); }

RichParameterList MeshLabSession::default_parameters(const QString& name, MeshDocument& doc) {
  QAction* a = impl_->action(name);
  RichParameterList list;
  qobject_cast<MeshFilterInterface*>(a->parent())->initParameterSet(a, doc, list);
  return list;
}

bool MeshLabSession::apply(const QString& name, MeshDocument& doc, const RichParameterList& params,
                           vcg::CallBackPos* progress, QStringList& log, std::string& error) {
  QAction* a = impl_->action(name);
  MeshFilterInterface* f = qobject_cast<MeshFilterInterface*>(a->parent());
  GLLogStream stream;
  f->setLog(&stream);
  if (doc.mm()) doc.mm()->updateDataMask(f->getRequirements(a));
  doc.setBusy(true);
  const bool ok = f->applyFilter(a, doc, params, progress);
  doc.setBusy(false);
  stream.print(log);
  f->setLog(nullptr);
  if (!ok) error = f->errorMsg().toStdString();
  return ok;
}

QStringList MeshLabSession::filter_names() const { return impl_->plugins.actionFilterMap.keys(); }


}  // namespace reliefkit::batch
