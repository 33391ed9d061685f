// The live byte sources: serial (termios), UDP listener, TCP client; and the URI factory.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "acc_identification/gnss/file_source.h"
#include "reconnecting_source.h"

namespace acc
{
namespace
{
std::string systemError(const std::string& what) { return what + ": " + std::strerror(errno); }

speed_t baudConstant(long baud)
{
  switch (baud)
  {
    case 4800: return B4800;
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 921600: return B921600;
    default: return B0;
  }
}

class SerialSource : public ReconnectingSource
{
public:
  SerialSource(const std::string& uri, std::string path, speed_t baud)
    : ReconnectingSource(uri), path_(std::move(path)), baud_(baud) {}

protected:
  int open(std::string& error) override
  {
    const int fd = ::open(path_.c_str(), O_RDONLY | O_NOCTTY | O_NONBLOCK);
    if (fd < 0)
    {
      error = systemError("open " + path_);
      return -1;
    }
    termios tty{};
    if (::tcgetattr(fd, &tty) != 0)
    {
      error = systemError("tcgetattr " + path_);
      ::close(fd);
      return -1;
    }
    ::cfmakeraw(&tty);  // 8 data bits, no parity, no echo, no line editing
    tty.c_cflag &= ~(CSTOPB | CRTSCTS);  // 1 stop bit, no hardware flow control
    tty.c_cflag |= CLOCAL | CREAD;
    ::cfsetispeed(&tty, baud_);
    ::cfsetospeed(&tty, baud_);
    if (::tcsetattr(fd, TCSANOW, &tty) != 0)
    {
      error = systemError("tcsetattr " + path_);
      ::close(fd);
      return -1;
    }
    ::tcflush(fd, TCIFLUSH);
    return fd;
  }

private:
  std::string path_;
  speed_t baud_;
};

class UdpSource : public ReconnectingSource
{
public:
  UdpSource(const std::string& uri, std::string host, int port)
    : ReconnectingSource(uri), host_(std::move(host)), port_(port) {}

protected:
  int open(std::string& error) override
  {
    const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
    if (fd < 0)
    {
      error = systemError("socket");
      return -1;
    }
    // No SO_REUSEADDR: with it a second driver binds the same port and takes every datagram from
    // the first, which then reads nothing without an error. Without it the second bind fails
    // (EADDRINUSE), and that driver says so.
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port_));
    address.sin_addr.s_addr = htonl(INADDR_ANY);
    if (!host_.empty() && ::inet_pton(AF_INET, host_.c_str(), &address.sin_addr) != 1)
    {
      error = "udp: listen address '" + host_ + "' is not an IPv4 address";
      ::close(fd);
      return -1;
    }
    if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0)
    {
      error = systemError("bind udp port " + std::to_string(port_));
      ::close(fd);
      return -1;
    }
    return fd;
  }
  bool zeroReadIsEnd() const override { return false; }

private:
  std::string host_;
  int port_;
};

class TcpSource : public ReconnectingSource
{
public:
  TcpSource(const std::string& uri, std::string host, int port)
    : ReconnectingSource(uri), host_(std::move(host)), port_(port) {}

protected:
  int open(std::string& error) override
  {
    addrinfo hints{};
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    const int status = ::getaddrinfo(host_.c_str(), std::to_string(port_).c_str(), &hints, &found);
    if (status != 0)
    {
      error = "resolve " + host_ + ": " + ::gai_strerror(status);
      return -1;
    }
    int fd = -1;
    error = "connect " + host_ + ":" + std::to_string(port_) + ": no address";
    for (addrinfo* a = found; a != nullptr && fd < 0; a = a->ai_next)
      fd = connectWithTimeout(a, error);
    ::freeaddrinfo(found);
    return fd;
  }

private:
  /// Non-blocking connect bounded to 2 s, so an unreachable host does not freeze the node.
  int connectWithTimeout(const addrinfo* a, std::string& error)
  {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK, a->ai_protocol);
    if (fd < 0)
    {
      error = systemError("socket");
      return -1;
    }
    if (::connect(fd, a->ai_addr, a->ai_addrlen) != 0 && errno != EINPROGRESS)
    {
      error = systemError("connect " + host_ + ":" + std::to_string(port_));
      ::close(fd);
      return -1;
    }
    pollfd descriptor{fd, POLLOUT, 0};
    int socket_error = 0;
    socklen_t length = sizeof socket_error;
    if (::poll(&descriptor, 1, 2000) != 1 || ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &socket_error, &length) != 0 ||
        socket_error != 0)
    {
      errno = socket_error != 0 ? socket_error : ETIMEDOUT;
      error = systemError("connect " + host_ + ":" + std::to_string(port_));
      ::close(fd);
      return -1;
    }
    return fd;
  }

  std::string host_;
  int port_;
};

bool numberParameter(const SourceUri& uri, const std::string& name, double fallback, double& value,
                     std::string& error)
{
  const auto it = uri.query.find(name);
  if (it == uri.query.end())
  {
    value = fallback;
    return true;
  }
  char* end = nullptr;
  value = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0' || !(value >= 0.0))
  {
    error = "source parameter " + name + "='" + it->second + "' is not a non-negative number";
    return false;
  }
  return true;
}
}  // namespace

std::unique_ptr<ByteSource> makeByteSource(const std::string& text, std::string& error)
{
  SourceUri uri;
  if (!parseSourceUri(text, uri, error))
    return nullptr;
  if (uri.scheme == "file")
  {
    double rate = 1.0;
    if (!numberParameter(uri, "rate", 1.0, rate, error))
      return nullptr;
    auto source = std::make_unique<FileSource>(uri.path, rate);
    if (!source->isOpen())
    {
      error = source->state();
      return nullptr;
    }
    return source;
  }
  if (uri.scheme == "serial")
  {
    double baud = 115200.0;
    if (!numberParameter(uri, "baud", 115200.0, baud, error))
      return nullptr;
    const speed_t speed = baudConstant(static_cast<long>(baud));
    if (speed == B0)
    {
      error = "serial baud rate " + std::to_string(static_cast<long>(baud)) +
              " is not one of 4800, 9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600";
      return nullptr;
    }
    return std::make_unique<SerialSource>(text, uri.path, speed);
  }
  if (uri.scheme == "udp")
    return std::make_unique<UdpSource>(text, uri.host, uri.port);
  return std::make_unique<TcpSource>(text, uri.host, uri.port);
}

}  // namespace acc
