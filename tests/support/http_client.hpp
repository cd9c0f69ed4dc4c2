#pragma once
// A small blocking HTTP/1.1 and WebSocket client (Boost.Beast) for the integration tests.

#include <chrono>
#include <map>
#include <memory>
#include <string>

namespace tourmap::test {

struct HttpResult {
  int status = 0;
  std::map<std::string, std::string> headers;  // lower-case names
  std::string body;                            // as received (gzip stays compressed)
  std::string header(const std::string& name) const {
    auto it = headers.find(name);
    return it == headers.end() ? "" : it->second;
  }
};

// One request on a fresh connection. `raw_target` is sent as is (no encoding).
HttpResult http_request(unsigned short port, const std::string& method, const std::string& raw_target,
                        const std::map<std::string, std::string>& headers = {}, const std::string& body = "");
inline HttpResult http_get(unsigned short port, const std::string& target,
                           const std::map<std::string, std::string>& headers = {}) {
  return http_request(port, "GET", target, headers);
}
// Sends raw bytes and returns what the server answers before closing (or until the timeout).
std::string raw_exchange(unsigned short port, const std::string& bytes, std::chrono::milliseconds timeout);

class WsClient {
 public:
  WsClient(unsigned short port, const std::string& path);
  ~WsClient();
  void send(const std::string& text);
  // Next text message; throws on timeout or close.
  std::string receive(std::chrono::milliseconds timeout);
  // Next message of either kind; `binary` tells which. Throws on timeout or close; after a
  // close, close_code() holds the server's code.
  struct Message {
    bool binary = false;
    std::string data;
  };
  Message receive_message(std::chrono::milliseconds timeout);
  int close_code() const;
  // Stops reading for a while (a slow client): the socket buffers fill up, the server must cope.
  void pause(std::chrono::milliseconds how_long);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tourmap::test
