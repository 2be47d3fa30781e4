#include "prominent_plugin.h"

#include "prominent_filters.h"

using namespace reliefkit::ml;

namespace {
enum FilterId { PROMINENT_FIELD, PROMINENT_ENHANCEMENT, PROMINENT_COLORING };
}

ReliefKitProminentPlugin::ReliefKitProminentPlugin()
    : ReliefKitPlugin("ReliefKitProminent", {prominent_field_filter(PROMINENT_FIELD),
                                             prominent_enhancement_filter(PROMINENT_ENHANCEMENT),
                                             prominent_coloring_filter(PROMINENT_COLORING)}) {}
