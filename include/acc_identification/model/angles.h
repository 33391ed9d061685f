#pragma once

namespace acc
{
/// pi and the degree conversions, defined once: the NMEA conversion, the OpenACC unit check and
/// the synthesis must turn the same radians into the same degrees to the last bit (the bundled
/// bags are compared byte for byte).
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDegToRad = kPi / 180.0;
inline constexpr double kRadToDeg = 180.0 / kPi;

}  // namespace acc
