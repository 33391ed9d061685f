#pragma once

#include <chrono>
#include <string>

#include "acc_identification/gnss/byte_source.h"

namespace acc
{
/// Common behaviour of the live sources (serial, UDP, TCP): a file descriptor that is opened on
/// demand, read with poll(), and closed and reopened with exponential back-off (0.5 s doubling
/// to 8 s) when opening fails or the peer or device goes away, so the node never stops.
class ReconnectingSource : public ByteSource
{
public:
  explicit ReconnectingSource(std::string description);
  ~ReconnectingSource() override;

  ReadResult read(char* buffer, std::size_t capacity, double timeout_s) override;
  std::string description() const override { return description_; }
  std::string state() const override { return state_; }
  bool isOpen() const override { return fd_ >= 0; }
  std::uint64_t reopenCount() const override { return reopen_count_; }

protected:
  /// Opens the descriptor (non-blocking); returns -1 and sets error on failure.
  virtual int open(std::string& error) = 0;
  /// A read of 0 bytes: end of stream for TCP; for datagram sockets an empty datagram.
  virtual bool zeroReadIsEnd() const { return true; }

private:
  using Clock = std::chrono::steady_clock;
  void closeAndRetry(const std::string& why);

  std::string description_;
  std::string state_ = "not opened yet";
  int fd_ = -1;
  bool ever_opened_ = false;
  std::uint64_t reopen_count_ = 0;
  double backoff_s_ = 0.0;
  Clock::time_point next_attempt_;
};

}  // namespace acc
