#include "reliefkit/base/noise_patch.h"

namespace reliefkit {

NoisePatch make_noise_patch(double relative_noise, int cells) {
  return {relative_noise, cells, std::make_shared<const Surface>(noise_patch(relative_noise, cells))};
}

bool NoisePatch::carries(double relative, int n) const {
  return surface && relative == relative_noise && n == cells;
}

NoisePatch NoisePatch::carrying(double relative, int n) const {
  return carries(relative, n) ? *this : make_noise_patch(relative, n);
}

}  // namespace reliefkit
