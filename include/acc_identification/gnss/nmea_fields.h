#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace acc
{
/// Low-level NMEA 0183 helpers on string_view, allocation-free so that the parser can reach
/// millions of sentences per second.

/// XOR of every byte of body (the characters between '$' and '*').
std::uint8_t nmeaChecksumValue(std::string_view body);

/// The fields of one sentence body split at ','. Fixed capacity: sentences with more fields keep
/// the first kMaxFields and report overflowed(); none of the supported sentences needs more.
class NmeaFields
{
public:
  static constexpr std::size_t kMaxFields = 32;

  explicit NmeaFields(std::string_view body);
  std::size_t size() const { return count_; }
  bool overflowed() const { return overflowed_; }
  /// Field i, or an empty view when the sentence has fewer fields.
  std::string_view operator[](std::size_t i) const { return i < count_ ? fields_[i] : std::string_view(); }

private:
  std::string_view fields_[kMaxFields];
  std::size_t count_ = 0;
  bool overflowed_ = false;
};

/// Result of reading one optional field: NMEA leaves a field empty when the receiver has no value.
enum class FieldStatus
{
  kAbsent,   ///< empty field
  kOk,
  kInvalid,  ///< present but not of the expected form
};

/// A decimal number (digits, optional sign, optional fraction); the whole field must be used.
FieldStatus readDouble(std::string_view field, double& value);
/// A non-negative integer.
FieldStatus readUnsigned(std::string_view field, std::uint32_t& value);
/// hhmmss or hhmmss.sss into seconds since midnight (a leap second 60 is accepted).
FieldStatus readTimeOfDay(std::string_view field, double& seconds);
/// ddmm.mmmm (latitude, max_degrees 90) or dddmm.mmmm (longitude, 180) with its hemisphere
/// field (N/S or E/W) into signed degrees. Both empty: absent; one empty: invalid.
FieldStatus readAngle(std::string_view value_field, std::string_view hemisphere_field, double max_degrees,
                      char positive, char negative, double& degrees);

}  // namespace acc
