#include "acc_identification/io/output_files.h"
#include "acc_identification/io/run_program.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <ostream>

namespace acc
{
bool sameFile(const std::string& a, const std::string& b)
{
  std::error_code error;
  if (std::filesystem::exists(a, error) && std::filesystem::exists(b, error))
    return std::filesystem::equivalent(a, b, error) && !error;
  const std::filesystem::path resolved_a = std::filesystem::weakly_canonical(std::filesystem::absolute(a), error);
  if (error)
    return false;
  const std::filesystem::path resolved_b = std::filesystem::weakly_canonical(std::filesystem::absolute(b), error);
  return !error && resolved_a == resolved_b;
}

bool outputsLeaveInputsAlone(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs,
                             std::ostream& errors)
{
  for (std::size_t i = 0; i < outputs.size(); ++i)
  {
    if (outputs[i].empty())
      continue;
    for (const std::string& input : inputs)
    {
      if (!input.empty() && sameFile(outputs[i], input))
      {
        errors << "error: " << outputs[i] << " would overwrite the input " << input
               << ": give the output another path (nothing was written)\n";
        return false;
      }
    }
    for (std::size_t j = i + 1; j < outputs.size(); ++j)
    {
      if (!outputs[j].empty() && sameFile(outputs[i], outputs[j]))
      {
        errors << "error: two outputs name the same file, " << outputs[i] << " and " << outputs[j]
               << ": one would overwrite the other (nothing was written)\n";
        return false;
      }
    }
  }
  return true;
}

bool writeTextFile(const std::string& text, const std::string& path, std::ostream& errors)
{
  std::ofstream out(path);
  out << text;
  out.flush();
  if (!out)
    errors << "error: cannot write " << path << "\n";
  return static_cast<bool>(out);
}

bool writeJsonFile(const nlohmann::json& json, const std::string& path, std::ostream& errors)
{
  return writeTextFile(json.dump(2) + "\n", path, errors);
}

bool makeOutputFolder(const std::string& dir, std::ostream& errors)
{
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error)
    errors << "error: cannot create " << dir << ": " << error.message() << "\n";
  return !error;
}

bool drawReportFigures(const std::string& script, const std::string& dir, const std::string& kept,
                       std::ostream& errors)
{
  if (!std::filesystem::exists(script))
  {
    errors << "error: no figure script at " << script << " (--plot-script, or --no-plots); " << kept << " are in "
           << dir << "\n";
    return false;
  }
  if (runProgram({"/usr/bin/python3", script, dir}) != 0)
  {
    errors << "error: the report figures failed (/usr/bin/python3 " << script << " " << dir << "); " << kept
           << " are in " << dir << "\n";
    return false;
  }
  errors << "report: " << dir << "/report.md\n";
  return true;
}

void showProgress(const std::string& stage, std::size_t done, std::size_t total)
{
  static const bool terminal = isatty(STDERR_FILENO) != 0;
  constexpr std::size_t kWidth = 30;
  if (terminal)
  {
    const std::size_t filled = total > 0 ? kWidth * done / total : kWidth;
    std::fprintf(stderr, "\r%-13s [%s%s] %zu/%zu", stage.c_str(), std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, '.').c_str(), done, total);
    if (done == total)
      std::fprintf(stderr, "\n");
  }
  else if (done == total || (total >= 10 && done % (total / 10) == 0))
  {
    std::fprintf(stderr, "%s: %zu/%zu done\n", stage.c_str(), done, total);
  }
}

}  // namespace acc
