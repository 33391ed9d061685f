#include "acc_identification/io/csv_fields.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>

namespace acc
{
namespace
{
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

std::string trimmed(const std::string& text)
{
  std::size_t first = 0, last = text.size();
  while (first < last && isSpace(text[first]))
    ++first;
  while (last > first && isSpace(text[last - 1]))
    --last;
  return text.substr(first, last - first);
}

/// The field that starts at `start`, to its comma (or the line's end); `next` is past that comma,
/// or npos at the line's end.
std::string fieldAt(const std::string& line, std::size_t start, std::size_t* next)
{
  std::size_t i = start;
  while (i < line.size() && isSpace(line[i]))
    ++i;
  if (i == line.size() || line[i] != '"')
  {
    const std::size_t comma = line.find(',', start);
    *next = comma == std::string::npos ? std::string::npos : comma + 1;
    return trimmed(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
  }
  std::string text;
  for (++i; i < line.size(); ++i)
  {
    if (line[i] != '"')
      text += line[i];
    else if (i + 1 < line.size() && line[i + 1] == '"')
      text += line[++i];  // "" is a quote inside the field
    else
      break;
  }
  const std::size_t comma = i < line.size() ? line.find(',', i) : std::string::npos;
  *next = comma == std::string::npos ? std::string::npos : comma + 1;
  return trimmed(text);
}
}  // namespace

std::vector<std::string> splitCsvFields(const std::string& line)
{
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (start != std::string::npos)
  {
    std::size_t next = std::string::npos;
    fields.push_back(fieldAt(line, start, &next));
    start = next;
  }
  return fields;
}

bool isBlankCsvLine(const std::string& line)
{
  return line.find_first_not_of(" \t\r\n,") == std::string::npos;
}

std::vector<std::string> firstLineFields(const std::string& path)
{
  std::ifstream in(path);
  std::string line;
  for (bool first = true; std::getline(in, line); first = false)
  {
    if (first)
      line = withoutByteOrderMark(line);
    if (!isBlankCsvLine(line))
      return splitCsvFields(line);
  }
  return {};
}

std::string withoutByteOrderMark(const std::string& line)
{
  static const std::string kUtf8Mark = "\xEF\xBB\xBF";
  return line.compare(0, kUtf8Mark.size(), kUtf8Mark) == 0 ? line.substr(kUtf8Mark.size()) : line;
}
namespace
{
/// Why the start of a file is not text a CSV reader can split ("" when it is).
std::string binaryHint(const std::string& start)
{
  if (start.compare(0, 7, "#ROSBAG") == 0)
    return " (it is a ROS bag: calibrate and diagnose read a bag of RelativeState when its name ends in .bag)";
  const bool utf16_mark = start.compare(0, 2, "\xFF\xFE") == 0 || start.compare(0, 2, "\xFE\xFF") == 0;
  if (utf16_mark || (start.size() > 1 && (start[0] == '\0' || start[1] == '\0')))
    return " (it is UTF-16 text, as a spreadsheet's \"Unicode text\" export writes it: save it as UTF-8 CSV)";
  if (start.find('\0') != std::string::npos)
    return " (it holds NUL bytes: a binary file, not CSV text)";
  return "";
}

/// " (its lines end in a carriage return alone ...)" when the start has a CR and no LF.
std::string lineEndHint(const std::string& start)
{
  if (start.find('\r') == std::string::npos || start.find('\n') != std::string::npos)
    return "";
  return " (its lines end in a carriage return alone, as Excel's \"CSV (Macintosh)\" writes them: save it with LF "
         "or CR LF line ends)";
}

std::string separatorHint(const std::string& first_line)
{
  if (first_line.find(',') != std::string::npos)
    return "";
  if (first_line.find(';') != std::string::npos)
    return " (its fields are separated by ';', as a spreadsheet set to a decimal comma writes them: save it with "
           "',' between fields and '.' in numbers)";
  if (first_line.find('\t') != std::string::npos)
    return " (its fields are separated by tabs: save it with ',' between fields)";
  return "";
}
}  // namespace

std::string textLayoutHint(const std::string& path)
{
  std::ifstream file(path, std::ios::binary);
  std::string start(4096, '\0');
  file.read(&start[0], static_cast<std::streamsize>(start.size()));
  start.resize(static_cast<std::size_t>(file.gcount()));
  if (std::string hint = binaryHint(start); !hint.empty())
    return hint;
  if (std::string hint = lineEndHint(start); !hint.empty())
    return hint;
  return separatorHint(start.substr(0, start.find('\n')));
}

std::string csvQuoted(const std::string& text)
{
  std::string out = "\"";
  for (const char c : text)
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

bool writtenInHexadecimal(const std::string& cell) { return cell.find_first_of("xX") != std::string::npos; }

CellKind parseCell(const std::string& text, double& value)
{
  value = std::numeric_limits<double>::quiet_NaN();
  if (text.empty())
  {
    return CellKind::kEmpty;
  }
  char* end = nullptr;
  errno = 0;
  const double parsed = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || writtenInHexadecimal(text))
  {
    return CellKind::kNotANumber;
  }
  if (!std::isfinite(parsed))
  {
    return CellKind::kNotFinite;
  }
  if (errno == ERANGE && std::abs(parsed) > 1.0)
  {
    return CellKind::kNotFinite;  // overflow (strtod returned HUGE_VAL)
  }
  value = parsed;
  return CellKind::kNumber;
}

}  // namespace acc
