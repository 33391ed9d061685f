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

}  // namespace acc
