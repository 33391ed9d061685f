#pragma once

#include <string>

namespace acc
{
/// The path of a file installed beside the running executable (the tools' figure scripts and the
/// SUMO driver, in the devel and the install space alike); the bare name when the executable's
/// own path cannot be read.
std::string installedBeside(const std::string& file_name);

}  // namespace acc
