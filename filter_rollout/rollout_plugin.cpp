#include "rollout_plugin.h"

#include "rollout_filters.h"

using namespace reliefkit::ml;

namespace {
enum FilterId { UNROLL };
}

ReliefKitRolloutPlugin::ReliefKitRolloutPlugin() : ReliefKitPlugin("ReliefKitRollout", {unroll_filter(UNROLL)}) {}
