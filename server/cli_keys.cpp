// `tourmap keys`: create, list and revoke the API keys the write endpoints ask for. The key is
// printed once at creation; the store keeps only a hash of its secret (store/api_keys.hpp).

#include "cli_options.hpp"

#include "store/api_keys.hpp"
#include "store/migrate.hpp"

#include <cstdio>
#include <iostream>

namespace tourmap::server {

namespace po = boost::program_options;

namespace {

constexpr const char* kKeysUsage =
    "usage: tourmap keys create --name NAME [--db FILE]   create a key (printed once)\n"
    "       tourmap keys list [--db FILE]                 list keys (ids, names, last use)\n"
    "       tourmap keys revoke ID [--db FILE]            revoke a key by its id\n"
    "\n"
    "Send the key with write requests as `Authorization: Bearer KEY` or `X-API-Key: KEY`.\n";

}  // namespace

int cmd_keys(const std::vector<std::string>& args) {
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::fputs(kKeysUsage, stdout);
    return args.empty() ? 2 : 0;
  }
  const std::string what = args[0];
  if (what != "create" && what != "list" && what != "revoke") {
    std::fprintf(stderr, "tourmap keys: unknown action '%s'\n\n%s", what.c_str(), kKeysUsage);
    return 2;
  }
  Config c = default_config();
  std::string name, id;
  po::options_description desc("tourmap keys " + what + " options");
  desc.add_options()("help,h", "show this help");
  if (what == "create") desc.add_options()("name", po::value(&name)->required(), "who or what the key is for");
  if (what == "revoke") desc.add_options()("id", po::value(&id)->required(), "the key's id (see `keys list`)");
  desc.add(db_options(c));
  po::positional_options_description pos;
  if (what == "revoke") pos.add("id", 1);
  po::variables_map vm;
  try {
    vm = parse_options(desc, pos, std::vector<std::string>(args.begin() + 1, args.end()));
  } catch (const po::error& e) {
    std::fprintf(stderr, "tourmap keys %s: %s\n", what.c_str(), e.what());
    return 2;
  }
  if (vm.count("help")) {
    std::cout << desc << "\n";
    return 0;
  }

  store::Db db(c.db_path);
  store::migrate(db);
  if (what == "create") {
    auto key = store::create_api_key(db, name);
    std::fprintf(stderr, "created key %s for '%s'; it is shown only now:\n", key.id.c_str(), name.c_str());
    std::printf("%s\n", key.key.c_str());
    return 0;
  }
  if (what == "revoke") {
    if (!store::revoke_api_key(db, id)) {
      std::fprintf(stderr, "tourmap keys revoke: no active key with id '%s'\n", id.c_str());
      return 1;
    }
    std::printf("revoked key %s\n", id.c_str());
    return 0;
  }
  auto keys = store::list_api_keys(db);
  if (keys.empty()) std::printf("no API keys (create one with `tourmap keys create --name NAME`)\n");
  for (const auto& k : keys)
    std::printf("%s  %-24s created %s  last used %s  %s\n", k.id.c_str(), k.name.c_str(), k.created_at.c_str(),
                k.last_used_at.empty() ? "never" : k.last_used_at.c_str(),
                k.revoked_at.empty() ? "active" : ("revoked " + k.revoked_at).c_str());
  return 0;
}

}  // namespace tourmap::server
