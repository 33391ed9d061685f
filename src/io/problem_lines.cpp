#include "acc_identification/io/problem_lines.h"

#include <cctype>
#include <cstddef>
#include <optional>

namespace acc
{
namespace
{
/// "path:12: why" taken apart; nullopt for a problem of another form.
struct LineProblem
{
  std::string path;
  std::size_t line;
  std::string why;
};

std::optional<LineProblem> parseLineProblem(const std::string& problem)
{
  // The first ":<digits>: " ends the path: a reason may hold colons, a path rarely ":12: ".
  for (std::size_t colon = problem.find(':'); colon != std::string::npos; colon = problem.find(':', colon + 1))
  {
    std::size_t end = colon + 1;
    while (end < problem.size() && std::isdigit(static_cast<unsigned char>(problem[end])))
      ++end;
    if (end > colon + 1 && end - colon <= 10 && problem.compare(end, 2, ": ") == 0)
      return LineProblem{problem.substr(0, colon), std::stoul(problem.substr(colon + 1, end - colon - 1)),
                         problem.substr(end + 2)};
  }
  return std::nullopt;
}

/// A stretch of consecutive lines with one reason.
struct Stretch
{
  LineProblem first;
  std::size_t last_line;
  std::size_t lines;

  std::string text() const
  {
    if (lines == 1)
      return first.path + ":" + std::to_string(first.line) + ": " + first.why;
    return first.path + ":" + std::to_string(first.line) + "-" + std::to_string(last_line) + " (" +
           std::to_string(lines) + " lines): " + first.why;
  }
};
}  // namespace

std::vector<std::string> condenseProblemLines(const std::vector<std::string>& problems)
{
  std::vector<std::string> condensed;
  std::optional<Stretch> open;
  for (const std::string& problem : problems)
  {
    const std::optional<LineProblem> parsed = parseLineProblem(problem);
    if (open && parsed && parsed->path == open->first.path && parsed->why == open->first.why &&
        parsed->line == open->last_line + 1)
    {
      open->last_line = parsed->line;
      ++open->lines;
      continue;
    }
    if (open)
      condensed.push_back(open->text());
    open.reset();
    if (parsed)
      open = Stretch{*parsed, parsed->line, 1};
    else
      condensed.push_back(problem);
  }
  if (open)
    condensed.push_back(open->text());
  return condensed;
}

}  // namespace acc
