#include "acc_identification/gnss/nmea_fields.h"

#include <charconv>
#include <cmath>

namespace acc
{
std::uint8_t nmeaChecksumValue(std::string_view body)
{
  std::uint8_t sum = 0;
  for (const char c : body)
    sum ^= static_cast<std::uint8_t>(c);
  return sum;
}

NmeaFields::NmeaFields(std::string_view body)
{
  // A plain byte loop: NMEA fields are a few characters long, where a memchr call per field
  // costs more than it saves (it was half of the parse time).
  const char* data = body.data();
  const std::size_t size = body.size();
  std::size_t start = 0;
  for (std::size_t i = 0; i <= size; ++i)
  {
    if (i < size && data[i] != ',')
      continue;
    if (count_ == kMaxFields)
    {
      overflowed_ = true;
      return;
    }
    fields_[count_++] = std::string_view(data + start, i - start);
    start = i + 1;
  }
}

namespace
{
bool isDigit(char c) { return c >= '0' && c <= '9'; }

int twoDigits(std::string_view s, std::size_t at) { return (s[at] - '0') * 10 + (s[at + 1] - '0'); }
}  // namespace

namespace
{
/// Fast path for the fixed-point numbers NMEA sends ([+-]digits[.digits], at most 15 significant
/// digits): the integer of all digits divided by a power of ten. Both are exact doubles, so the
/// one division is correctly rounded, the same result as from_chars, several times faster.
bool readFixedPoint(const char* begin, const char* end, double& value)
{
  static constexpr double kPowersOfTen[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7,
                                            1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  const bool negative = begin != end && *begin == '-';
  if (negative)
    ++begin;
  std::uint64_t mantissa = 0;
  int digits = 0, fraction_digits = 0;
  bool point = false;
  for (const char* p = begin; p != end; ++p)
  {
    if (*p == '.' && !point)
      point = true;
    else if (isDigit(*p))
    {
      mantissa = mantissa * 10 + static_cast<std::uint64_t>(*p - '0');
      fraction_digits += point ? 1 : 0;
      if (++digits > 15)
        return false;
    }
    else
      return false;
  }
  if (digits == 0)
    return false;
  value = static_cast<double>(mantissa) / kPowersOfTen[fraction_digits];
  if (negative)
    value = -value;
  return true;
}
}  // namespace

FieldStatus readDouble(std::string_view field, double& value)
{
  if (field.empty())
    return FieldStatus::kAbsent;
  const char* begin = field.data();
  const char* end = begin + field.size();
  if (*begin == '+')  // from_chars rejects a leading '+', some receivers send one
    ++begin;
  if (readFixedPoint(begin, end, value))
    return FieldStatus::kOk;
  const auto result = std::from_chars(begin, end, value, std::chars_format::fixed);
  if (result.ec != std::errc() || result.ptr != end || !std::isfinite(value))
    return FieldStatus::kInvalid;
  return FieldStatus::kOk;
}

FieldStatus readUnsigned(std::string_view field, std::uint32_t& value)
{
  if (field.empty())
    return FieldStatus::kAbsent;
  const char* end = field.data() + field.size();
  const auto result = std::from_chars(field.data(), end, value);
  return result.ec == std::errc() && result.ptr == end ? FieldStatus::kOk : FieldStatus::kInvalid;
}

FieldStatus readTimeOfDay(std::string_view field, double& seconds)
{
  if (field.empty())
    return FieldStatus::kAbsent;
  if (field.size() < 6)
    return FieldStatus::kInvalid;
  for (std::size_t i = 0; i < 6; ++i)
    if (!isDigit(field[i]))
      return FieldStatus::kInvalid;
  const int hours = twoDigits(field, 0);
  const int minutes = twoDigits(field, 2);
  double second = 0.0;
  if (readDouble(field.substr(4), second) != FieldStatus::kOk)
    return FieldStatus::kInvalid;
  if (hours > 23 || minutes > 59 || second < 0.0 || second >= 61.0)
    return FieldStatus::kInvalid;
  seconds = hours * 3600.0 + minutes * 60.0 + second;
  return FieldStatus::kOk;
}

FieldStatus readAngle(std::string_view value_field, std::string_view hemisphere_field, double max_degrees,
                      char positive, char negative, double& degrees)
{
  if (value_field.empty() && hemisphere_field.empty())
    return FieldStatus::kAbsent;
  if (value_field.empty() || hemisphere_field.size() != 1 || value_field.front() == '-')
    return FieldStatus::kInvalid;
  double packed = 0.0;  // degrees * 100 + minutes
  if (readDouble(value_field, packed) != FieldStatus::kOk)
    return FieldStatus::kInvalid;
  const double whole_degrees = std::floor(packed / 100.0);
  const double minutes = packed - whole_degrees * 100.0;
  const double magnitude = whole_degrees + minutes / 60.0;
  if (minutes >= 60.0 || magnitude > max_degrees)
    return FieldStatus::kInvalid;
  const char hemisphere = hemisphere_field.front();
  if (hemisphere != positive && hemisphere != negative)
    return FieldStatus::kInvalid;
  degrees = hemisphere == positive ? magnitude : -magnitude;
  return FieldStatus::kOk;
}

}  // namespace acc
