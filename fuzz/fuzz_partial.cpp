// libFuzzer target for `endatsim merge`'s reader of partials (scenarios/merge.hpp): any bytes
// as a shard's results file, JUnit file, text log, JSON-lines log or sweep file. Reading one
// either gives a partial or throws MergeError; a partial that reads as the only shard of its
// run (1/1) is merged, which again only throws MergeError. Anything else (another exception, a
// crash, UB, a leak, a hang) is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "endatsim/scenarios/merge.hpp"

namespace scenarios = endatsim::scenarios;

namespace {

[[noreturn]] void bug(const std::string& what) {
  std::fprintf(stderr, "fuzz_partial: %s\n", what.c_str());
  std::abort();
}

// One file per process under TMPDIR (fuzz/run gives each run a private one).
const std::string& input_path() {
  static const std::string path = [] {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir != nullptr ? dir : "/tmp") + "/fuzz_partial_" + std::to_string(getpid());
  }();
  return path;
}

void merge(const scenarios::Partial& p) {
  const auto groups = scenarios::group_partials({p}, p.mark.endatsim);
  const auto& shards = groups.at(p.kind);
  scenarios::require_every_shard(shards, scenarios::option_of(p.kind));
  std::ostringstream out;
  switch (p.kind) {
    case scenarios::PartialKind::Results: scenarios::merge_results_json(shards, out); break;
    case scenarios::PartialKind::Junit: scenarios::merge_junit(shards, out); break;
    case scenarios::PartialKind::Log: scenarios::merge_log(shards, out); break;
    case scenarios::PartialKind::LogJson: scenarios::merge_log_json(shards, out); break;
    case scenarios::PartialKind::Sweep: (void)scenarios::merge_sweep(shards); break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream f(input_path(), std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const auto partial = scenarios::read_partial(input_path());
    if (partial.mark.shard.count == 1) merge(partial);
  } catch (const scenarios::MergeError&) {
  } catch (const std::exception& e) {
    bug(std::string("an exception other than MergeError: ") + e.what());
  }
  return 0;
}
