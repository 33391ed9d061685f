#include "reconnecting_source.h"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <thread>

namespace acc
{
namespace
{
constexpr double kFirstBackoffS = 0.5;
constexpr double kMaxBackoffS = 8.0;

std::chrono::steady_clock::duration seconds(double s)
{
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}
}  // namespace

ReconnectingSource::ReconnectingSource(std::string description)
  : description_(std::move(description)), next_attempt_(Clock::now())
{
}

ReconnectingSource::~ReconnectingSource()
{
  if (fd_ >= 0)
    ::close(fd_);
}

void ReconnectingSource::closeAndRetry(const std::string& why)
{
  if (fd_ >= 0)
    ::close(fd_);
  fd_ = -1;
  backoff_s_ = backoff_s_ == 0.0 ? kFirstBackoffS : std::min(2.0 * backoff_s_, kMaxBackoffS);
  next_attempt_ = Clock::now() + seconds(backoff_s_);
  char retry[48];
  std::snprintf(retry, sizeof retry, "; retrying in %.1f s", backoff_s_);
  state_ = why + retry;
}

ReadResult ReconnectingSource::read(char* buffer, std::size_t capacity, double timeout_s)
{
  ReadResult result;
  const Clock::time_point deadline = Clock::now() + seconds(timeout_s);
  if (fd_ < 0)
  {
    if (Clock::now() < next_attempt_)
    {
      std::this_thread::sleep_until(std::min(deadline, next_attempt_));
      return result;
    }
    std::string error;
    fd_ = open(error);
    if (fd_ < 0)
    {
      closeAndRetry(error);
      return result;
    }
    reopen_count_ += ever_opened_ ? 1 : 0;
    ever_opened_ = true;
    state_ = "open";
  }
  pollfd descriptor{fd_, POLLIN, 0};
  const auto wait_ms = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  const int ready = ::poll(&descriptor, 1, static_cast<int>(std::max<long long>(0, wait_ms)));
  if (ready < 0)
  {
    if (errno != EINTR)
      closeAndRetry(std::string("poll: ") + std::strerror(errno));
    return result;
  }
  if (ready == 0)
    return result;
  const ssize_t count = ::read(fd_, buffer, capacity);
  if (count > 0)
  {
    backoff_s_ = 0.0;  // a working connection resets the back-off
    result.status = ReadStatus::kData;
    result.size = static_cast<std::size_t>(count);
  }
  else if (count == 0 && zeroReadIsEnd())
    closeAndRetry("closed by the other end");
  else if (count < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)
    closeAndRetry(std::string("read: ") + std::strerror(errno));  // e.g. EIO: device unplugged
  else if (descriptor.revents & (POLLHUP | POLLERR | POLLNVAL))
    closeAndRetry("hang-up");
  return result;
}

}  // namespace acc
