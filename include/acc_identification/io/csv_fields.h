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

/// How a cell reads: a finite number, or why not.
enum class CellKind
{
  kNumber,
  kEmpty,
  kNotFinite,
  kNotANumber
};
/// Reads a whole cell into value (NaN unless it is a finite number). A number too small for a
/// double ("1e-320") is the nearest one, subnormal or zero: strtod flags it as out of range, yet it
/// is what the text says; one too large is not finite; hexadecimal is not a number.
CellKind parseCell(const std::string& text, double& value);

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

/// For a reader's error, why the file does not read as comma-separated text, when its first bytes
/// say: " (it is a ROS bag ...)", " (it is UTF-16 text ...)" or another binary file; " (its lines end
/// in a carriage return alone ...)", as Excel's "CSV (Macintosh)" writes them; " (its fields are
/// separated by ';' ...)" when the first line has semicolons and no comma, as a spreadsheet set to a
/// decimal comma writes it, the same for tabs; "" otherwise.
std::string textLayoutHint(const std::string& path);
}  // namespace acc
