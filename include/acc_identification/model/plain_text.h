#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace acc
{
/// Lists and letter case in the package's texts (notes, reasons, names).

/// The parts with `separator` between them ("a, b, c"; "" for none).
std::string join(const std::vector<std::string>& parts, const std::string& separator);

/// The text in capitals (ASCII letters; "min" -> "MIN"), for names matched in any case.
std::string upperCase(std::string text);

/// The text cut to `most` characters, its end "..." when it was longer: a line of a file quoted in
/// a message (a file without line ends would otherwise be quoted whole).
std::string shortened(const std::string& text, std::size_t most = 120);

/// Natural order: digit runs compare as numbers, so dynamic_part5 comes before dynamic_part12 (and
/// "part5 Hyundai#2" before "part5 Hyundai#10"). The order the tools put files and runs in.
bool naturalLess(const std::string& a, const std::string& b);

/// The items by their names in natural order (naturalLess; equal names keep their order):
/// the order the tools fit and resample runs in, so that a set of runs gives one answer whatever
/// order it is named in (the resampling draws blocks over the runs in this order).
/// `name_of(item)` gives an item's name.
template <class Item, class NameOf>
std::vector<Item> inNaturalOrder(std::vector<Item> items, NameOf name_of)
{
  std::stable_sort(items.begin(), items.end(),
                   [&name_of](const Item& a, const Item& b) { return naturalLess(name_of(a), name_of(b)); });
  return items;
}
}  // namespace acc
