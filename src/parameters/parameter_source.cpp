#include "acc_identification/parameters/parameter_source.h"

#include <sstream>

namespace acc
{
std::string ParameterValue::describe() const
{
  std::ostringstream out;
  switch (type)
  {
    case Type::kString:
      out << "the string \"" << text << "\"";
      break;
    case Type::kInt:
      out << "the integer " << integer;
      break;
    case Type::kDouble:
      out << "the number " << number;
      break;
    case Type::kBool:
      out << "the bool " << (boolean ? "true" : "false");
      break;
    case Type::kList:
      out << "a list of " << items.size() << " values";
      break;
    case Type::kDictionary:
      out << "a dictionary";
      break;
    case Type::kNull:
      out << "empty (null)";
      break;
  }
  return out.str();
}

}  // namespace acc
