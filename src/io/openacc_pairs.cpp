#include "acc_identification/io/openacc_file.h"

#include <algorithm>

#include "openacc_text.h"

namespace acc
{
using namespace openacc;

std::string OpenAccPair::label() const
{
  return follower_name + " behind " + leader_name + ", positions " + std::to_string(follower_position) + "/" +
         std::to_string(leader_position);
}

std::string describePairlessFollower(const OpenAccFile& file, int follower_position)
{
  const int k = follower_position;
  const int highest = file.lastPosition();
  if (k < 1 || k > highest)
  {
    return "no car at position " + std::to_string(k) + " (Vehicle_order names " +
           std::to_string(file.metadata.vehicle_order.size()) + " cars)";
  }
  const std::string follower = file.vehicleName(k) + " (" + std::to_string(k) + ")";
  if (k == 1)
  {
    return follower + " leads the platoon: no car ahead of it";
  }
  const OpenAccVehicle* behind = file.vehicle(k);
  if (behind == nullptr)
  {
    return follower + " has no data in this file (" + noDataReason(file, k) + ")";
  }
  if (!behind->copied_column.empty())
  {
    return follower + " has no pair: " + behind->copied_column;
  }
  if (behind->speed_values == 0)
  {
    return follower + " has no pair: it has no Speed" + std::to_string(k) + " data";
  }
  const std::string ahead = file.vehicleName(k - 1) + " (" + std::to_string(k - 1) + ")";
  const OpenAccVehicle* leader = file.vehicle(k - 1);
  if (leader == nullptr)
  {
    return follower + " has no pair: the car directly ahead of it, " + ahead + ", has no data in this file (" +
           noDataReason(file, k - 1) + "); a car further ahead is never taken as its leader";
  }
  if (!leader->copied_column.empty())
  {
    return follower + " has no pair: the car directly ahead of it, " + ahead +
           ", is a copied column (its speeds equal another car's on every row), so its leader's speed is not measured";
  }
  if (leader->speed_values == 0)
  {
    return follower + " has no pair: the car directly ahead of it, " + ahead + ", has no Speed" +
           std::to_string(k - 1) + " data";
  }
  const std::string gap = "IVS" + std::to_string(k - 1);
  if (!leader->has_gap_to_follower)
  {
    return follower + " has no pair: their gap " + gap + " (behind " + ahead + ") has no column";
  }
  if (leader->gap_values == 0)
  {
    return follower + " has no pair: their gap " + gap + " (behind " + ahead + ") has no value";
  }
  return "";
}

std::vector<OpenAccPair> availablePairs(const OpenAccFile& file)
{
  std::vector<OpenAccPair> pairs;
  for (const OpenAccVehicle& follower : file.vehicles)
  {
    if (follower.position >= 2 && describePairlessFollower(file, follower.position).empty())
    {
      pairs.push_back(
          {follower.position - 1, follower.position, file.vehicleName(follower.position - 1), follower.name});
    }
  }
  return pairs;
}

std::string describeAvailablePairs(const OpenAccFile& file)
{
  std::vector<std::string> labels;
  for (const OpenAccPair& pair : availablePairs(file))
  {
    labels.push_back(pair.label());
  }
  return labels.empty() ? "none" : join(labels, "; ");
}

OpenAccPairSelector OpenAccPairSelector::parse(const std::string& text)
{
  const std::string trimmed = trim(text);
  if (trimmed.empty())
  {
    return first();
  }
  if (upperCase(trimmed) == "ALL")
  {
    return all();
  }
  return byFollower(trimmed);
}

std::string OpenAccPairSelector::describe() const
{
  switch (kind)
  {
    case Kind::kFirst: return "the first available pair";
    case Kind::kAll: return "all pairs";
    case Kind::kFollower: break;
  }
  return "follower '" + follower + "'";
}

namespace
{
/// Why the file has no pair: each follower's reason.
std::string noPairError(const OpenAccFile& file)
{
  std::vector<std::string> why;
  for (int k = 2; k <= file.lastPosition(); ++k)
  {
    why.push_back(file.vehicle(k) != nullptr ? describePairlessFollower(file, k)
                                             : file.vehicleName(k) + " (" + std::to_string(k) + ") has no data");
  }
  return file.path + ": no leader-follower pair (a follower and the car directly ahead, both with Speed "
                     "data, and their IVS gap)" +
         (why.empty() ? std::string("") : ": " + join(why, "; "));
}

/// The first pair, and the others named: never chosen silently.
OpenAccPairChoice firstPair(const OpenAccFile& file, const std::vector<OpenAccPair>& pairs)
{
  OpenAccPairChoice choice;
  choice.pairs.push_back(pairs.front());
  std::vector<std::string> others;
  for (std::size_t i = 1; i < pairs.size(); ++i)
  {
    others.push_back(pairs[i].label());
  }
  choice.note = file.path + ": pair read: " + pairs.front().label() + " (no follower chosen: the first available " +
                (others.empty() ? std::string("and only pair)") : "pair; the others: " + join(others, "; ") + ")");
  return choice;
}

/// The position of the follower named by a number or a Vehicle_order name (any case); 0 with
/// error set when the name is not there or not unique; -1 for a number too large to be one.
int followerPosition(const OpenAccFile& file, const std::string& wanted, const std::string& listed, std::string& error)
{
  if (!wanted.empty() && wanted.find_first_not_of("0123456789") == std::string::npos)
  {
    const auto number = parseInteger(wanted);
    return number && *number <= 100000 ? static_cast<int>(*number) : -1;
  }
  std::vector<std::string> at;  // the positions of the name, as written in messages
  int position = 0;
  for (std::size_t i = 0; i < file.metadata.vehicle_order.size(); ++i)
  {
    if (upperCase(file.metadata.vehicle_order[i]) == upperCase(wanted))
    {
      position = at.empty() ? static_cast<int>(i) + 1 : position;
      at.push_back(std::to_string(i + 1));
    }
  }
  if (at.empty())
  {
    error = file.path + ": no car '" + wanted + "' in Vehicle_order (" + join(file.metadata.vehicle_order, ", ") +
            "); " + listed;
  }
  else if (at.size() > 1)
  {
    error = file.path + ": '" + wanted + "' is at positions " + join(at, " and ") +
            " of Vehicle_order: choose the follower by position; " + listed;
  }
  return error.empty() ? position : 0;
}

/// The pair of one follower, by position or by name.
OpenAccPairChoice followerPair(const OpenAccFile& file, const std::vector<OpenAccPair>& pairs,
                               const std::string& follower)
{
  OpenAccPairChoice choice;
  const std::string wanted = trim(follower);
  const std::string listed = "pairs in this file: " + describeAvailablePairs(file);
  const int position = followerPosition(file, wanted, listed, choice.error);
  if (!choice.error.empty())
  {
    return choice;
  }
  for (const OpenAccPair& pair : pairs)
  {
    if (pair.follower_position == position)
    {
      choice.pairs.push_back(pair);
      choice.note = file.path + ": pair read: " + pair.label() + " (follower '" + wanted + "' chosen)";
      return choice;
    }
  }
  // A number too large to be a position (-1) is named as written, not as the 0 it is not.
  const std::string why = position >= 0 ? describePairlessFollower(file, position)
                                         : "no car at position " + wanted + " (Vehicle_order names " +
                                               std::to_string(file.metadata.vehicle_order.size()) + " cars)";
  choice.error = file.path + ": no pair with follower '" + wanted + "'" +
                 (position >= 1 ? " (position " + std::to_string(position) + ")" : "") + ": " + why + "; " + listed;
  return choice;
}
}  // namespace

OpenAccPairChoice selectOpenAccPairs(const OpenAccFile& file, const OpenAccPairSelector& selector)
{
  const std::vector<OpenAccPair> pairs = availablePairs(file);
  if (pairs.empty())
  {
    OpenAccPairChoice choice;
    choice.error = noPairError(file);
    return choice;
  }
  switch (selector.kind)
  {
    case OpenAccPairSelector::Kind::kFirst: return firstPair(file, pairs);
    case OpenAccPairSelector::Kind::kAll:
      return {pairs, "", file.path + ": every pair read (" + std::to_string(pairs.size()) + "): " +
                             describeAvailablePairs(file)};
    case OpenAccPairSelector::Kind::kFollower: break;
  }
  return followerPair(file, pairs, selector.follower);
}


}  // namespace acc
