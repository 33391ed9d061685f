#include "acc_identification/ros/ros_parameter_source.h"

#include <algorithm>

#include <ros/param.h>
#include <xmlrpcpp/XmlRpcValue.h>

namespace acc
{
namespace
{
ParameterValue fromXmlRpc(XmlRpc::XmlRpcValue& raw)
{
  ParameterValue value;
  switch (raw.getType())
  {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      value.type = ParameterValue::Type::kBool;
      value.boolean = static_cast<bool>(raw);
      break;
    case XmlRpc::XmlRpcValue::TypeInt:
      value.type = ParameterValue::Type::kInt;
      value.integer = static_cast<int>(raw);
      break;
    case XmlRpc::XmlRpcValue::TypeDouble:
      value.type = ParameterValue::Type::kDouble;
      value.number = static_cast<double>(raw);
      break;
    case XmlRpc::XmlRpcValue::TypeString:
      value.type = ParameterValue::Type::kString;
      value.text = static_cast<std::string&>(raw);
      break;
    case XmlRpc::XmlRpcValue::TypeArray:
      value.type = ParameterValue::Type::kList;
      for (int i = 0; i < raw.size(); ++i)
        value.items.push_back(fromXmlRpc(raw[i]));
      break;
    case XmlRpc::XmlRpcValue::TypeStruct:
      value.type = ParameterValue::Type::kDictionary;
      break;
    default:
      value.type = ParameterValue::Type::kNull;  // dates and binary: no parameter of ours takes them
  }
  return value;
}
}  // namespace

std::optional<ParameterValue> RosParameterSource::get(const std::string& name) const
{
  XmlRpc::XmlRpcValue raw;
  if (!node_.getParam(name, raw))
    return std::nullopt;
  return fromXmlRpc(raw);
}

std::vector<std::string> RosParameterSource::names() const
{
  std::vector<std::string> all, mine;
  if (!ros::param::getParamNames(all))
    return mine;
  const std::string prefix = node_.getNamespace() + "/";
  for (const std::string& name : all)
    if (name.compare(0, prefix.size(), prefix) == 0)
      mine.push_back(name.substr(prefix.size()));
  std::sort(mine.begin(), mine.end());
  return mine;
}

}  // namespace acc
