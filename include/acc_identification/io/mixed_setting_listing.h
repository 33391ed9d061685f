#pragma once

#include <map>
#include <string>
#include <vector>

namespace acc
{
/// The OpenACC database's table of mixed-setting runs. In ZalaZone's handling course a platoon ran
/// at the short setting but for two cars in its middle at the long one; such a file says
/// `Distance_setting,SL` and does not name the two. The database names them in a separate CSV
/// ("Long setting vehs in mixed timegap experiment handling": a header `filename,Long timegap
/// setting`, then per file `handling_part12,BMW_I3/MERCEDES_GLE450`). Recognised by that header,
/// whatever the file is called; the setting it lists is the one the header's first word names
/// (Long -> L, Short -> S, Medium -> M: `distanceSettingLetter`).
struct MixedSettingListing
{
  std::string path;
  std::string listed_setting;  ///< "L"; "" when the header names no known setting
  /// The cars at listed_setting, by run name as the campaign names a file (its name without
  /// ".csv": "handling_part12").
  std::map<std::string, std::vector<std::string>> cars_by_run;
  /// "line 4: no car named for handling_part7", each a line left out; and a header without a
  /// known setting.
  std::vector<std::string> problems;
};

/// Whether the file's first non-blank line is such a header: `filename` and a column whose name
/// says "setting".
bool looksLikeMixedSettingListing(const std::string& path);

/// Reads the table. A row without a car, or naming a run listed before, is left out with a
/// problem; a file that cannot be opened gives one problem and no rows.
MixedSettingListing readMixedSettingListing(const std::string& path);

}  // namespace acc
