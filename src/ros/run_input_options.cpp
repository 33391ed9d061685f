#include "acc_identification/ros/run_input_options.h"

#include "acc_identification/tools/number_checks.h"

namespace acc
{
void RunInputOptions::declare(CLI::App& app, const std::string& all_pairs_means, bool required)
{
  auto* run_option = app.add_option("RUN", paths,
                                    "a canonical CSV (time_s,space_gap_m,follower_speed_mps,leader_speed_mps), an "
                                    "OpenACC CSV, or a bag of acc_identification/RelativeState")
                         ->check(CLI::ExistingFile);
  if (required)
    run_option->required();
  app.add_option("--topic", bag.relative_state, "RelativeState topic in bags")->capture_default_str();
  app.add_option("--acc-engaged-topic", bag.acc_engaged,
                 "bags: the ACC's engagement reports (std_msgs/Bool); samples recorded while the latest says false "
                 "are not used, as identifier_node does not use them ('': none)")
      ->capture_default_str();
  app.add_flag("--require-acc-engaged", bag.engagement.required,
               "bags: use a sample only while the latest engagement report says engaged (identifier_node's "
               "~require_acc_engaged)");
  app.add_option("--acc-engaged-timeout", bag.engagement.timeout_s,
                 "bags: an engagement report older than this says nothing (identifier_node's ~acc_engaged_timeout_s; "
                 "0: it holds until the next) [s]")
      ->check(acc::nonNegativeNumber())
      ->capture_default_str();
  app.add_option("--acc-setting-topic", bag.acc_setting,
                 "bags: the ACC's distance setting (std_msgs/String), as identifier_node reads it: runs end where it "
                 "changes ('': none)")
      ->capture_default_str();
  app.add_option("--acc-setting", bag.only_setting,
                 "bags: use only the samples recorded at this ACC setting, as the setting topic names it");
  app.add_option("--max-gap", max_gap_s, "split runs at holes longer than this [s]")
      ->check(acc::positiveNumber())
      ->capture_default_str();
  auto* follower_option =
      app.add_option("--follower", follower,
                     "OpenACC files: the follower of the pair to read, by its Vehicle_order name (e.g. BMW_I3, any "
                     "case) or position (e.g. 3); its leader is the car directly ahead (default: the first pair, "
                     "said on stderr)");
  auto* all_pairs_option =
      app.add_flag("--all-pairs", all_pairs, "OpenACC files: read every leader-follower pair; " + all_pairs_means);
  follower_option->excludes(all_pairs_option);
}

RunArguments RunInputOptions::read(std::ostream& log) const { return readPaths(paths, log); }

RunArguments RunInputOptions::readPaths(const std::vector<std::string>& other_paths, std::ostream& log) const
{
  return readRunArguments(other_paths, bag, max_gap_s, log, pairSelectorFromOptions(follower, all_pairs));
}

std::pair<RunArguments, RunArguments> RunInputOptions::readWithHeldOut(const std::vector<std::string>& held_out_paths,
                                                                       std::ostream& log) const
{
  std::pair<RunArguments, RunArguments> read{this->read(log), readPaths(held_out_paths, log)};
  refuseHeldOutRepeats(read.first, read.second);
  return read;
}

}  // namespace acc
