#include "acc_identification/campaign/campaign_inputs.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "acc_identification/io/csv_fields.h"
#include "acc_identification/io/distance_setting.h"
#include "acc_identification/io/gap_kinematics.h"
#include "acc_identification/io/mixed_setting_listing.h"
#include "acc_identification/io/repeated_recording.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/model/plain_text.h"

namespace acc
{
namespace
{
namespace fs = std::filesystem;


/// The notes, each on an indented line of its own (for an error that lists them).
std::string joinNotes(const std::vector<std::string>& notes)
{
  std::string text;
  for (const std::string& note : notes)
    text += "\n  " + note;
  return text;
}

/// The folder's *.csv files in natural order: the OpenACC ones to read, the others skipped.
CampaignFileList openAccFilesIn(const std::string& folder)
{
  std::vector<std::string> csv;
  // Not read, and said so: a subfolder of runs (the parent of the run folders given), a table
  // named .CSV. The database's notes (.txt) beside its runs are expected and not listed.
  std::size_t subfolders = 0, other_case = 0;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    const std::string extension = entry.path().extension().string();
    if (entry.is_regular_file() && extension == ".csv")
      csv.push_back(entry.path().string());
    else if (entry.is_directory())
      ++subfolders;
    else if (entry.is_regular_file() && extension.size() == 4 &&
             std::equal(extension.begin(), extension.end(), ".csv",
                        [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; }))
      ++other_case;
  }
  std::sort(csv.begin(), csv.end(), naturalLess);
  CampaignFileList list;
  if (subfolders + other_case > 0)
    list.unread.push_back(folder + ": " + std::to_string(subfolders) + " subfolder(s) not searched and " +
                          std::to_string(other_case) + " file(s) named .CSV in another case not read (give a folder "
                          "of runs as its own argument; name a table .csv)");
  for (const std::string& path : csv)
  {
    if (looksLikeOpenAccFile(path))
      list.files.push_back(path);
    else if (looksLikeMixedSettingListing(path))
      list.listings.push_back(path);
    else
      list.skipped.push_back(path + ": not an OpenACC file (its first line is neither a Date line nor a header with "
                                    "Time and a car's Speedk)" +
                             textLayoutHint(path) + ", skipped");
  }
  if (list.files.empty())
    throw std::invalid_argument(folder + ": no OpenACC *.csv file in this folder" +
                                (csv.empty() && list.unread.empty()
                                     ? std::string("")
                                     : ":" + joinNotes(list.unread) + joinNotes(list.skipped)));
  return list;
}

/// Why a pair read from the file gave no run: its rows' counts, and the first problem met.
std::string whyNoUsableRun(const RunFileContents& contents)
{
  if (contents.acc_off_rows == contents.data_rows)
    return "the follower is on ACC in none of its " + std::to_string(contents.data_rows) + " rows";
  std::string why = std::to_string(contents.data_rows) + " rows, " + std::to_string(contents.rejected_rows) +
                    " rejected, " + std::to_string(contents.acc_off_rows) +
                    " not on ACC: no stretch of two samples or more";
  if (!contents.problems.empty())
    why += " (first problem: " + contents.problems.front() + ")";
  return why + describeTimeOrder(contents) + describeCoarseSteps(contents);
}

/// A ZalaZone setting that names two or three of S, M and L ("SL": the database's mixed runs, the
/// platoon at the first but for a few cars at the second, listed outside the file).
bool isMixedSetting(const std::string& setting)
{
  const std::string upper = upperCase(setting);
  return upper.size() >= 2 && upper.size() <= 3 && upper.find_first_not_of("SML") == std::string::npos &&
         std::set<char>(upper.begin(), upper.end()).size() == upper.size();
}

/// The file's Distance_setting as the campaign spells it: "?" when unknown. A setting met before
/// under another spelling takes the first spelling, said in a note, so that one car's runs at one
/// setting are one group: another case ("Min" after "min"), or another word for the same setting
/// ("min" after "S": both the shortest, `distanceSettingLetter`).
std::string settingSpelling(const std::string& written, std::map<std::string, std::string>& spellings,
                            const std::string& path, std::vector<std::string>& notes)
{
  if (written.empty())
    return "?";
  const std::string letter = distanceSettingLetter(written);
  const auto [known, first] = spellings.emplace(letter.empty() ? upperCase(written) : letter, written);
  if (first && letter.empty() && !isMixedSetting(written))
    notes.push_back(path + ": Distance_setting '" + written + "' is no word for the shortest, a middle or the longest "
                    "setting this reader knows (S, M, L, min, max, ...): its cars form groups of their own, '" +
                    written + "'");
  if (first || known->second == written)
    return known->second;
  const bool same_word = upperCase(known->second) == upperCase(written);
  notes.push_back(path + ": Distance_setting '" + written + "' taken as '" + known->second +
                  "', as an earlier file writes it" +
                  (same_word ? "" : " (both name " + describeDistanceSetting(letter) + ")"));
  return known->second;
}

/// One run of a mixed-setting listing: the cars at the listed setting, and the listing's path.
struct ListedRun
{
  std::string setting;
  std::vector<std::string> cars;
  std::string listing_path;
};
using ListedRuns = std::map<std::string, ListedRun>;  ///< by run name ("handling_part12")

/// Every listing's runs; what a listing leaves out, and a run listed twice, in the notes.
ListedRuns readListings(const std::vector<std::string>& paths, std::vector<std::string>& notes)
{
  ListedRuns runs;
  for (const std::string& path : paths)
  {
    const MixedSettingListing listing = readMixedSettingListing(path);
    for (const std::string& problem : listing.problems)
      notes.push_back(path + ": " + problem);
    if (listing.listed_setting.empty())
      continue;
    notes.push_back(path + ": read as the database's listing of mixed-setting runs: " +
                    std::to_string(listing.cars_by_run.size()) + " run(s) with cars at " + listing.listed_setting);
    for (const auto& [run, cars] : listing.cars_by_run)
    {
      const auto [known, added] = runs.emplace(run, ListedRun{listing.listed_setting, cars, path});
      if (!added)
        notes.push_back(path + ": " + run + " is listed in " + known->second.listing_path +
                        " too: that listing is followed");
    }
  }
  return runs;
}

/// The file's car of this name in the file's spelling, or "" (matched in any case).
std::string carNamed(const OpenAccFile& file, const std::string& name)
{
  for (int k = 1; k <= file.lastPosition(); ++k)
  {
    if (upperCase(file.vehicleName(k)) == upperCase(name))
      return file.vehicleName(k);
  }
  return "";
}

/// The mixed setting's other letter than `listed` ("SL", "L" -> "S"), or "" when the listed
/// setting is not one of its two.
std::string otherSettingOf(const std::string& mixed, const std::string& listed)
{
  const std::string upper = upperCase(mixed);
  if (upper.size() != 2 || upper.find(listed) == std::string::npos)
    return "";
  return std::string(1, upper[0] == listed[0] ? upper[1] : upper[0]);
}

/// Why a listing's entry for this file is not followed, or "" when it is.
std::string whyListingNotFollowed(const CampaignFile& file, const ListedRun& listed,
                                  const std::vector<std::string>& unknown_cars)
{
  if (!isMixedSetting(file.setting))
    return "its Distance_setting '" + file.setting + "' is not a mixed one: every car is taken at '" +
           file.setting + "'";
  if (otherSettingOf(file.setting, listed.setting).empty())
    return "'" + listed.setting + "' is not one of the two settings of '" + file.setting + "'";
  if (!unknown_cars.empty())
    return join(unknown_cars, ", ") + " not in this file's Vehicle_order";
  return "";
}

/// Each car's own setting in a mixed-setting run that a listing names, said in a note; a mixed
/// run no listing names (or one whose entry does not fit the file) is a group of its own, said too.
/// The two settings are spelled as the files before spell them (settingSpelling).
void resolveMixedSetting(CampaignFile& file, const ListedRuns& listed_runs,
                         std::map<std::string, std::string>& setting_spellings, std::vector<std::string>& notes)
{
  const auto entry = listed_runs.find(file.name);
  std::string why_not;
  if (entry != listed_runs.end())
  {
    const ListedRun& listed = entry->second;
    std::vector<std::string> unknown_cars, cars;
    for (const std::string& name : listed.cars)
    {
      const std::string car = carNamed(file.contents, name);
      (car.empty() ? unknown_cars : cars).push_back(car.empty() ? name : car);
    }
    why_not = whyListingNotFollowed(file, listed, unknown_cars);
    if (why_not.empty())
    {
      const std::string other =
          settingSpelling(otherSettingOf(file.setting, listed.setting), setting_spellings, file.path, notes);
      const std::string listed_setting = settingSpelling(listed.setting, setting_spellings, file.path, notes);
      for (int k = 1; k <= file.contents.lastPosition(); ++k)
        file.car_settings[file.contents.vehicleName(k)] = other;
      for (const std::string& car : cars)
        file.car_settings[car] = listed_setting;
      notes.push_back(file.path + ": Distance_setting '" + file.setting + "' is a mixed run; " + listed.listing_path +
                      " names " + join(cars, ", ") + " at " + listed_setting + ": grouped at " + listed_setting +
                      ", the other cars at " + other);
      return;
    }
    notes.push_back(file.path + ": " + listed.listing_path + " lists " + join(listed.cars, ", ") + " at " +
                    listed.setting + " in this run, not followed: " + why_not);
  }
  if (isMixedSetting(file.setting))
    notes.push_back(file.path + ": Distance_setting '" + file.setting +
                    "' is a mixed run (in the ZalaZone notes: the platoon at the first setting but for a few "
                    "cars at the other, which the file does not name; the database names them in a separate "
                    "listing, not given with it" + (why_not.empty() ? "" : " or not followed") +
                    "): each car's setting here is not known, so its runs of this file form a group of their own at '" +
                    file.setting + "', apart from its runs at either setting");
}

/// The file's cars that give the campaign no pair, each with the reader's reason.
void noteCarsWithoutPair(const OpenAccFile& file, std::vector<std::string>& notes)
{
  if (file.vehicle(1) == nullptr)
    notes.push_back(file.path + ": the first car, " + file.vehicleName(1) +
                    ", has no data: the platoon of this file is not checked");
  std::vector<std::string> without_data;
  for (int k = 2; k <= file.lastPosition(); ++k)
  {
    if (file.vehicle(k) == nullptr)
      without_data.push_back(file.vehicleName(k) + " (" + std::to_string(k) + ")");
    else if (const std::string why = describePairlessFollower(file, k); !why.empty())
      notes.push_back(file.path + ": " + why + ": not in the campaign");
  }
  if (!without_data.empty())
    notes.push_back(file.path + ": no data for " + join(without_data, ", ") + ": not in the campaign");
}

/// The rows a pair rejects for a cell of its own: not the file's exact repeats, which every pair
/// counts and the file's own note lists.
std::size_t ownRejectedRows(const PairRunContents& pair)
{
  return pair.contents.rejected_rows - pair.contents.duplicate_rows;
}

/// "TESLA_MODEL3 59", "BMW_I3 3 and 1 hole in time" or "Hyundai none, 1 hole in time": what one
/// pair loses.
std::string describePairLosses(const PairRunContents& pair)
{
  const std::size_t rows = ownRejectedRows(pair), holes = pair.contents.time_holes;
  const std::string hole_text = std::to_string(holes) + (holes == 1 ? " hole" : " holes") + " in time";
  if (rows == 0)
    return pair.pair.follower_name + " none, " + hole_text;
  return pair.pair.follower_name + " " + std::to_string(rows) + (holes == 0 ? "" : " and " + hole_text);
}

/// One pair's saw-tooth spans (gap_sawtooth.h), with where the pair sits in the platoon.
struct PairSawtooth
{
  const OpenAccPair* pair = nullptr;
  std::vector<GapSawtoothSpan> spans;
};

/// The first span of `ahead` (the gap in front of a car) that overlaps one of `behind` (the gap
/// behind it) in time with the opposite sign, or nullptr.
const GapSawtoothSpan* oppositePhaseSpan(const PairSawtooth& ahead, const PairSawtooth& behind)
{
  for (const GapSawtoothSpan& a : ahead.spans)
    for (const GapSawtoothSpan& b : behind.spans)
      if (a.start_s < b.end_s && b.start_s < a.end_s && a.median_step_mismatch_m * b.median_step_mismatch_m < 0.0)
        return &a;
  return nullptr;
}

/// A car whose gap ahead and gap behind saw-tooth at once, in opposite phase: the two gaps share
/// only its position, so that position was held or extrapolated, not either range. One note per
/// such car, beside the pairs' own.
void addSawtoothCars(const std::vector<PairSawtooth>& pairs, const std::string& path, std::vector<std::string>& notes)
{
  for (const PairSawtooth& ahead : pairs)
    for (const PairSawtooth& behind : pairs)
    {
      if (behind.pair->leader_position != ahead.pair->follower_position)
        continue;
      if (const GapSawtoothSpan* span = oppositePhaseSpan(ahead, behind))
        notes.push_back(path + ": " + ahead.pair->follower_name + " (" + std::to_string(ahead.pair->follower_position) +
                        printfText("): its gaps ahead and behind saw-tooth from t = %.1f s in opposite phase: ",
                                   span->start_s) +
                        "its own position was held (or extrapolated) there, not either gap's measurement");
    }
}

/// The file's unit error: the first pair's words when some pair's ratio is a unit error and no
/// pair's judged ratio is right (speeds or gaps in other units throughout, not one car's column;
/// pairs in steady following judge nothing), else "". `kinematics`: kinematicsOfPairs(all).
std::string unitErrorOfFile(const AllPairRuns& all, const std::vector<GapKinematics>& kinematics)
{
  std::string first;
  for (std::size_t i = 0; i < all.pairs.size(); ++i)
  {
    if (kinematics[i].ratio_judged && kinematics[i].unit_error.empty())
      return "";
    if (first.empty() && !kinematics[i].unit_error.empty())
      first = all.pairs[i].pair.label() + ": " + kinematics[i].unit_error;
  }
  return first;
}

/// Each pair's gap against its speeds (checkGapKinematics), in all.pairs' order: judged once for
/// the file's unit error and for each pair's own.
std::vector<GapKinematics> kinematicsOfPairs(const AllPairRuns& all)
{
  std::vector<GapKinematics> kinematics;
  for (const PairRunContents& pair : all.pairs)
    kinematics.push_back(checkGapKinematics(pair.contents.runs));
  return kinematics;
}

/// Adds the pairs of one file to the groups being built (keyed by vehicle and setting);
/// `kinematics` is kinematicsOfPairs(all).
void addPairs(const AllPairRuns& all, const std::vector<GapKinematics>& kinematics, std::size_t file_index,
              const CampaignFile& file, std::map<std::pair<std::string, std::string>, CampaignGroup>& groups,
              std::vector<std::string>& notes, std::size_t& skipped_pairs)
{
  std::vector<std::string> rejected;  // "TESLA_MODEL3 59": the pairs that lose rows, in one note
  std::vector<std::string> acc_off;   // "BMW_I3 120": the pairs whose follower was driven by hand
  std::vector<PairSawtooth> sawtooths;
  for (std::size_t i = 0; i < all.pairs.size(); ++i)
  {
    const PairRunContents& pair = all.pairs[i];
    if (pair.contents.runs.empty())
    {
      notes.push_back(file.path + ": " + pair.pair.label() + ": no usable run (" + whyNoUsableRun(pair.contents) +
                      "), skipped");
      ++skipped_pairs;
      continue;
    }
    if (!kinematics[i].unit_error.empty())
    {
      notes.push_back(file.path + ": " + pair.pair.label() + ": " + kinematics[i].unit_error + kUnitErrorRefusal +
                      ", skipped");
      ++skipped_pairs;
      continue;
    }
    if (ownRejectedRows(pair) + pair.contents.time_holes > 0)
      rejected.push_back(describePairLosses(pair));
    if (pair.contents.acc_off_rows > 0)
      acc_off.push_back(pair.pair.follower_name + " " + std::to_string(pair.contents.acc_off_rows));
    for (const std::string& disagreement : kinematics[i].warnings)
      notes.push_back(file.path + ": " + pair.pair.label() + ": " + disagreement);
    for (const GapSawtoothSpan& span : pair.contents.sawtooth_spans)
      notes.push_back(file.path + ": " + pair.pair.label() + ": " + describeSawtoothSpan(span) + "; " +
                      describeGapRebuilt(span));
    if (!pair.contents.sawtooth_spans.empty())
      sawtooths.push_back({&pair.pair, pair.contents.sawtooth_spans});
    const std::string& setting = file.settingOf(pair.pair.follower_name);
    CampaignGroup& group = groups[{pair.pair.follower_name, setting}];
    group.vehicle = pair.pair.follower_name;
    group.setting = setting;
    group.runs.push_back({file_index, pair.pair, pair.contents.runs});
  }
  addSawtoothCars(sawtooths, file.path, notes);
  if (!rejected.empty())
    notes.push_back(file.path + ": rows a pair cannot use (a bad or implausible cell of its own, its time not "
                    "increasing) split its runs there, each listed by calibrate --all-pairs; rejected of " +
                    std::to_string(file.contents.rows()) + " rows: " + join(rejected, ", "));
  if (!acc_off.empty())
    notes.push_back(file.path + ": rows with the follower's ACC off (driven by hand) are not used and split its runs "
                    "there, each stretch listed by calibrate --all-pairs; of " +
                    std::to_string(file.contents.rows()) + " rows: " + join(acc_off, ", "));
}

bool groupLess(const CampaignGroup& a, const CampaignGroup& b)
{
  if (a.vehicle != b.vehicle)
    return a.vehicle < b.vehicle;
  if (settingRank(a.setting) != settingRank(b.setting))
    return settingRank(a.setting) < settingRank(b.setting);
  return a.setting < b.setting;
}
}  // namespace

const std::string& settingOfCar(const std::map<std::string, std::string>& car_settings, const std::string& run_setting,
                                const std::string& vehicle)
{
  const auto own = car_settings.find(vehicle);
  return own == car_settings.end() ? run_setting : own->second;
}

const std::string& CampaignFile::settingOf(const std::string& vehicle) const
{
  return settingOfCar(car_settings, setting, vehicle);
}

std::size_t CampaignRun::samples() const { return sampleCount(segments); }

std::size_t CampaignGroup::samples() const
{
  std::size_t n = 0;
  for (const CampaignRun& run : runs)
    n += run.samples();
  return n;
}

std::vector<CarFollowingRun> CampaignGroup::segments() const
{
  std::vector<CarFollowingRun> all;
  for (const CampaignRun& run : runs)
    all.insert(all.end(), run.segments.begin(), run.segments.end());
  return all;
}

std::vector<CarFollowingRun> CampaignGroup::segmentsExcept(std::size_t file_index) const
{
  std::vector<CarFollowingRun> others;
  for (const CampaignRun& run : runs)
  {
    if (run.file_index != file_index)
      others.insert(others.end(), run.segments.begin(), run.segments.end());
  }
  return others;
}

const CampaignRun* CampaignGroup::runIn(std::size_t file_index) const
{
  for (const CampaignRun& run : runs)
  {
    if (run.file_index == file_index)
      return &run;
  }
  return nullptr;
}

std::string CampaignGroup::label() const
{
  return vehicle + "/" + setting;
}

const CampaignGroup* CampaignInputs::findGroup(const std::string& vehicle, const std::string& setting) const
{
  for (const CampaignGroup& group : groups)
  {
    if (group.vehicle == vehicle && group.setting == setting)
      return &group;
  }
  return nullptr;
}

int settingRank(const std::string& setting)
{
  static const std::vector<std::string> order{"S", "M", "L"};
  const auto it = std::find(order.begin(), order.end(), distanceSettingLetter(setting));
  return it == order.end() ? static_cast<int>(order.size()) : static_cast<int>(it - order.begin());
}

CampaignFileList listCampaignFiles(const std::vector<std::string>& files_or_folders)
{
  CampaignFileList list;
  for (const std::string& path : files_or_folders)
  {
    if (fs::is_directory(path))
    {
      const CampaignFileList found = openAccFilesIn(path);
      list.files.insert(list.files.end(), found.files.begin(), found.files.end());
      list.skipped.insert(list.skipped.end(), found.skipped.begin(), found.skipped.end());
      list.listings.insert(list.listings.end(), found.listings.begin(), found.listings.end());
      list.unread.insert(list.unread.end(), found.unread.begin(), found.unread.end());
    }
    else if (fs::is_regular_file(path))
    {
      (looksLikeMixedSettingListing(path) ? list.listings : list.files).push_back(path);
    }
    else
    {
      throw std::invalid_argument(path + ": neither a file nor a folder");
    }
  }
  // A set of files gives one answer whatever order they are named in: the resampling draws blocks
  // over the runs in this order (reversed, the same runs moved p-values by 0.007).
  std::stable_sort(list.files.begin(), list.files.end(), naturalLess);
  std::stable_sort(list.listings.begin(), list.listings.end(), naturalLess);
  return list;
}

namespace
{
/// The cars' speeds of a file: the series of its recording (repeated_recording.h), in the order
/// of file.vehicles.
Recording speedsOf(const OpenAccFile& file)
{
  Recording speeds;
  for (const OpenAccVehicle& car : file.vehicles)
    speeds.push_back(car.speed_mps);
  return speeds;
}

/// Why the file is a recording read before (every car of it whose speeds vary repeats a car of an
/// earlier file, sample for sample: repeated_recording.h), or "". The index's ids are into `files`.
std::string whyRepeatsEarlierFile(const OpenAccFile& file, const RepeatedRecordingIndex& read,
                                  const std::vector<CampaignFile>& files)
{
  const std::optional<RepeatedRecording> repeat = read.find(speedsOf(file));
  if (!repeat)
    return "";
  const OpenAccFile& earlier = files[repeat->id].contents;
  return file.vehicles[repeat->series].label() + "'s speeds from " +
         describeSampleTime(file.time_s[repeat->later_row]) + " repeat " + earlier.path + "'s " +
         earlier.vehicles[repeat->earlier_series].label() + " from " +
         describeSampleTime(earlier.time_s[repeat->earlier_row]) + " sample for sample (" +
         std::to_string(kRepeatedRecordingMinSamples) +
         " samples or more, to the last digit), and so do its other cars: the same recording (a copy, an "
         "excerpt or an export of the same drive), skipped, so that no run is predicted by a model fitted on "
         "itself; the file read first is kept (" +
         std::to_string(earlier.rows()) + " rows; this one " + std::to_string(file.rows()) +
         "): give each recording once";
}

/// Why the file holds one drive twice (a piece of a pair repeats an earlier piece of the file
/// sample for sample: the drive appended after itself, its time reset between), or "".
std::string whyHoldsADriveTwice(const std::string& path, const AllPairRuns& all)
{
  std::vector<CarFollowingRun> runs;
  for (const PairRunContents& pair : all.pairs)
    runs.insert(runs.end(), pair.contents.runs.begin(), pair.contents.runs.end());
  const std::string repeat = describeRepeatedRun(runs, std::vector<std::size_t>(runs.size(), 0),
                                                 std::vector<std::string>(runs.size(), path));
  return repeat.empty() ? "" : repeat + ": the file is skipped, so that no drive counts twice; give each drive once";
}

/// One file into the inputs: its pairs into the groups, or a note saying why it is skipped.
void addFile(const std::string& path, const RunPlausibilityBounds& bounds, const ListedRuns& listed_runs,
             CampaignInputs& inputs, std::map<std::pair<std::string, std::string>, CampaignGroup>& groups,
             std::map<std::string, std::string>& setting_spellings, RepeatedRecordingIndex& read)
{
  CampaignFile file;
  file.path = path;
  file.contents = readOpenAccFile(path);
  if (!file.contents.error.empty())
  {
    inputs.notes.push_back(path + ": not read as an OpenACC file (" + file.contents.error + "), skipped");
    ++inputs.skipped_files;
    return;
  }
  if (const std::string why = whyRepeatsEarlierFile(file.contents, read, inputs.files); !why.empty())
  {
    inputs.notes.push_back(path + ": " + why);
    ++inputs.skipped_files;
    return;
  }
  if (!file.contents.metadata.lines_present)
  {
    // The reader's first note, here too: the cars' names and the setting "?" come from it.
    inputs.notes.push_back(file.contents.notes.front());
  }
  file.name = file.contents.name;
  file.setting = settingSpelling(file.contents.metadata.distance_setting, setting_spellings, path, inputs.notes);
  resolveMixedSetting(file, listed_runs, setting_spellings, inputs.notes);
  AllPairRuns all;
  try
  {
    all = readAllPairRuns(path, bounds);
  }
  catch (const RunReadError& error)
  {
    inputs.notes.push_back(std::string(error.what()) + ", skipped");
    ++inputs.skipped_files;
    return;
  }
  if (const std::string twice = whyHoldsADriveTwice(path, all); !twice.empty())
  {
    inputs.notes.push_back(twice);
    ++inputs.skipped_files;
    return;
  }
  const std::vector<GapKinematics> kinematics = kinematicsOfPairs(all);
  if (const std::string unit_error = unitErrorOfFile(all, kinematics); !unit_error.empty())
  {
    // Not one car's column but the file's units: its platoon would be judged in them too.
    inputs.notes.push_back(path + ": no pair's gap and speeds agree, and " + unit_error + kUnitErrorRefusal +
                           ": the file is skipped");
    ++inputs.skipped_files;
    return;
  }
  for (const std::string& problem : file.contents.metadata_problems)
    inputs.notes.push_back(problem);
  if (!file.contents.duplicate_lines.empty())
    inputs.notes.push_back(describeDuplicateRows(file.contents));
  noteCarsWithoutPair(file.contents, inputs.notes);
  for (const PairRunContents& pair : all.pairs)
    file.pairs_read.push_back(accountOfRunFile(path, pair.contents));
  read.add(speedsOf(file.contents), inputs.files.size());
  inputs.files.push_back(std::move(file));
  addPairs(all, kinematics, inputs.files.size() - 1, inputs.files.back(), groups, inputs.notes, inputs.skipped_pairs);
}
}  // namespace

CampaignInputs loadCampaign(const std::vector<std::string>& paths, const RunPlausibilityBounds& bounds)
{
  CampaignInputs inputs;
  const CampaignFileList list = listCampaignFiles(paths);
  inputs.notes = list.unread;
  inputs.notes.insert(inputs.notes.end(), list.skipped.begin(), list.skipped.end());
  inputs.skipped_files = list.skipped.size();
  std::map<std::pair<std::string, std::string>, CampaignGroup> groups;
  std::map<std::string, std::string> setting_spellings;  // by the setting in upper case
  const ListedRuns listed_runs = readListings(list.listings, inputs.notes);
  RepeatedRecordingIndex read;  // the files read so far
  for (const std::string& path : list.files)
    addFile(path, bounds, listed_runs, inputs, groups, setting_spellings, read);
  for (auto& entry : groups)
    inputs.groups.push_back(std::move(entry.second));
  std::sort(inputs.groups.begin(), inputs.groups.end(), groupLess);
  if (inputs.groups.empty())
    throw RunReadError("no leader-follower pair with usable runs in the files given; skipped:" +
                       joinNotes(inputs.notes));
  return inputs;
}

std::string CampaignInputs::describeSkipped() const
{
  return "skipped " + std::to_string(skipped_files) + " file(s) and " + std::to_string(skipped_pairs) + " pair(s)" +
         (skipped_files + skipped_pairs > 0 ? " (each in a note above)" : "");
}

}  // namespace acc
