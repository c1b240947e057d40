// `endatsim merge`: joins the partials that `run --shard K/N` and `sweep --shard K/N` wrote
// (shard.hpp) into the outputs the whole run would have written, byte for byte. A run's
// partials are its usual outputs (--json, --junit, --log, --log-json), each carrying its
// ShardMark: the results file as its last key "shard", the JUnit file as a last comment line,
// the logs as a last line. A sweep's partial is its --json file with the key "shard".
// Scenario objects, test cases and log records are copied as the shards wrote them, so that a
// million-frame results file is merged with the memory of one line.
#pragma once

#include <cstdint>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "endatsim/scenarios/shard.hpp"
#include "endatsim/scenarios/sweep.hpp"

namespace endatsim::scenarios {

// A partial that cannot be read, or partials that are not the shards of one run: bad input.
class MergeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class PartialKind : std::uint8_t { Results, Junit, Log, LogJson, Sweep };
// The option whose output a partial of this kind is: "--json", "--junit", "--log", "--log-json".
const char* option_of(PartialKind kind);

struct Partial {
  std::string path;
  PartialKind kind = PartialKind::Results;
  ShardMark mark;
};

// Reads what a partial is and its mark, checking its whole structure. Throws MergeError naming
// the path, where in it and what was expected.
Partial read_partial(const std::string& path);

// Checks that every partial comes from one sharded run of this version (`version`): the same
// command, number of shards, inputs and options. Returns them by kind, each in shard order.
// Throws MergeError naming the two partials that differ and how.
std::map<PartialKind, std::vector<Partial>> group_partials(const std::vector<Partial>& partials,
                                                           const std::string& version);
// Throws MergeError unless `shards` holds each shard 1..N exactly once (naming the missing or
// doubled one and `option`, the output they would make).
void require_every_shard(const std::vector<Partial>& shards, const std::string& option);

// What the whole run gave, from one complete set of partials.
struct RunVerdict {
  bool passed = true;
  std::string incomplete;
  std::vector<NotRun> not_run;
  std::size_t scenarios = 0;  // scenario files of the run
};
RunVerdict run_verdict(const std::vector<Partial>& shards);

// Each writes the whole run's output from a complete set of its kind, in shard order.
void merge_results_json(const std::vector<Partial>& shards, std::ostream& out);
void merge_junit(const std::vector<Partial>& shards, std::ostream& out);
void merge_log(const std::vector<Partial>& shards, std::ostream& out);
void merge_log_json(const std::vector<Partial>& shards, std::ostream& out);
// The sweep of every grid point, as `sweep` would have it before writing its outputs.
Sweep merge_sweep(const std::vector<Partial>& shards);

}  // namespace endatsim::scenarios
