#include "pottery_plugin.h"

#include "pottery_filters.h"

using namespace reliefkit::ml;

namespace {
enum FilterId { VESSEL_AXIS };
}

ReliefKitPotteryPlugin::ReliefKitPotteryPlugin() : ReliefKitPlugin("ReliefKitPottery", {vessel_axis_filter(VESSEL_AXIS)}) {}
