#include "acc_identification/model/number_text.h"

#include <cmath>

namespace acc
{
std::string significant(double value, int digits)
{
  return printfText("%.*g", digits, value);
}

std::string cellNumber(const char* pattern, double value)
{
  if (std::isinf(value))
    return value > 0.0 ? "inf" : "-inf";
  return std::isfinite(value) ? printfText(pattern, value) : "NaN";
}

}  // namespace acc
