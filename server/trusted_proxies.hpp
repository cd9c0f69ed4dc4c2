#pragma once
// Which peer addresses are reverse proxies (`--trusted-proxies`), and the client address of a
// request behind them. Behind nginx every connection comes from nginx; the rate limiter and the
// access log need the address nginx saw, which it appends to X-Forwarded-For. That header is
// believed only from a trusted peer, and read right to left: the right-most entry that is not a
// trusted proxy is the client (entries further left were written by the client and can lie).

#include <boost/asio/ip/network_v4.hpp>
#include <boost/asio/ip/network_v6.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace tourmap::server {

class TrustedProxies {
 public:
  // Comma-separated addresses or CIDR networks, e.g. "127.0.0.1, 10.0.0.0/8, ::1". Empty: none.
  // Throws std::invalid_argument naming the entry that is neither.
  explicit TrustedProxies(std::string_view spec = {});

  bool enabled() const { return !v4_.empty() || !v6_.empty(); }
  bool trusts(std::string_view address) const;
  // The request's client address: `peer` itself unless it is a trusted proxy with a well-formed
  // X-Forwarded-For (then the right-most untrusted entry, or the left-most if all are trusted).
  std::string client_of(const std::string& peer, std::string_view forwarded_for) const;

 private:
  std::vector<boost::asio::ip::network_v4> v4_;
  std::vector<boost::asio::ip::network_v6> v6_;
};

}  // namespace tourmap::server
