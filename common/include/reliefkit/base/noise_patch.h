// ReliefKit — what a scan's noise alone draws, simulated: the one form of the noise patch.
#pragma once

#include <memory>

#include "reliefkit/base/scale.h"
#include "reliefkit/base/surface.h"

namespace reliefkit {

/// A flat, irregular patch `cells` across carrying `relative_noise` edge lengths of noise
/// (noise_patch, scale.h), as a Surface: the curve filters measure on it what noise alone draws
/// after their own pre-smoothing. Copies share the surface, so a run builds it once and hands it
/// to its stages; an empty one (no surface) means none was given.
struct NoisePatch {
  double relative_noise = 0;
  int cells = 0;
  std::shared_ptr<const Surface> surface;

  explicit operator bool() const { return surface != nullptr; }
  /// Whether it carries `relative_noise` at `cells`.
  bool carries(double relative_noise, int cells) const;
  /// This patch when it carries them, else a new one that does.
  NoisePatch carrying(double relative_noise, int cells) const;
};

NoisePatch make_noise_patch(double relative_noise, int cells);

}  // namespace reliefkit
