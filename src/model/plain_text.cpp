#include "acc_identification/model/plain_text.h"

#include <cctype>

namespace acc
{
std::string join(const std::vector<std::string>& parts, const std::string& separator)
{
  std::string text;
  for (const std::string& part : parts)
    text += (text.empty() ? "" : separator) + part;
  return text;
}

std::string upperCase(std::string text)
{
  for (char& c : text)
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}
}  // namespace acc
