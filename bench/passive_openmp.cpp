// Linked into every benchmark: its OpenMP threads wait as the plugins' do
// (reliefkit/base/openmp_waiting.h), so that its figures are what a user's MeshLab gets, also
// beside other busy programs.
#include "reliefkit/base/openmp_waiting.h"

namespace {
const bool kWaitingPassively = reliefkit::wait_passively_in_openmp();
}  // namespace
