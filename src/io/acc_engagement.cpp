#include "acc_identification/io/acc_engagement.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace acc
{
std::string describeAccEngagementSettingsProblem(const AccEngagementSettings& settings)
{
  if (!(std::isfinite(settings.timeout_s) && settings.timeout_s >= 0.0))
  {
    std::ostringstream why;
    why << "the engagement report timeout must be a finite number >= 0 s (0: a report holds until the next), not "
        << settings.timeout_s;
    return why.str();
  }
  return "";
}

AccEngagement::AccEngagement(const AccEngagementSettings& settings) : settings_(settings)
{
  const std::string problem = describeAccEngagementSettingsProblem(settings);
  if (!problem.empty())
  {
    throw std::invalid_argument("AccEngagement: " + problem);
  }
}

void AccEngagement::report(double arrival_s, bool engaged)
{
  if (!engaged && (!has_report_ || engaged_))
  {
    ++disengagements_;
  }
  has_report_ = true;
  engaged_ = engaged;
  report_time_s_ = arrival_s;
  ++reports_;
}

AccEngagement::Use AccEngagement::useAt(double arrival_s) const
{
  // A report from after the sample (the clock went back) is the latest one: age 0.
  const bool stale = settings_.timeout_s > 0.0 && arrival_s - report_time_s_ > settings_.timeout_s;
  if (has_report_ && !stale)
  {
    return engaged_ ? Use::kUsed : Use::kAccOff;
  }
  return settings_.required ? Use::kStateUnknown : Use::kUsed;
}

AccEngagement::Judgement AccEngagement::judge(double arrival_s)
{
  Judgement judgement;
  judgement.use = useAt(arrival_s);
  judgement.starts_stretch = judgement.use != Use::kUsed && judgement.use != previous_use_;
  previous_use_ = judgement.use;
  if (judgement.use == Use::kAccOff)
  {
    ++samples_off_;
  }
  else if (judgement.use == Use::kStateUnknown)
  {
    ++samples_unknown_;
  }
  return judgement;
}

std::string AccEngagement::describe(Use use) const
{
  switch (use)
  {
    case Use::kUsed: return "";
    case Use::kAccOff: return "ACC off (the latest acc_engaged report is false)";
    case Use::kStateUnknown: break;
  }
  if (!has_report_)
  {
    return "ACC state unknown: no acc_engaged report yet, and an engaged ACC is required";
  }
  std::ostringstream why;
  why << "ACC state unknown: the latest acc_engaged report is older than " << settings_.timeout_s
      << " s, and an engaged ACC is required";
  return why.str();
}

std::string AccEngagement::latestReport() const
{
  if (!has_report_)
  {
    return "no report yet";
  }
  return engaged_ ? "engaged" : "off";
}

}  // namespace acc
