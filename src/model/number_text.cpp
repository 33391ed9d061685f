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
  return std::isfinite(value) ? printfText(pattern, value) : "NaN";
}

}  // namespace acc
