#include "relief_plugin.h"

#include "relief_filters.h"

using namespace reliefkit::ml;

namespace {
enum FilterId { RELIEF_EDGES, BASE_NORMALS, RIDGES_VALLEYS };
}

ReliefKitReliefEdgesPlugin::ReliefKitReliefEdgesPlugin()
    : ReliefKitPlugin("ReliefKitReliefEdges", {relief_edges_filter(RELIEF_EDGES), base_normals_filter(BASE_NORMALS),
                                               ridges_valleys_filter(RIDGES_VALLEYS)}) {}
