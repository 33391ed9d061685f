#include "acc_identification/io/csv_fields.h"

#include <fstream>

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
std::string separatorHint(const std::string& path)
{
  std::ifstream file(path);
  std::string first_line;
  std::getline(file, first_line);
  if (first_line.find(',') != std::string::npos)
    return "";
  if (first_line.find(';') != std::string::npos)
    return " (its fields are separated by ';', as a spreadsheet set to a decimal comma writes them: save it with "
           "',' between fields and '.' in numbers)";
  if (first_line.find('\t') != std::string::npos)
    return " (its fields are separated by tabs: save it with ',' between fields)";
  return "";
}

std::string csvQuoted(const std::string& text)
{
  std::string out = "\"";
  for (const char c : text)
    out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

bool writtenInHexadecimal(const std::string& cell) { return cell.find_first_of("xX") != std::string::npos; }

}  // namespace acc
