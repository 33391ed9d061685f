#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/model/angles.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "acc_identification/gnss/nmea_fields.h"
#include "acc_identification/gnss/utc_date.h"

namespace acc
{
namespace
{
constexpr double kKnotToMps = 1852.0 / 3600.0;
constexpr double kKmhToMps = 1.0 / 3.6;
// Satellite counts beyond GnssFix::satellites_used (uint16) are malformed, in GGA as in PUBX,00
// (the fuzzer found a PUBX count that GGA would not read back).

using Outcome = NmeaParseOutcome;

int hexValue(char c)
{
  if (c >= '0' && c <= '9')
    return c - '0';
  if (c >= 'A' && c <= 'F')
    return c - 'A' + 10;
  if (c >= 'a' && c <= 'f')
    return c - 'a' + 10;
  return -1;
}

/// Reads an optional field into value (NaN stays when absent). False when present but invalid.
bool optionalDouble(std::string_view field, double& value)
{
  double read = 0.0;
  const FieldStatus status = readDouble(field, read);
  if (status == FieldStatus::kOk)
    value = read;
  return status != FieldStatus::kInvalid;
}

bool optionalTime(std::string_view field, double& seconds)
{
  double read = 0.0;
  const FieldStatus status = readTimeOfDay(field, read);
  if (status == FieldStatus::kOk)
    seconds = read;
  return status != FieldStatus::kInvalid;
}

/// Latitude (fields i, i+1) and longitude (i+2, i+3); both or neither.
bool optionalPosition(const NmeaFields& f, std::size_t i, NmeaSentence& s)
{
  double latitude = 0.0, longitude = 0.0;
  const FieldStatus lat = readAngle(f[i], f[i + 1], 90.0, 'N', 'S', latitude);
  const FieldStatus lon = readAngle(f[i + 2], f[i + 3], 180.0, 'E', 'W', longitude);
  if (lat == FieldStatus::kInvalid || lon == FieldStatus::kInvalid || lat != lon)
    return false;
  if (lat == FieldStatus::kOk)
  {
    s.latitude_deg = latitude;
    s.longitude_deg = longitude;
  }
  return true;
}

/// Course in degrees into radians in [0, 2 pi).
bool optionalCourse(std::string_view field, double& course_rad)
{
  double degrees = NmeaSentence::kNaN;
  if (!optionalDouble(field, degrees))
    return false;
  if (std::isnan(degrees))
    return true;
  if (degrees < 0.0 || degrees > 360.0)
    return false;
  course_rad = degrees >= 360.0 ? 0.0 : degrees * kPi / 180.0;
  return true;
}

bool optionalSpeed(std::string_view field, double unit_mps, double& speed_mps)
{
  double value = NmeaSentence::kNaN;
  if (!optionalDouble(field, value) || value < 0.0)
    return false;
  if (!std::isnan(value))
    speed_mps = value * unit_mps;
  return true;
}

bool optionalSigma(std::string_view field, double& sigma_m)
{
  return optionalDouble(field, sigma_m) && !(sigma_m < 0.0);
}

/// RMC / PUBX mode indicator to the GGA quality scale.
int qualityFromMode(char mode)
{
  switch (mode)
  {
    case 'A': return 1;
    case 'D': return 2;
    case 'P': return 3;
    case 'R': return 4;
    case 'F': return 5;
    case 'E': return 6;
    default: return 0;
  }
}

/// GGA quality 1..6 is a fix; 0 is none, 7 (manual input) and 8 (simulator) are not measurements.
bool isFix(int quality) { return quality >= 1 && quality <= 6; }

/// Position fields (i .. i+3) of a sentence whose fix is known: an unreadable position makes a
/// sentence with a fix malformed; a sentence without a fix reports none anyway, so a placeholder
/// there (MediaTek's 8960.000000,N at cold start) does not cost its time and date.
bool positionOfFix(const NmeaFields& f, std::size_t i, int quality, NmeaSentence& s)
{
  if (!optionalPosition(f, i, s) && isFix(quality))
    return false;
  if (!isFix(quality))
    s.latitude_deg = s.longitude_deg = s.altitude_m = NmeaSentence::kNaN;
  return true;
}

// $xxGGA,time,lat,NS,lon,EW,quality,numSV,HDOP,alt,M,sep,M,diffAge,diffStation
// The fields after the geoid separation (its unit, differential age and station) may be absent.
Outcome parseGga(const NmeaFields& f, NmeaSentence& s)
{
  if (f.size() < 12)
    return Outcome::kMalformed;
  std::uint32_t quality = 0, satellites = 0;
  const FieldStatus q = readUnsigned(f[6], quality);
  const FieldStatus n = readUnsigned(f[7], satellites);
  if (!optionalTime(f[1], s.time_of_day_s) || q == FieldStatus::kInvalid || quality > 8 ||
      n == FieldStatus::kInvalid || satellites > 65535 || !optionalDouble(f[8], s.hdop) ||
      !optionalDouble(f[9], s.altitude_m) || !optionalDouble(f[11], s.geoid_separation_m))
    return Outcome::kMalformed;
  s.fix_quality = q == FieldStatus::kOk ? static_cast<int>(quality) : 0;
  if (n == FieldStatus::kOk)
    s.satellites = static_cast<int>(satellites);
  // Without a fix a receiver may repeat its last position or send a made-up one: not a fix.
  return positionOfFix(f, 2, s.fix_quality, s) ? Outcome::kOk : Outcome::kMalformed;
}

/// GNS mode indicator, one character per constellation (GPS, GLONASS, Galileo, BeiDou, ...):
/// the best of them on the GGA scale; 0 when none has a fix; -1 when a character is unknown.
int qualityFromModes(std::string_view modes)
{
  // Best first: RTK fixed, RTK float, precise, differential, autonomous, estimated (dead
  // reckoning); then no fix, manual input, simulator.
  constexpr std::string_view kOrder = "RFPDAENMS";
  std::size_t best = kOrder.size();
  for (const char c : modes)
  {
    const std::size_t rank = kOrder.find(c);
    if (rank == std::string_view::npos)
      return -1;
    best = std::min(best, rank);
  }
  return best < kOrder.size() ? qualityFromMode(kOrder[best]) : 0;
}

// $xxGNS,time,lat,NS,lon,EW,posMode,numSV,HDOP,alt,sep,diffAge,diffStation[,navStatus]
// The fields after the geoid separation may be absent.
Outcome parseGns(const NmeaFields& f, NmeaSentence& s)
{
  if (f.size() < 11)
    return Outcome::kMalformed;
  std::uint32_t satellites = 0;
  const FieldStatus n = readUnsigned(f[7], satellites);
  const int quality = qualityFromModes(f[6]);
  if (!optionalTime(f[1], s.time_of_day_s) || quality < 0 || n == FieldStatus::kInvalid || satellites > 65535 ||
      !optionalDouble(f[8], s.hdop) || !optionalDouble(f[9], s.altitude_m) ||
      !optionalDouble(f[10], s.geoid_separation_m))
    return Outcome::kMalformed;
  s.fix_quality = quality;
  if (n == FieldStatus::kOk)
    s.satellites = static_cast<int>(satellites);
  return positionOfFix(f, 2, s.fix_quality, s) ? Outcome::kOk : Outcome::kMalformed;
}

// $xxGLL,lat,NS,lon,EW,time,status[,posMode]
Outcome parseGll(const NmeaFields& f, NmeaSentence& s)
{
  if (f.size() < 7)
    return Outcome::kMalformed;
  const std::string_view status = f[6];
  const std::string_view mode = f.size() > 7 ? f[7] : std::string_view();
  if (status.size() > 1 || mode.size() > 1 || !optionalTime(f[5], s.time_of_day_s))
    return Outcome::kMalformed;
  s.fix_quality = status != "A" ? 0 : (mode.size() == 1 ? qualityFromMode(mode[0]) : 1);
  return positionOfFix(f, 1, s.fix_quality, s) ? Outcome::kOk : Outcome::kMalformed;
}

bool readRmcDate(std::string_view field, std::optional<std::int64_t>& day)
{
  if (field.empty())
    return true;
  if (field.size() != 6)
    return false;
  for (const char c : field)
    if (c < '0' || c > '9')
      return false;
  const unsigned dd = (field[0] - '0') * 10 + (field[1] - '0');
  const unsigned mm = (field[2] - '0') * 10 + (field[3] - '0');
  const int yy = (field[4] - '0') * 10 + (field[5] - '0');
  const int year = nmeaYear(yy);
  if (!isValidDate(year, mm, dd))
    return false;
  day = daysFromCivil(year, mm, dd);
  return true;
}

// $xxRMC,time,status,lat,NS,lon,EW,spd(kn),cog,date,mv,mvEW[,posMode[,navStatus]]
Outcome parseRmc(const NmeaFields& f, NmeaSentence& s)
{
  if (f.size() < 12)
    return Outcome::kMalformed;
  const std::string_view status = f[2];
  if (status.size() > 1 || !optionalTime(f[1], s.time_of_day_s) || !optionalSpeed(f[7], kKnotToMps, s.speed_mps) ||
      !optionalCourse(f[8], s.course_rad) || !readRmcDate(f[9], s.day))
    return Outcome::kMalformed;
  const bool valid = status == "A";
  const std::string_view mode = f.size() > 12 ? f[12] : std::string_view();
  s.fix_quality = !valid ? 0 : (mode.size() == 1 ? qualityFromMode(mode[0]) : 1);
  if (!positionOfFix(f, 3, s.fix_quality, s))
    return Outcome::kMalformed;
  if (s.fix_quality == 0)  // status V: the receiver says position and velocity are not valid
    s.speed_mps = s.course_rad = NmeaSentence::kNaN;
  return Outcome::kOk;
}

// $xxVTG,cogt,T,cogm,M,knots,N,kph,K[,posMode]
Outcome parseVtg(const NmeaFields& f, NmeaSentence& s)
{
  if (f.size() < 9)
    return Outcome::kMalformed;
  if (!optionalCourse(f[1], s.course_rad))
    return Outcome::kMalformed;
  // km/h has the finer resolution on u-blox; knots when km/h is empty.
  if (!f[7].empty() ? !optionalSpeed(f[7], kKmhToMps, s.speed_mps) : !optionalSpeed(f[5], kKnotToMps, s.speed_mps))
    return Outcome::kMalformed;
  const std::string_view mode = f.size() > 9 ? f[9] : std::string_view();
  if (mode == "N")
    s.speed_mps = s.course_rad = NmeaSentence::kNaN;
  return Outcome::kOk;
}

// $xxGST,time,rangeRms,stdMajor,stdMinor,orient,stdLat,stdLong,stdAlt
Outcome parseGst(const NmeaFields& f, NmeaSentence& s)
{
  if (f.size() < 9)
    return Outcome::kMalformed;
  double ignored = 0.0;
  for (std::size_t i = 2; i <= 5; ++i)
    if (!optionalDouble(f[i], ignored))
      return Outcome::kMalformed;
  if (!optionalTime(f[1], s.time_of_day_s) || !optionalSigma(f[6], s.latitude_sigma_m) ||
      !optionalSigma(f[7], s.longitude_sigma_m) || !optionalSigma(f[8], s.altitude_sigma_m))
    return Outcome::kMalformed;
  return Outcome::kOk;
}

// $xxZDA,time,day,month,year,ltzh,ltzn
Outcome parseZda(const NmeaFields& f, NmeaSentence& s)
{
  if (f.size() < 7)
    return Outcome::kMalformed;
  if (!optionalTime(f[1], s.time_of_day_s))
    return Outcome::kMalformed;
  std::uint32_t day = 0, month = 0, year = 0;
  const FieldStatus d = readUnsigned(f[2], day), m = readUnsigned(f[3], month), y = readUnsigned(f[4], year);
  if (d == FieldStatus::kAbsent && m == FieldStatus::kAbsent && y == FieldStatus::kAbsent)
    return Outcome::kOk;  // time without date (receiver at start-up)
  if (d != FieldStatus::kOk || m != FieldStatus::kOk || y != FieldStatus::kOk || year < 1980 || year > 2200 ||
      !isValidDate(static_cast<int>(year), month, day))
    return Outcome::kMalformed;
  s.day = daysFromCivil(static_cast<int>(year), month, day);
  return Outcome::kOk;
}

// $PUBX,00,time,lat,NS,lon,EW,altRef,navStat,hAcc,vAcc,SOG(km/h),COG,vVel,diffAge,HDOP,VDOP,TDOP,numSvs,res,DR
Outcome parsePubx00(const NmeaFields& f, NmeaSentence& s)
{
  if (f.size() < 20)
    return Outcome::kMalformed;
  double horizontal_accuracy = NmeaSentence::kNaN, vertical_accuracy = NmeaSentence::kNaN;
  std::uint32_t satellites = 0;
  const FieldStatus n = readUnsigned(f[18], satellites);
  if (!optionalTime(f[2], s.time_of_day_s) || !optionalPosition(f, 3, s) || f[8].size() > 2 ||
      !optionalSigma(f[9], horizontal_accuracy) || !optionalSigma(f[10], vertical_accuracy) ||
      !optionalSpeed(f[11], kKmhToMps, s.speed_mps) || !optionalCourse(f[12], s.course_rad) ||
      !optionalDouble(f[15], s.hdop) || n == FieldStatus::kInvalid || satellites > 65535)
    return Outcome::kMalformed;
  if (n == FieldStatus::kOk)
    s.satellites = static_cast<int>(satellites);
  // navStat: NF no fix, DR dead reckoning, G2/G3 stand-alone 2D/3D, D2/D3 differential, RK, TT.
  const std::string_view nav = f[8];
  s.fix_quality = nav == "G2" || nav == "G3" ? 1 : nav == "D2" || nav == "D3" ? 2 : nav == "RK" ? 1 : nav == "DR" ? 6 : 0;
  if (s.fix_quality == 0)
    s.latitude_deg = s.longitude_deg = s.speed_mps = s.course_rad = NmeaSentence::kNaN;
  // hAcc is a horizontal (2D) 1-sigma estimate; split evenly between north and east.
  s.latitude_sigma_m = s.longitude_sigma_m = horizontal_accuracy / std::sqrt(2.0);
  s.altitude_sigma_m = vertical_accuracy;
  return Outcome::kOk;
}

/// Checks '$', '*hh' and the checksum; body receives the characters between '$' and '*'.
Outcome checkFrame(std::string_view line, std::string_view& body)
{
  while (!line.empty() && (line.back() == '\r' || line.back() == '\n' || line.back() == ' '))
    line.remove_suffix(1);
  if (line.size() < 4 || (line.front() != '$' && line.front() != '!') || line[line.size() - 3] != '*')
    return Outcome::kMalformed;
  const int high = hexValue(line[line.size() - 2]);
  const int low = hexValue(line[line.size() - 1]);
  if (high < 0 || low < 0)
    return Outcome::kMalformed;
  body = line.substr(1, line.size() - 4);
  // One pass: the checksum, and no '$' or '*' inside the body (two sentences run together).
  std::uint8_t sum = 0;
  for (const char c : body)
  {
    if (c == '$' || c == '*')
      return Outcome::kMalformed;
    sum ^= static_cast<std::uint8_t>(c);
  }
  return sum == (high << 4 | low) ? Outcome::kOk : Outcome::kBadChecksum;
}

/// Sentence type from the address field; kUnsupported for anything else.
Outcome classify(const NmeaFields& f, NmeaSentence& s)
{
  const std::string_view address = f[0];
  if (address == "PUBX")
  {
    if (f[1] != "00")
      return Outcome::kUnsupported;
    s.type = NmeaSentenceType::kPubx00;
    s.talker[0] = 'P';
    s.talker[1] = 'U';
    return Outcome::kOk;
  }
  if (address.size() != 5)
    return address.size() >= 2 && address[0] == 'P' ? Outcome::kUnsupported : Outcome::kMalformed;
  for (const char c : address)
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')))
      return Outcome::kMalformed;
  const std::string_view type = address.substr(2);
  s.talker[0] = address[0];
  s.talker[1] = address[1];
  if (type == "GGA")
    s.type = NmeaSentenceType::kGga;
  else if (type == "RMC")
    s.type = NmeaSentenceType::kRmc;
  else if (type == "VTG")
    s.type = NmeaSentenceType::kVtg;
  else if (type == "GST")
    s.type = NmeaSentenceType::kGst;
  else if (type == "ZDA")
    s.type = NmeaSentenceType::kZda;
  else if (type == "GNS")
    s.type = NmeaSentenceType::kGns;
  else if (type == "GLL")
    s.type = NmeaSentenceType::kGll;
  else
    return Outcome::kUnsupported;
  return Outcome::kOk;
}
}  // namespace

const char* toString(NmeaSentenceType type)
{
  switch (type)
  {
    case NmeaSentenceType::kGga: return "GGA";
    case NmeaSentenceType::kRmc: return "RMC";
    case NmeaSentenceType::kVtg: return "VTG";
    case NmeaSentenceType::kGst: return "GST";
    case NmeaSentenceType::kZda: return "ZDA";
    case NmeaSentenceType::kPubx00: return "PUBX,00";
    case NmeaSentenceType::kGns: return "GNS";
    case NmeaSentenceType::kGll: return "GLL";
  }
  return "?";
}

const char* toString(NmeaParseOutcome outcome)
{
  switch (outcome)
  {
    case Outcome::kOk: return "ok";
    case Outcome::kBadChecksum: return "bad checksum";
    case Outcome::kMalformed: return "malformed";
    case Outcome::kUnsupported: return "unsupported";
  }
  return "?";
}

NmeaParseOutcome parseNmeaSentence(std::string_view line, NmeaSentence& sentence)
{
  std::string_view body;
  const Outcome frame = checkFrame(line, body);
  if (frame != Outcome::kOk)
    return frame;
  if (line.front() == '!')  // encapsulation (AIS !AIVDM, !AIVDO): valid, not for the driver
    return Outcome::kUnsupported;
  const NmeaFields fields(body);
  sentence = NmeaSentence();
  const Outcome kind = classify(fields, sentence);
  if (kind != Outcome::kOk)
    return kind;
  switch (sentence.type)
  {
    case NmeaSentenceType::kGga: return parseGga(fields, sentence);
    case NmeaSentenceType::kRmc: return parseRmc(fields, sentence);
    case NmeaSentenceType::kVtg: return parseVtg(fields, sentence);
    case NmeaSentenceType::kGst: return parseGst(fields, sentence);
    case NmeaSentenceType::kZda: return parseZda(fields, sentence);
    case NmeaSentenceType::kPubx00: return parsePubx00(fields, sentence);
    case NmeaSentenceType::kGns: return parseGns(fields, sentence);
    case NmeaSentenceType::kGll: return parseGll(fields, sentence);
  }
  return Outcome::kMalformed;
}

bool nmeaLineTimeOfDay(std::string_view line, double& time_of_day_s)
{
  if (line.size() < 7 || line.front() != '$')
    return false;
  const std::size_t star = line.find('*');
  const NmeaFields fields(line.substr(1, star == std::string_view::npos ? line.npos : star - 1));
  const std::string_view address = fields[0];
  std::string_view time_field;
  if (address == "PUBX")
    time_field = fields[1] == "00" || fields[1] == "04" ? fields[2] : std::string_view();
  else if (address.size() == 5)
  {
    const std::string_view type = address.substr(2);
    if (type == "GGA" || type == "RMC" || type == "GST" || type == "ZDA" || type == "GNS" || type == "GBS")
      time_field = fields[1];
    else if (type == "GLL")
      time_field = fields[5];
  }
  return readTimeOfDay(time_field, time_of_day_s) == FieldStatus::kOk;
}

bool lacksChecksumField(std::string_view line)
{
  return !line.empty() && (line.front() == '$' || line.front() == '!') && line.find('*') == std::string_view::npos;
}

}  // namespace acc
