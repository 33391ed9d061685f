#pragma once

#include <fstream>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/model/platoon_simulation.h"

namespace acc
{
/// A figure's CSV: the header at once, rows through row(), 9 significant digits; throws
/// std::runtime_error when the file cannot be opened or written (close() checks the last write).
class CsvWriter
{
public:
  CsvWriter(const std::string& path, const std::string& header);
  std::ostream& row() { return out_; }
  void close();

private:
  std::ofstream out_;
  std::string path_;
};

/// Speeds of every vehicle of every platoon, one row per setting and sample
/// (setting,time_s,v0_mps,v1_mps,...).
void writePlatoonCsv(const std::string& path, const std::vector<std::pair<std::string, PlatoonTrajectory>>& runs);

}  // namespace acc
