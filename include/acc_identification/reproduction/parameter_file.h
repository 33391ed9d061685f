#pragma once

#include <stdexcept>
#include <string>

#include "acc_identification/model/paper_settings.h"

namespace acc
{
/// A parameter file that cannot be used (missing, not JSON, fields missing or not numbers).
class ParameterFileError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Reads the parameters of a calibrate JSON: {"parameters": {"k1_per_s2", "k2_per_s",
/// "tau_e_s", "eta_m"}, ...}; other fields are ignored, but a non-empty "effects" (a model the
/// paper's law alone does not simulate) is refused. Named after the file's stem. Throws
/// ParameterFileError with the path and the reason (also for a negative gain or time gap).
NamedSetting readParameterFile(const std::string& path);

/// Why the calibrate JSON's k1, k2 or tau_e are not determined by its data ("" when they are, or
/// when the file does not say): their reasons from identifiable_quantities. A figure drawn from them
/// shows dynamics the data do not pin, which the figure's user must be told (eta moves none).
std::string describeUndeterminedParameterFile(const std::string& path);

}  // namespace acc
