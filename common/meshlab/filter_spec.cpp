// ReliefKit — the run every filter shares, for both MeshLab adapters. See filter_spec.h.
#include <rk_plugin.h>  // the adapter of the MeshLab configured (RELIEFKIT_MESHLAB_API)

#include <QFileInfo>
#include <algorithm>
#include <cstdlib>
#include <exception>

#include "reliefkit/base/memory.h"
#include "reliefkit/base/mesh.h"
#include "reliefkit/base/openmp_waiting.h"
#include "reliefkit/base/work_counts.h"

namespace reliefkit::ml {

// About what a filter run allocates per face of its mesh, reserved with huge pages at its start
// (RetainedMemory). Peak resident memory above loading a 1 M-face relief, `/usr/bin/time -f %M`
// around scripts/meshlabserver: the curvature filter 160 MB, Relief Edges 400 MB.
constexpr size_t kHeapBytesPerFace = 400;

QString log_text(QString line) {
  // MeshLab's log window reads its lines as rich text: "<=" and ">=" would start tags.
  line.replace("<=", QString::fromUtf8("\u2264")).replace(">=", QString::fromUtf8("\u2265"));
  line.replace('<', QString::fromUtf8("\u2039")).replace('>', QString::fromUtf8("\u203a"));
  return line;
}

const FilterSpec& spec_of(const std::vector<FilterSpec>& filters, int id) {
  for (const auto& f : filters)
    if (f.id == id) return f;
  return filters.front();
}

int post_conditions(const FilterSpec& s) {
  return s.adds_layers ? s.postconditions | MeshModel::MM_VERTNUMBER | MeshModel::MM_FACENUMBER : s.postconditions;
}

QString run_filter(const FilterSpec& s, FilterCall& call) {
  if (call.current == nullptr && s.needs_mesh) return "there is no mesh layer to work on; open a mesh first.";
  try {
    reliefkit::wait_passively_in_openmp();  // beside other busy programs, waiting threads sleep
    reliefkit::reset_work_counts();
    // One run: freed blocks reused, huge pages on the heap it will use, all returned at the end.
    const size_t faces = call.current ? size_t(std::max(0, call.current->cm.FN())) : 0;
    const reliefkit::RetainedMemory retained(faces * kHeapBytesPerFace);
    s.apply(call);
    if (std::getenv("RELIEFKIT_WORK_COUNTS"))
      call.log("Work counts of " + s.name + ": " + QString::fromStdString(reliefkit::work_counts().summary()));
    return QString();
  } catch (const reliefkit::InputError& e) {
    return QString::fromUtf8(e.what());
  } catch (const std::bad_alloc&) {
    return "not enough memory for this mesh.";
  } catch (const std::exception& e) {
    return QString("internal error: ") + e.what();
  }
}

QString derived_file_folder(const QString& input) {
  const QString batch_folder = qEnvironmentVariable("RELIEFKIT_OUTPUT_FOLDER");
  return batch_folder.isEmpty() ? QFileInfo(input).absolutePath() : batch_folder;
}

}  // namespace reliefkit::ml
