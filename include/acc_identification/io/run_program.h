#pragma once

#include <string>
#include <vector>

namespace acc
{
/// Runs argv (argv[0] looked up on PATH) without a shell, so that its arguments may hold anything
/// (spaces, quotes: "Bob's drives"), and waits for it. Its stdout and stderr go to log_path, or
/// stay the caller's when log_path is empty. Returns its exit status; -1 when it could not be
/// started or did not exit on its own.
int runProgram(const std::vector<std::string>& argv, const std::string& log_path = "");

}  // namespace acc
