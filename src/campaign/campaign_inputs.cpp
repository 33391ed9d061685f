#include "acc_identification/campaign/campaign_inputs.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <utility>

#include "acc_identification/io/run_csv.h"

namespace acc
{
namespace
{
namespace fs = std::filesystem;

/// Natural order: digit runs compare as numbers, so dynamic_part5 comes before dynamic_part12.
bool naturalLess(const std::string& a, const std::string& b)
{
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size())
  {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j])))
    {
      std::size_t i_end = i, j_end = j;
      while (i_end < a.size() && std::isdigit(static_cast<unsigned char>(a[i_end])))
        ++i_end;
      while (j_end < b.size() && std::isdigit(static_cast<unsigned char>(b[j_end])))
        ++j_end;
      const std::string x = a.substr(i, i_end - i), y = b.substr(j, j_end - j);
      if (x.size() != y.size())
        return x.size() < y.size();
      if (x != y)
        return x < y;
      i = i_end;
      j = j_end;
      continue;
    }
    if (a[i] != b[j])
      return a[i] < b[j];
    ++i;
    ++j;
  }
  return a.size() - i < b.size() - j;
}

std::vector<std::string> openAccFilesIn(const std::string& folder)
{
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(folder))
  {
    const std::string path = entry.path().string();
    if (entry.is_regular_file() && entry.path().extension() == ".csv" && looksLikeOpenAccFile(path))
      found.push_back(path);
  }
  std::sort(found.begin(), found.end(), naturalLess);
  if (found.empty())
    throw std::invalid_argument(folder + ": no OpenACC *.csv file in this folder");
  return found;
}

/// Adds the pairs of one file to the groups being built (keyed by vehicle and setting).
void addPairs(const AllPairRuns& all, std::size_t file_index, const CampaignFile& file,
              std::map<std::pair<std::string, std::string>, CampaignGroup>& groups, std::vector<std::string>& notes)
{
  for (const PairRunContents& pair : all.pairs)
  {
    if (pair.contents.runs.empty())
    {
      notes.push_back(file.path + ": " + pair.pair.label() + ": no usable run, skipped");
      continue;
    }
    CampaignGroup& group = groups[{pair.pair.follower_name, file.setting}];
    group.vehicle = pair.pair.follower_name;
    group.setting = file.setting;
    group.runs.push_back({file_index, pair.pair, pair.contents.runs});
  }
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

std::size_t CampaignRun::samples() const
{
  std::size_t n = 0;
  for (const CarFollowingRun& segment : segments)
    n += segment.size();
  return n;
}

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
  const auto it = std::find(order.begin(), order.end(), setting);
  return it == order.end() ? static_cast<int>(order.size()) : static_cast<int>(it - order.begin());
}

std::vector<std::string> listCampaignFiles(const std::vector<std::string>& files_or_folders)
{
  std::vector<std::string> files;
  for (const std::string& path : files_or_folders)
  {
    if (fs::is_directory(path))
    {
      const std::vector<std::string> found = openAccFilesIn(path);
      files.insert(files.end(), found.begin(), found.end());
    }
    else if (fs::is_regular_file(path))
    {
      files.push_back(path);
    }
    else
    {
      throw std::invalid_argument(path + ": neither a file nor a folder");
    }
  }
  return files;
}

CampaignInputs loadCampaign(const std::vector<std::string>& paths, const RunPlausibilityBounds& bounds)
{
  CampaignInputs inputs;
  std::map<std::pair<std::string, std::string>, CampaignGroup> groups;
  for (const std::string& path : listCampaignFiles(paths))
  {
    CampaignFile file;
    file.path = path;
    file.contents = readOpenAccFile(path);
    if (!file.contents.error.empty())
    {
      inputs.notes.push_back(path + ": not read as an OpenACC file (" + file.contents.error + "), skipped");
      continue;
    }
    file.name = file.contents.name;
    file.setting = file.contents.metadata.distance_setting.empty() ? "?" : file.contents.metadata.distance_setting;
    AllPairRuns all;
    try
    {
      all = readAllPairRuns(path, bounds);
    }
    catch (const RunReadError& error)
    {
      inputs.notes.push_back(std::string(error.what()) + ", skipped");
      continue;
    }
    inputs.files.push_back(std::move(file));
    addPairs(all, inputs.files.size() - 1, inputs.files.back(), groups, inputs.notes);
  }
  for (auto& entry : groups)
    inputs.groups.push_back(std::move(entry.second));
  std::sort(inputs.groups.begin(), inputs.groups.end(), groupLess);
  if (inputs.groups.empty())
    throw RunReadError("no leader-follower pair with usable runs in the files given");
  return inputs;
}

}  // namespace acc
