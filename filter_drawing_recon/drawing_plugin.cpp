#include "drawing_plugin.h"

#include "drawing_filters.h"

using namespace reliefkit::ml;

namespace {
enum FilterId { DRAWING_CURVES, DRAWING_RELIEF, BASE_FROM_SILHOUETTE, VESSEL_FROM_PROFILE };
}

ReliefKitDrawingPlugin::ReliefKitDrawingPlugin()
    : ReliefKitPlugin("ReliefKitDrawing", {drawing_curves_filter(DRAWING_CURVES), drawing_relief_filter(DRAWING_RELIEF),
                                           base_from_silhouette_filter(BASE_FROM_SILHOUETTE),
                                           vessel_from_profile_filter(VESSEL_FROM_PROFILE)}) {}
