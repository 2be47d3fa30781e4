#include "rk_plugin.h"

#include "reliefkit/base/memory.h"

#include <cstdlib>
#include <exception>

#include "reliefkit/base/mesh.h"
#include "reliefkit/base/work_counts.h"

namespace reliefkit::ml {

// About what a filter run allocates per face of its mesh, reserved with huge pages at its start
// (RetainedMemory). Peak resident memory above loading a 1 M-face relief, `/usr/bin/time -f %M`
// around scripts/meshlabserver: the curvature filter 160 MB, Relief Edges 400 MB.
constexpr size_t kHeapBytesPerFace = 400;

ReliefKitPlugin::ReliefKitPlugin(QString plugin_name, std::vector<FilterSpec> filters)
    : plugin_name_(std::move(plugin_name)), filters_(std::move(filters)) {
  for (const auto& f : filters_) typeList << f.id;
  for (FilterIDType id : types()) actionList << new QAction(filterName(id), this);
}

const FilterSpec& ReliefKitPlugin::spec(FilterIDType id) const {
  for (const auto& f : filters_)
    if (f.id == id) return f;
  return filters_.front();  // MeshLab only asks for ids it got from types()
}

QString ReliefKitPlugin::filterName(FilterIDType id) const { return spec(id).name; }
QString ReliefKitPlugin::filterInfo(FilterIDType id) const { return spec(id).info; }
MeshFilterInterface::FilterClass ReliefKitPlugin::getClass(QAction* a) { return spec(ID(a)).menu; }
int ReliefKitPlugin::getPreConditions(QAction* a) const { return spec(ID(a)).preconditions; }
int ReliefKitPlugin::postCondition(QAction* a) const {
  const FilterSpec& s = spec(ID(a));
  // MeshLab's dialog offers Preview unless the filter says it changes the vertex or face count.
  return s.adds_layers ? s.postconditions | MeshModel::MM_VERTNUMBER | MeshModel::MM_FACENUMBER : s.postconditions;
}

QString log_text(QString line) {
  // MeshLab's log window reads its lines as rich text: "<=" and ">=" would start tags.
  line.replace("<=", QString::fromUtf8("\u2264")).replace(">=", QString::fromUtf8("\u2265"));
  line.replace('<', QString::fromUtf8("\u2039")).replace('>', QString::fromUtf8("\u203a"));
  return line;
}

void ReliefKitPlugin::initParameterSet(QAction* a, MeshModel& m, RichParameterList& par) {
  const FilterSpec& s = spec(ID(a));
  if (s.parameters) s.parameters(m, par);
}

bool ReliefKitPlugin::applyFilter(QAction* a, MeshDocument& md, const RichParameterList& par,
                                  vcg::CallBackPos* cb) {
  const FilterSpec& s = spec(ID(a));
  auto fail = [&](const QString& msg) {
    errorMessage = msg;
    // meshlabserver does not print errorMsg(): log it as well, so batch users see why.
    Log(GLLogStream::SYSTEM, qUtf8Printable(log_text(s.name + " failed: " + msg)));
    return false;
  };
  if (md.mm() == nullptr && s.needs_mesh) return fail("there is no mesh layer to work on; open a mesh first.");
  try {
    reliefkit::reset_work_counts();
    // One run: freed blocks reused, huge pages on the heap it will use, all returned at the end.
    const size_t faces = md.mm() ? size_t(std::max(0, md.mm()->cm.FN())) : 0;
    const reliefkit::RetainedMemory retained(faces * kHeapBytesPerFace);
    FilterCall call{md, md.mm(), par, cb, [this](const QString& line) { Log(qUtf8Printable(log_text(line))); }};
    s.apply(call);
    if (std::getenv("RELIEFKIT_WORK_COUNTS")) call.log("Work counts of " + s.name + ": " + QString::fromStdString(reliefkit::work_counts().summary()));
    return true;
  } catch (const reliefkit::InputError& e) {
    return fail(QString::fromUtf8(e.what()));
  } catch (const std::bad_alloc&) {
    return fail("not enough memory for this mesh.");
  } catch (const std::exception& e) {
    return fail(QString("internal error: ") + e.what());
  }
}

}  // namespace reliefkit::ml
