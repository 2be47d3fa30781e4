#include "demarcating_plugin.h"

#include "curvature_filter.h"
#include "demarcating_filters.h"

using namespace reliefkit::ml;

namespace {
enum FilterId { CURVATURE_TENSOR, DEMARCATING_CURVES, CURVATURE_SHADING };
}

ReliefKitDemarcatingPlugin::ReliefKitDemarcatingPlugin()
    : ReliefKitPlugin("ReliefKitDemarcating",
                      {curvature_tensor_filter(CURVATURE_TENSOR), demarcating_curves_filter(DEMARCATING_CURVES),
                       curvature_shading_filter(CURVATURE_SHADING)}) {}
