#pragma once

// The text of one CSV line, as both run readers (canonical and OpenACC) take it.

#include <string>
#include <vector>

namespace acc
{
/// The fields of one line: split at every comma outside double quotes, so "a,b," is three fields,
/// the last empty; each field trimmed of spaces, tabs and line ends, and a quoted one unquoted
/// ("" inside it is one "), as spreadsheet exports write them. An unterminated quote runs to the
/// line's end.
std::vector<std::string> splitCsvFields(const std::string& line);

/// Whether a cell is written in hexadecimal ("0x25"): strtod reads it (as 37), no recorder writes
/// it, so the readers take it for what it is, not a number.
bool writtenInHexadecimal(const std::string& cell);

/// A text field as a CSV writer writes it, for splitCsvFields and Python's csv to read back whole:
/// quoted, its quotes doubled. Run names come from file names and Vehicle_order, which may hold
/// commas and quotes.
std::string csvQuoted(const std::string& text);

/// Nothing but white space and commas (a spreadsheet's empty row).
bool isBlankCsvLine(const std::string& line);

/// The fields of the file's first line that is not blank, its byte-order mark dropped; empty when
/// the file has none or cannot be opened. What a reader tells a file's kind by.
std::vector<std::string> firstLineFields(const std::string& path);

/// The line without the UTF-8 byte-order mark a spreadsheet export may put at a file's start.
std::string withoutByteOrderMark(const std::string& line);

/// For a reader's error: " (its fields are separated by ';' ...)" when the file's first line has
/// semicolons and no comma, as a spreadsheet set to a decimal comma writes it, the same for tabs
/// (a tab-separated export); "" otherwise.
std::string separatorHint(const std::string& path);
}  // namespace acc
