// A regression (`run FILE...`) or a sweep's grid split across processes or machines:
// `--shard K/N` runs the K-th of N contiguous slices of the scenario files or grid points and
// marks each output it writes as a partial (ShardMark); `endatsim merge` (merge.hpp) joins the N
// partials into the outputs the whole run would have written, byte for byte.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "endatsim/scenarios/junit.hpp"
#include "endatsim/scenarios/limits.hpp"

namespace endatsim::scenarios {

struct Shard {
  std::size_t index = 1;  // K, from 1
  std::size_t count = 1;  // N
};
inline constexpr std::size_t kMaxShards = 100'000;

// "K/N" with 1 <= K <= N <= kMaxShards. Throws std::invalid_argument saying what it expects.
Shard parse_shard(const std::string& text);

// The items [begin, end) of `total` that shard K of N runs: the K-th of N contiguous slices
// whose sizes differ by at most one, so that joining the slices in shard order gives the whole
// list in its order.
struct Slice {
  std::size_t begin = 0, end = 0;
};
Slice slice_of(const Shard& shard, std::size_t total);

// What a partial says about itself; every partial of one sharded run carries one, the same in
// all but the shard and what it ran.
struct ShardMark {
  std::string endatsim;   // the version that wrote it: merge joins only its own version's
  std::string command;    // "run" or "sweep"
  Shard shard;
  std::size_t first = 0;  // the slice's first scenario file or grid point
  std::size_t items = 0;  // how many it holds
  std::size_t total = 0;  // of the whole run
  // What the whole run runs: the scenario files in order (run), or the file and the grid (sweep).
  nlohmann::json inputs;
  // The options that shape the results: every shard must have run with the same ones.
  nlohmann::json options;
  // run: what the shard's scenarios gave.
  bool passed = true;
  std::string incomplete;  // the first reason a run of the shard ended early, "" if none did
  std::vector<NotRun> not_run;
};

nlohmann::json to_json(const ShardMark& mark);
// Throws std::invalid_argument naming the key and what it expected.
ShardMark shard_mark_of(const nlohmann::json& j);

// The mark as the last line of a partial (each with its "\n"): a text log's comment line, a
// JSON-lines log's record {"shard": MARK}, a JUnit file's comment after its root element (with
// "-" written \u002d, so that no "--" can end the comment early).
inline constexpr const char* kTextLogMarkPrefix = "# shard ";
inline constexpr const char* kJunitMarkPrefix = "<!-- endatsim shard ";
inline constexpr const char* kJunitMarkSuffix = " -->";
std::string text_log_mark(const ShardMark& mark);
std::string json_lines_mark(const ShardMark& mark);
std::string junit_mark(const ShardMark& mark);

// The options of `run` that shape its results, as a ShardMark records them.
nlohmann::json run_shard_options(const std::optional<std::uint64_t>& seed, std::size_t examples, const Limits& limits,
                                 JunitCases cases);
nlohmann::json limits_json(const Limits& limits);

}  // namespace endatsim::scenarios
