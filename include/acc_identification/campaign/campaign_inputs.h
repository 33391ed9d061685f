#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "acc_identification/io/input_account.h"
#include "acc_identification/io/openacc_file.h"
#include "acc_identification/io/run_plausibility.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// A car's setting in a run: its own from `car_settings` (a resolved mixed run), else the run's.
const std::string& settingOfCar(const std::map<std::string, std::string>& car_settings, const std::string& run_setting,
                                const std::string& vehicle);

/// One OpenACC file of a campaign: the file as read (every car's speed and gap, for the platoon
/// check) and its distance setting.
struct CampaignFile
{
  std::string path;
  std::string name;     ///< "dynamic_part12"
  std::string setting;  ///< the Distance_setting line ("S", "M", "L"; "?" when absent)
  OpenAccFile contents;
  /// Each car's own setting where the file's is a mixed one ("SL") that a mixed-setting listing
  /// resolves (io/mixed_setting_listing.h): by vehicle name, every car of the file; else empty.
  std::map<std::string, std::string> car_settings;
  /// Every pair of the file as read (accountOfRunFile: the pair and the reader's counts), also the
  /// pairs skipped for want of a usable run: the JSON's inputs.files[].pairs_read.
  std::vector<InputAccount> pairs_read;

  /// The car's setting: its own from car_settings, else the file's.
  const std::string& settingOf(const std::string& vehicle) const;
};

/// One leader-follower pair of one file: the follower's runs there (a pair's data split at NaN
/// cells and holes, so possibly several segments).
struct CampaignRun
{
  std::size_t file_index = 0;  ///< into CampaignInputs::files
  OpenAccPair pair;
  std::vector<CarFollowingRun> segments;

  std::size_t samples() const;
};

/// One car at one distance setting: every file where it follows with that setting.
struct CampaignGroup
{
  std::string vehicle;
  std::string setting;
  std::vector<CampaignRun> runs;  ///< in file order

  std::size_t samples() const;
  /// Every segment of every run: what the group's model is calibrated on.
  std::vector<CarFollowingRun> segments() const;
  /// The segments of every run but the one in this file (leave-one-run-out).
  std::vector<CarFollowingRun> segmentsExcept(std::size_t file_index) const;
  /// The run in this file, or nullptr.
  const CampaignRun* runIn(std::size_t file_index) const;
  /// "TOYOTA_RAV4/S".
  std::string label() const;
};

/// The files of a campaign and its followers grouped by (vehicle, setting).
struct CampaignInputs
{
  std::vector<CampaignFile> files;
  std::vector<CampaignGroup> groups;  ///< by vehicle name, then setting (S, M, L, then others)
  std::vector<std::string> notes;     ///< files and pairs skipped and why, and what read files lose
  std::size_t skipped_files = 0;      ///< files not read (not OpenACC, unreadable, no pair)
  std::size_t skipped_pairs = 0;      ///< pairs of read files without a usable run

  /// "skipped 1 file(s) and 2 pair(s) (each in a note above)", for the summary line.
  std::string describeSkipped() const;

  /// The group of this vehicle and setting, or nullptr.
  const CampaignGroup* findGroup(const std::string& vehicle, const std::string& setting) const;
};

/// The files a campaign reads, and the folder's files it does not, each with its reason.
struct CampaignFileList
{
  std::vector<std::string> files;
  std::vector<std::string> skipped;  ///< "path: not an OpenACC file (...), skipped"
  std::vector<std::string> listings;  ///< the database's mixed-setting tables (looksLikeMixedSettingListing)
  /// "folder: N subfolder(s) not searched and M file(s) named .CSV in another case not read": said
  /// once per folder, not counted as skipped files
  std::vector<std::string> unread;
};

/// The files to read: each FILE given and each folder's *.csv files that look like OpenACC files
/// (looksLikeOpenAccFile), all in the natural order of their paths (part5 before part12), whatever
/// order they are named in, so that a set of files gives one answer; a folder's other *.csv
/// files are listed as skipped. Throws std::invalid_argument for a path that is neither a file nor
/// a folder, or a folder without any OpenACC file. A mixed-setting listing, given or in a folder,
/// goes to `listings`.
CampaignFileList listCampaignFiles(const std::vector<std::string>& files_or_folders);

/// Reads every file (readOpenAccFile and readAllPairRuns: every available pair) and groups the
/// followers by (vehicle name, Distance_setting; a setting written in another case or another word
/// than an earlier file's, "Min" or "S" after "min", takes the earlier spelling: distanceSettingLetter). In a mixed-setting run ("SL") that a listing among the paths
/// names, each car is grouped at its own setting (CampaignFile::car_settings), said in a note; one
/// no listing names is a group of its own at "SL", said too. A file that cannot be read as OpenACC, or a pair without
/// usable runs, is skipped with a note that says why, and counted; so is a file whose cars' speeds
/// repeat an earlier file's sample for sample (io/repeated_recording.h: a copy, an excerpt, the same
/// drive exported twice), which leave-one-run-out would otherwise fit on itself. What a read file loses is a
/// note too: duplicate rows dropped, cars without data or without a pair, the rows each pair
/// rejects, where its gap saw-tooths and is rebuilt (each stretch named; a car whose gaps ahead and
/// behind saw-tooth in opposite phase is named once more, as the one whose position is at
/// fault), a first car without data, where a pair's gap and speeds disagree (checkGapKinematics), and metadata the file lacks or contradicts (OpenAccFile::metadata_problems). Throws RunReadError, naming every skip, when no group results.
CampaignInputs loadCampaign(const std::vector<std::string>& paths,
                            const RunPlausibilityBounds& bounds = RunPlausibilityBounds{});

/// Rank of a distance setting for ordering: S, M, L first (in any of their words: min, medium,
/// max...), then anything else.
int settingRank(const std::string& setting);

}  // namespace acc
