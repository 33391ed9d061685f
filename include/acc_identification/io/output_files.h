#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace acc
{
/// What every tool does with the files it is asked to write. Each returns false after saying on
/// `errors` what failed ("error: cannot write PATH"), so a tool can end with status 1.

/// Whether two paths name one file: the same file for the file system when both exist, the same
/// absolute path with links and dots resolved otherwise.
bool sameFile(const std::string& a, const std::string& b);

/// Whether the outputs leave the inputs alone: false, after saying which on `errors`, when an
/// output names the same file as an input ("error: OUT would overwrite the input IN") or as another
/// output. Tools call it before any work, since one slip in the order of the arguments would
/// otherwise overwrite a recording. The same file is found through links and spellings (a/../b, ./b);
/// empty paths (outputs not asked for) are skipped. Report folders are not outputs here: files are
/// written into them, and a folder that holds the inputs is a fine place for a report.
bool outputsLeaveInputsAlone(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs,
                             std::ostream& errors);

/// The text, as it is.
bool writeTextFile(const std::string& text, const std::string& path, std::ostream& errors);

/// The JSON, indented by two, with a final newline.
bool writeJsonFile(const nlohmann::json& json, const std::string& path, std::ostream& errors);

/// The folder and its parents. Tools make their report folder before the work, so that a folder
/// that cannot be made fails at once rather than after minutes of fitting.
bool makeOutputFolder(const std::string& dir, std::ostream& errors);

/// Draws a report's figures and report.md: `/usr/bin/python3 SCRIPT DIR`. Says which script is
/// missing or which command failed, and that `kept` (e.g. "tables and JSON") are in DIR all the
/// same; "report: DIR/report.md" when done.
bool drawReportFigures(const std::string& script, const std::string& dir, const std::string& kept,
                       std::ostream& errors);

/// A progress display for long batch work on stderr: redrawn in place on a terminal, a line per
/// tenth otherwise (logs stay short).
void showProgress(const std::string& stage, std::size_t done, std::size_t total);

}  // namespace acc
