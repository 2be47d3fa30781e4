#include "illustration_plugin.h"

#include "plate_filter.h"

using namespace reliefkit::ml;

namespace {
enum FilterId { ILLUSTRATION_PLATE };
}

ReliefKitIllustrationPlugin::ReliefKitIllustrationPlugin()
    : ReliefKitPlugin("ReliefKitIllustration", {illustration_plate_filter(ILLUSTRATION_PLATE)}) {}
