// Where Debian's sigrok-cli is, for tests that make sigrok session files and CSV with it.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <sstream>
#include <string>

namespace endatsim::test_support {

// The path of sigrok-cli, or "" when it is not installed.
inline std::string sigrok_cli() {
  for (const char* p : {"/usr/bin/sigrok-cli", "/usr/local/bin/sigrok-cli"})
    if (::access(p, X_OK) == 0) return p;
  if (const char* path = std::getenv("PATH")) {
    std::stringstream dirs(path);
    for (std::string dir; std::getline(dirs, dir, ':');)
      if (!dir.empty() && ::access((dir + "/sigrok-cli").c_str(), X_OK) == 0) return dir + "/sigrok-cli";
  }
  return "";
}

inline constexpr const char* kNoSigrokCli =
    "sigrok-cli is not installed: these tests make their sigrok session files and CSV with Debian's sigrok-cli "
    "(apt-get install sigrok-cli; tools/quickstart installs it)";

}  // namespace endatsim::test_support
