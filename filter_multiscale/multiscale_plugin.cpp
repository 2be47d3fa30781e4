#include "multiscale_plugin.h"

#include "multiscale_filters.h"

using namespace reliefkit::ml;

namespace {
enum FilterId { OPTIMAL_SCALE, SMOOTHED_SURFACE, MULTISCALE_RIDGES, MULTISCALE_RELIEF_EDGES };
}

ReliefKitMultiscalePlugin::ReliefKitMultiscalePlugin()
    : ReliefKitPlugin("ReliefKitMultiscale",
                      {optimal_scale_filter(OPTIMAL_SCALE), smoothed_surface_filter(SMOOTHED_SURFACE),
                       multiscale_ridges_filter(MULTISCALE_RIDGES), multiscale_relief_edges_filter(MULTISCALE_RELIEF_EDGES)}) {}
