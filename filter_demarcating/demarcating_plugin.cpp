#include "demarcating_plugin.h"

#include "curvature_filter.h"

using namespace reliefkit::ml;

namespace {
enum FilterId { CURVATURE_TENSOR };
}

ReliefKitDemarcatingPlugin::ReliefKitDemarcatingPlugin()
    : ReliefKitPlugin("ReliefKitDemarcating", {curvature_tensor_filter(CURVATURE_TENSOR)}) {}
