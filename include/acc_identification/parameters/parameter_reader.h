#pragma once

#include <set>
#include <string>
#include <vector>

#include "acc_identification/parameters/parameter_source.h"

namespace acc
{
/// Reads a node's parameters with their types checked, for every node of the package, and a
/// tool's from a YAML file of the same keys (nmea_to_csv --params): one reader, one set of checks.
///
/// ros::NodeHandle::param keeps the default, and says nothing, when a parameter is set with a type
/// it cannot read: `timeout_s: 1e6` in a YAML file is the string "1e6" (YAML 1.1 wants a dot and a
/// signed exponent, 1.0e+6), `queue_size: 2.5` is no integer, `use_gnss_time: 1` no bool. The node
/// would run on a value nobody chose. Here such a parameter is an error that names it, what it
/// holds and what it takes; an unset parameter keeps the caller's default.
///
/// It also remembers what it read, so that a node can warn of the parameters it was given and never
/// reads (a misspelt `max_gap: 2.5` is ignored by any node, and would otherwise be silently).
///
/// A number parameter (double) takes an integer too; an integer one takes a whole double (200.0).
/// After the first error every later read is skipped and returns false, so a loader can chain its
/// reads with && and report the first problem.
class ParameterReader
{
public:
  /// source must outlive the reader.
  explicit ParameterReader(const ParameterSource& source) : source_(source) {}

  /// ~name into value when set. False, with error(), when it holds another type.
  bool read(const std::string& name, double& value);
  bool read(const std::string& name, int& value);
  bool read(const std::string& name, bool& value);
  bool read(const std::string& name, std::string& value);
  bool read(const std::string& name, std::vector<std::string>& value);

  /// read, then value >= minimum (or > minimum when strictly), finite. The error names the bound.
  bool readAtLeast(const std::string& name, double& value, double minimum);
  bool readAbove(const std::string& name, double& value, double minimum);
  bool readAtLeast(const std::string& name, int& value, int minimum);

  /// Records message as the error unless condition holds (checks across parameters); returns condition.
  bool require(bool condition, const std::string& message);

  bool ok() const { return error_.empty(); }
  /// The first problem, "parameter ~name ...": empty while ok().
  const std::string& error() const { return error_; }
  bool has(const std::string& name) const { return source_.get(name).has_value(); }

  /// Marks ~name as read by someone else (diagnostic_updater reads ~diagnostic_period).
  void readElsewhere(const std::string& name) { read_.insert(name); }
  /// "parameters ~a, ~b are set but never read (misspelt?): ignored", or empty when
  /// every parameter in the node's namespace was read (or asked for while unset).
  std::string unreadNote() const;

private:
  /// ~name's value, remembering the name: false after an error or when it is unset.
  bool fetch(const std::string& name, ParameterValue& raw);
  bool fail(const std::string& message);

  const ParameterSource& source_;
  std::string error_;
  std::set<std::string> read_;  ///< every name asked for, set or not
};

}  // namespace acc
