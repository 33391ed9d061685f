#pragma once

#include <cstddef>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "acc_identification/model/paper_settings.h"

namespace acc
{
/// Bad input to a figure (an option's value, a missing --run): the tool prints it with its usage
/// and exits 2, where any other error exits 1.
struct FigureUsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Every value option the figures read, without the leading "--" (the tool declares each one to
/// its parser; each figure reads its own with the default it documents in paperFiguresHelp()).
const std::vector<std::string>& figureValueOptions();

/// The figure options as given on the command line (every value of each, in order), with typed
/// access: each accessor takes the figure's default and throws FigureUsageError for a bad value.
class FigureOptions
{
public:
  explicit FigureOptions(std::map<std::string, std::vector<std::string>> given) : given_(std::move(given)) {}

  /// The value of --name as a finite number, or fallback when it is not given; given twice, an
  /// error (which one is meant is not said). Every accessor records the name as read.
  double number(const std::string& name, double fallback) const;
  double positive(const std::string& name, double fallback) const;
  /// A number from lower to upper: the figures' sizes (a step, a duration) kept to what a machine
  /// simulates and holds, rather than ending in an allocation failure.
  double between(const std::string& name, double fallback, double lower, double upper) const;
  /// A whole number >= minimum (and <= 1e6).
  std::size_t count(const std::string& name, std::size_t fallback, std::size_t minimum) const;
  std::string text(const std::string& name, const std::string& fallback) const;
  /// Every value of a repeatable option, in command-line order.
  std::vector<std::string> texts(const std::string& name) const;
  bool has(const std::string& name) const;
  /// The options given a value, by name.
  std::vector<std::string> namesGiven() const;
  /// The options a figure asked for so far, given or not (paper_figures' test of its option lists).
  const std::set<std::string>& namesRead() const { return read_; }

private:
  /// The one value of a single-valued option (given: has(name)).
  const std::string& single(const std::string& name) const;

  std::map<std::string, std::vector<std::string>> given_;
  mutable std::set<std::string> read_;
};

/// "0.5,1,1.5" -> {0.5, 1, 1.5}; throws FigureUsageError naming --option for an item that is not a
/// finite number.
std::vector<double> parseNumberList(const std::string& text, const std::string& option);

/// The parameter sets the options name, in command-line order (--setting, --params, then one
/// custom set from --k1 --k2 --tau-e [--eta]), or the figure's default named settings.
std::vector<NamedSetting> resolveSettings(const FigureOptions& options, const std::vector<std::string>& defaults);

}  // namespace acc
