// Angles: π and the two conversions, one name each.
#pragma once

namespace reliefkit {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadiansPerDegree = kPi / 180;  // an angle in degrees times this is in radians
constexpr double kDegreesPerRadian = 180 / kPi;  // an angle in radians times this is in degrees

}  // namespace reliefkit
