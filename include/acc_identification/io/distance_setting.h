#pragma once

#include <string>

namespace acc
{
/// The ACC setting a `Distance_setting` word names, as one letter: "S" for the shortest time gap
/// (S, short, shortest, min, minimum), "M" for a middle one (M, medium, mid, middle), "L" for the
/// longest (L, long, longest, max, maximum); "" for any other word (a number, a mixed "SL").
/// Case is ignored. The campaigns spell the same setting differently: ZalaZone writes S and L
/// ("S and L settings refer to the minimum and maximum vehicle setting", its notes), Casale writes
/// `min`, and the database's mixed-run listing names "Long timegap setting".
std::string distanceSettingLetter(const std::string& word);

/// "the shortest setting" for "S", "a middle setting" for "M", "the longest setting" for "L"; ""
/// for anything else. For notes that say why two spellings are one setting.
std::string describeDistanceSetting(const std::string& letter);

}  // namespace acc
