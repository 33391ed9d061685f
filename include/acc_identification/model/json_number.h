#pragma once

#include <cmath>

#include <nlohmann/json.hpp>

namespace acc
{
/// A number for the package's JSON: null where it is NaN or infinite (JSON has neither, and a
/// reader must see "not available", not a made-up value). The one definition for every output.
inline nlohmann::json jsonNumber(double value)
{
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

/// A number that may rightly be infinite (lambda2 with tau_e = 0, where every low frequency grows;
/// the peak gain of an undamped model): "inf" or "-inf" there, null where it is NaN (not
/// determined), the number otherwise. null for +infinity read as "not determined".
inline nlohmann::json jsonNumberOrInfinity(double value)
{
  if (std::isinf(value))
    return value > 0.0 ? "inf" : "-inf";
  return jsonNumber(value);
}

}  // namespace acc
