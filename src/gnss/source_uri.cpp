#include <arpa/inet.h>

#include <cstdlib>

#include "acc_identification/gnss/byte_source.h"

namespace acc
{
namespace
{
bool parsePort(const std::string& text, int& port)
{
  char* end = nullptr;
  const long value = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || value < 1 || value > 65535)
    return false;
  port = static_cast<int>(value);
  return true;
}

void parseQuery(const std::string& text, std::map<std::string, std::string>& query)
{
  std::size_t start = 0;
  while (start < text.size())
  {
    std::size_t end = text.find('&', start);
    if (end == std::string::npos)
      end = text.size();
    const std::string item = text.substr(start, end - start);
    const std::size_t equals = item.find('=');
    query[item.substr(0, equals)] = equals == std::string::npos ? "" : item.substr(equals + 1);
    start = end + 1;
  }
}
/// The query keys a scheme reads ("" when none): a key it does not read (a typo such as Rate=0,
/// baud on a UDP source) would otherwise be ignored and its default taken without a word.
std::string queryKeysOf(const std::string& scheme)
{
  if (scheme == "serial")
    return "baud";
  if (scheme == "file")
    return "rate";
  return "";
}

bool checkQueryKeys(const std::string& text, const SourceUri& uri, std::string& error)
{
  const std::string known = queryKeysOf(uri.scheme);
  for (const auto& [key, value] : uri.query)
  {
    if (key != known)
    {
      error = "source '" + text + "': " + uri.scheme + " takes " +
              (known.empty() ? std::string("no query parameter") : "only ?" + known + "=...") + ", not '" + key +
              "' (names are case-sensitive)";
      return false;
    }
  }
  return true;
}
}  // namespace

bool parseSourceUri(const std::string& text, SourceUri& uri, std::string& error)
{
  uri = SourceUri();
  const std::size_t separator = text.find("://");
  if (separator == std::string::npos)
  {
    error = "source '" + text + "' is not a URI (serial:///dev/ttyACM0?baud=115200, udp://:10110, "
            "tcp://host:port, file:///path?rate=1)";
    return false;
  }
  uri.scheme = text.substr(0, separator);
  std::string rest = text.substr(separator + 3);
  const std::size_t question = rest.find('?');
  if (question != std::string::npos)
  {
    parseQuery(rest.substr(question + 1), uri.query);
    rest = rest.substr(0, question);
  }
  if (uri.scheme != "serial" && uri.scheme != "file" && uri.scheme != "udp" && uri.scheme != "tcp")
  {
    error = "source '" + text + "' has unknown scheme '" + uri.scheme + "' (serial, udp, tcp or file)";
    return false;
  }
  if (!checkQueryKeys(text, uri, error))
    return false;
  if (uri.scheme == "serial" || uri.scheme == "file")
  {
    uri.path = rest;
    if (uri.path.empty() || uri.path[0] != '/')
    {
      error = "source '" + text + "' needs an absolute path (three slashes: " + uri.scheme + ":///...)";
      return false;
    }
    return true;
  }
  // udp or tcp: host:port
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string::npos || !parsePort(rest.substr(colon + 1), uri.port))
  {
    error = "source '" + text + "' needs a port from 1 to 65535 (" + uri.scheme + "://host:port)";
    return false;
  }
  uri.host = rest.substr(0, colon);
  if (uri.scheme == "tcp" && uri.host.empty())
  {
    error = "source '" + text + "' needs a host (tcp://host:port)";
    return false;
  }
  in_addr address{};
  if (uri.scheme == "udp" && !uri.host.empty() && ::inet_pton(AF_INET, uri.host.c_str(), &address) != 1)
  {
    // Found here rather than when the socket opens, where it would only be retried for ever.
    error = "source '" + text + "': the address to listen on must be an IPv4 address (udp://127.0.0.1:" +
            std::to_string(uri.port) + "), or nothing for every interface (udp://:" + std::to_string(uri.port) +
            "), not '" + uri.host + "'";
    return false;
  }
  return true;
}

}  // namespace acc
