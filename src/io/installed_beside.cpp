#include "acc_identification/io/installed_beside.h"

#include <filesystem>
#include <system_error>

namespace acc
{
std::string installedBeside(const std::string& file_name)
{
  std::error_code error;
  const auto executable = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? file_name : (executable.parent_path() / file_name).string();
}

}  // namespace acc
