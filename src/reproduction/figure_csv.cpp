#include "acc_identification/reproduction/figure_csv.h"

#include <stdexcept>

namespace acc
{
CsvWriter::CsvWriter(const std::string& path, const std::string& header) : out_(path), path_(path)
{
  if (!out_)
  {
    throw std::runtime_error("cannot write " + path);
  }
  out_.precision(9);
  out_ << header << '\n';
}

void CsvWriter::close()
{
  out_.close();
  if (!out_)
  {
    throw std::runtime_error("error writing " + path_);
  }
}

void writePlatoonCsv(const std::string& path, const std::vector<std::pair<std::string, PlatoonTrajectory>>& runs)
{
  const std::size_t vehicles = runs.front().second.vehicleCount();
  std::string header = "setting,time_s";
  for (std::size_t i = 0; i < vehicles; ++i)
  {
    header += ",v" + std::to_string(i) + "_mps";
  }
  CsvWriter csv(path, header);
  for (const auto& [name, platoon] : runs)
  {
    for (std::size_t k = 0; k < platoon.sampleCount(); ++k)
    {
      csv.row() << name << ',' << static_cast<double>(k) * platoon.time_step_s;
      for (std::size_t i = 0; i < platoon.vehicleCount(); ++i)
      {
        csv.row() << ',' << platoon.speed_mps[i][k];
      }
      csv.row() << '\n';
    }
  }
  csv.close();
}

}  // namespace acc
