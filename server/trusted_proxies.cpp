#include "trusted_proxies.hpp"

#include <boost/asio/ip/address.hpp>

#include <optional>
#include <stdexcept>

namespace tourmap::server {

namespace ip = boost::asio::ip;

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// IPv4-mapped IPv6 addresses (a dual-stack listener's view of IPv4 peers) compare as IPv4.
std::optional<ip::address> parse_address(std::string_view text) {
  boost::system::error_code ec;
  auto a = ip::make_address(std::string(text), ec);
  if (ec) return std::nullopt;
  if (a.is_v6() && a.to_v6().is_v4_mapped()) return ip::make_address_v4(ip::v4_mapped, a.to_v6());
  return a;
}

template <class F>
void for_each_entry(std::string_view list, F&& f) {
  while (!list.empty()) {
    auto comma = list.find(',');
    f(trim(list.substr(0, comma)));
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
}

}  // namespace

TrustedProxies::TrustedProxies(std::string_view spec) {
  for_each_entry(spec, [this](std::string_view entry) {
    if (entry.empty()) return;
    boost::system::error_code ec;
    std::string text(entry);
    if (text.find('/') == std::string::npos) text += text.find(':') == std::string::npos ? "/32" : "/128";
    if (text.find(':') == std::string::npos) {
      auto net = ip::make_network_v4(text, ec);
      if (!ec) return v4_.push_back(net.canonical());
    } else {
      auto net = ip::make_network_v6(text, ec);
      if (!ec) return v6_.push_back(net.canonical());
    }
    throw std::invalid_argument("'" + std::string(entry) + "' is neither an IP address nor a CIDR network");
  });
}

bool TrustedProxies::trusts(std::string_view address) const {
  auto a = parse_address(address);
  if (!a) return false;
  if (a->is_v4()) {
    const auto host = ip::network_v4(a->to_v4(), 32);
    for (const auto& net : v4_)
      if (host == net || host.is_subnet_of(net)) return true;
    return false;
  }
  const auto host = ip::network_v6(a->to_v6(), 128);
  for (const auto& net : v6_)
    if (host == net || host.is_subnet_of(net)) return true;
  return false;
}

std::string TrustedProxies::client_of(const std::string& peer, std::string_view forwarded_for) const {
  if (!enabled() || forwarded_for.empty() || !trusts(peer)) return peer;
  std::vector<std::string_view> hops;
  bool well_formed = true;
  for_each_entry(forwarded_for, [&](std::string_view entry) {
    if (!parse_address(entry)) well_formed = false;
    hops.push_back(entry);
  });
  if (!well_formed || hops.empty()) return peer;  // garbage from a proxy: keep the proxy's address
  for (auto it = hops.rbegin(); it != hops.rend(); ++it)
    if (!trusts(*it)) return std::string(*it);
  return std::string(hops.front());
}

}  // namespace tourmap::server
