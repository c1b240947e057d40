// libFuzzer target for encoder profiles (profiles/*.json, or a profile file given with check
// --encoder or a scenario's encoder.profile): any bytes either load or raise a ProfileError that
// names the file. A profile that loads is applied to the encoder's parameters, described, written
// back as text and loaded again to the same profile. Anything else (another exception, a crash,
// UB, a leak, a broken round trip) is a bug.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "endatsim/slave/profile.hpp"

namespace slave = endatsim::slave;

namespace {

[[noreturn]] void bug(const std::string& what) {
  std::fprintf(stderr, "fuzz_profile: %s\n", what.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  slave::EncoderProfile profile;
  try {
    profile = slave::load_profile_text(text, "fuzz.json");
  } catch (const slave::ProfileError& e) {
    if (std::string(e.what()).rfind("fuzz.json: ", 0) != 0) bug("error does not name the file: " + std::string(e.what()));
    return 0;
  }
  slave::EncoderParams params;
  profile.apply(params);
  (void)slave::describe_profile(profile);
  (void)slave::check_profile(profile);
  const std::string written = slave::profile_text(profile);
  try {
    if (!(slave::load_profile_text(written, "again.json") == profile)) bug("the profile written back loads differently");
  } catch (const slave::ProfileError& e) {
    bug("the profile written back does not load: " + std::string(e.what()));
  }
  return 0;
}
