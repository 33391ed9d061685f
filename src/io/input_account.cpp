#include "acc_identification/io/input_account.h"

#include <string>

namespace acc
{
std::optional<std::size_t> InputAccount::count(const std::string& name) const
{
  for (const auto& [counted, n] : counts)
    if (counted == name)
      return n;
  return std::nullopt;
}

InputAccount accountOfRunFile(const std::string& path, const RunFileContents& contents)
{
  InputAccount account;
  account.path = path;
  account.format = contents.pairs.empty() ? "csv" : "openacc";
  for (const OpenAccPair& pair : contents.pairs)
    account.openacc_pairs.push_back(pair.label());
  account.counts = {{"data_rows", contents.data_rows},
                    {"samples_used", sampleCount(contents.runs)},
                    {"runs", contents.runs.size()},
                    {"rejected_rows", contents.rejected_rows},
                    {"implausible_rows", contents.implausible_rows},
                    {"marked_invalid_rows", contents.marked_invalid_rows},
                    {"duplicate_rows", contents.duplicate_rows},
                    {"acc_off_rows", contents.acc_off_rows},
                    {"single_sample_rows", contents.single_sample_rows},
                    {"time_holes", contents.time_holes},
                    {"gap_rebuilt_rows", contents.sawtooth_rows}};
  return account;
}

std::string describeLossesAndRepairs(const InputAccount& account)
{
  std::string text;
  for (const auto& [name, count] : account.counts)
  {
    if (count == 0 || name == "data_rows" || name == "messages" || name == "samples_used" || name == "runs")
      continue;
    text += (text.empty() ? "" : ", ") + name + " " + std::to_string(count);
  }
  return text;
}

nlohmann::json countsJson(const InputAccount& account)
{
  nlohmann::json counts = nlohmann::json::object();
  for (const auto& [name, count] : account.counts)
    counts[name] = count;
  return counts;
}

nlohmann::json inputAccountsJson(const std::vector<InputAccount>& accounts)
{
  nlohmann::json json = nlohmann::json::array();
  for (const InputAccount& account : accounts)
  {
    nlohmann::json entry{{"path", account.path}, {"format", account.format}, {"counts", countsJson(account)}};
    if (!account.openacc_pairs.empty())
      entry["openacc_pairs"] = account.openacc_pairs;
    json.push_back(entry);
  }
  return json;
}

bool anyOpenAcc(const std::vector<InputAccount>& accounts)
{
  for (const InputAccount& account : accounts)
    if (!account.openacc_pairs.empty())
      return true;
  return false;
}

nlohmann::json openAccPairsJson(const std::vector<InputAccount>& accounts)
{
  nlohmann::json json = nlohmann::json::array();
  for (const InputAccount& account : accounts)
    if (!account.openacc_pairs.empty())
      json.push_back({{"path", account.path}, {"pairs", account.openacc_pairs}});
  return json;
}

void printOpenAccPairs(const std::vector<InputAccount>& accounts, std::ostream& out)
{
  for (const InputAccount& account : accounts)
  {
    if (account.openacc_pairs.empty())
      continue;
    out << "OpenACC pair" << (account.openacc_pairs.size() > 1 ? "s" : "") << " read: " << account.path << ": ";
    for (std::size_t i = 0; i < account.openacc_pairs.size(); ++i)
      out << (i > 0 ? "; " : "") << account.openacc_pairs[i];
    out << "\n";
  }
}

}  // namespace acc
