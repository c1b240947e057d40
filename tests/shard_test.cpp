#include <gtest/gtest.h>

#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <unistd.h>
#include <vector>

#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/merge.hpp"
#include "endatsim/scenarios/shard.hpp"

namespace {

using endatsim::scenarios::kMaxShards;
using endatsim::scenarios::MergeError;
using endatsim::scenarios::parse_shard;
using endatsim::scenarios::read_partial;
using endatsim::scenarios::Shard;
using endatsim::scenarios::ShardMark;
using endatsim::scenarios::slice_of;

ShardMark sample_mark() {
  ShardMark m;
  m.endatsim = "1.2.3";
  m.command = "run";
  m.shard = {2, 3};
  m.total = 7;
  const auto slice = slice_of(m.shard, m.total);
  m.first = slice.begin;
  m.items = slice.end - slice.begin;
  m.inputs = {"a.json", "b--c.json", "d.json", "e.json", "f.json", "g.json", "h.json"};
  m.options = {{"seed", nullptr}};
  m.passed = false;
  m.incomplete = "d: limit records reached";
  m.not_run = {{"e.json", "e", "not run: interrupted by SIGINT"}};
  return m;
}

std::string temp_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / (std::to_string(getpid()) + "_" + name);
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

}  // namespace

TEST(ParseShard, TakesKOfNFromOneToTheLargestCount) {
  EXPECT_EQ(parse_shard("1/1").index, 1U);
  EXPECT_EQ(parse_shard("2/4").index, 2U);
  EXPECT_EQ(parse_shard("2/4").count, 4U);
  const std::string largest = std::to_string(kMaxShards);
  EXPECT_EQ(parse_shard(largest + "/" + largest).count, kMaxShards);
}

TEST(ParseShard, RefusesWhatIsNotKOfNSayingWhatItExpects) {
  const std::string over = std::to_string(kMaxShards + 1);
  for (const std::string& bad : std::vector<std::string>{"0/1", "2/1", "1/0", "1/", "/1", "1", "", "1/2x", " 1/2", "-1/2", "1//2", "a/b",
                                "1/" + over, "18446744073709551616/18446744073709551617"}) {
    try {
      (void)parse_shard(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--shard expects K/N"), std::string::npos) << e.what();
    }
  }
}

TEST(SliceOf, SlicesCoverEveryListInOrderWithSizesDifferingByAtMostOne) {
  for (std::size_t n = 1; n <= 12; ++n)
    for (std::size_t total = 0; total <= 40; ++total) {
      std::size_t next = 0, smallest = total, largest = 0;
      for (std::size_t k = 1; k <= n; ++k) {
        const auto s = slice_of({k, n}, total);
        ASSERT_EQ(s.begin, next) << k << "/" << n << " of " << total;
        ASSERT_LE(s.begin, s.end);
        smallest = std::min(smallest, s.end - s.begin);
        largest = std::max(largest, s.end - s.begin);
        next = s.end;
      }
      EXPECT_EQ(next, total) << n << " shards of " << total;
      EXPECT_LE(largest - smallest, 1U) << n << " shards of " << total;
    }
}

TEST(SliceOf, DoesNotWrapForTheLongestList) {
  const std::size_t total = std::numeric_limits<std::size_t>::max();
  EXPECT_EQ(slice_of({kMaxShards, kMaxShards}, total).end, total);
  EXPECT_EQ(slice_of({1, kMaxShards}, total).begin, 0U);
  EXPECT_EQ(slice_of({2, 2}, total).begin, total / 2);
}

TEST(ShardMark, ReadsBackWhatItWrites) {
  const ShardMark m = sample_mark();
  const ShardMark back = endatsim::scenarios::shard_mark_of(to_json(m));
  EXPECT_EQ(to_json(back), to_json(m));
  EXPECT_EQ(back.not_run.size(), 1U);
  EXPECT_EQ(back.not_run[0].reason, "not run: interrupted by SIGINT");
}

TEST(ShardMark, RefusesASliceThatIsNotItsShards) {
  auto j = to_json(sample_mark());
  j["first"] = 0;
  EXPECT_THROW((void)endatsim::scenarios::shard_mark_of(j), std::invalid_argument);
  j = to_json(sample_mark());
  j["index"] = 4;
  EXPECT_THROW((void)endatsim::scenarios::shard_mark_of(j), std::invalid_argument);
  j = to_json(sample_mark());
  j["command"] = "check";
  EXPECT_THROW((void)endatsim::scenarios::shard_mark_of(j), std::invalid_argument);
  j = to_json(sample_mark());
  j.erase("options");
  EXPECT_THROW((void)endatsim::scenarios::shard_mark_of(j), std::invalid_argument);
}

TEST(ShardMark, InAJunitCommentHasNoDoubleHyphenAndReadsBack) {
  const ShardMark m = sample_mark();
  const std::string mark = endatsim::scenarios::junit_mark(m);
  const std::string inside = mark.substr(std::string(endatsim::scenarios::kJunitMarkPrefix).size());
  EXPECT_EQ(inside.find("--"), inside.size() - std::string("-->\n").size()) << mark;  // only where the comment ends
  const std::string doc = endatsim::scenarios::junit_head("endatsim", 2, 0, 1) +
                          "    <testcase classname=\"endatsim.x\" name=\"d\" file=\"d.json\"/>\n"
                          "    <testcase classname=\"endatsim.x\" name=\"e\" file=\"e.json\">\n"
                          "      <error type=\"not run\" message=\"not run: interrupted by SIGINT\"/>\n"
                          "    </testcase>\n" +
                          endatsim::scenarios::junit_tail() + mark;
  const auto path = temp_file("shard_junit.xml", doc);
  const auto partial = read_partial(path);
  std::filesystem::remove(path);
  EXPECT_EQ(partial.kind, endatsim::scenarios::PartialKind::Junit);
  EXPECT_EQ(partial.mark.inputs[1], "b--c.json");
}

TEST(ReadPartial, RefusesAJunitFileWhoseCountsDisagreeWithItsCases) {
  const std::string doc = endatsim::scenarios::junit_head("endatsim", 3, 0, 0) +
                          "    <testcase classname=\"endatsim.x\" name=\"d\" file=\"d.json\"/>\n" +
                          endatsim::scenarios::junit_tail() + endatsim::scenarios::junit_mark(sample_mark());
  const auto path = temp_file("shard_junit_counts.xml", doc);
  try {
    (void)read_partial(path);
    ADD_FAILURE() << "accepted";
  } catch (const MergeError& e) {
    EXPECT_NE(std::string(e.what()).find("holds 1 test cases where its tests=\"3\" says"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

namespace {

// Each text, as a partial, is refused with a MergeError that begins with the file's path.
void expect_refused_naming_the_path(const std::vector<std::string>& texts) {
  for (const std::string& text : texts) {
    const auto path = temp_file("shard_bad", text);
    try {
      (void)read_partial(path);
      ADD_FAILURE() << "accepted '" << text << "'";
    } catch (const MergeError& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0U) << e.what();
    }
    std::filesystem::remove(path);
  }
}

}  // namespace

TEST(ReadPartial, RefusesWhatNoShardWroteNamingThePath) {
  expect_refused_naming_the_path({"", "hello\n", "# a log without its mark\n", "{\"time_ps\": 0}\n", "<?xml version=\"1.0\"?>\n"});
  EXPECT_THROW((void)read_partial("/nonexistent/partial.json"), MergeError);
}

// Found by fuzz_partial (fuzz/corpus/partial/number_overflow.jsonl): a number too large for a
// double in a mark is bad input like any other, not an escaping exception.
TEST(ReadPartial, RefusesANumberThatOverflowsNamingThePath) {
  expect_refused_naming_the_path({"{\"tim\"t>888\n8e88888888s\":2}}\n", "{\"time_ps\": 0}\n{\"shard\": 1e999}\n",
                                  "# endatsim\n# shard {\"k\": 1e999}\n"});
}

TEST(MergeLog, StopsWhenInterruptedAndWritesNoMore) {
  ShardMark m = sample_mark();
  m.shard = {1, 1};
  m.first = 0;
  m.total = m.items = 1;  // one scenario, whole: merge checks the log's scenarios and frames against the mark
  m.inputs = {"a.json"};
  m.incomplete.clear();
  m.not_run.clear();
  std::string text = "# a (a.json, seed 1)\n";
  for (int i = 0; i < 10'000; ++i) text += "        " + std::to_string(i) + " ps  #" + std::to_string(i) + "\n";
  text += "# 10000 frames\n";
  const auto path = temp_file("shard_interrupted.log", text + endatsim::scenarios::text_log_mark(m));
  const auto partial = read_partial(path);
  std::ostringstream out;
  endatsim::scenarios::merge_log({partial}, out);
  EXPECT_EQ(out.str(), text);  // not interrupted: every line but the mark
  endatsim::scenarios::request_interrupt(SIGINT);
  std::ostringstream cut;
  EXPECT_THROW(endatsim::scenarios::merge_log({partial}, cut), endatsim::scenarios::Interrupted);
  endatsim::scenarios::request_interrupt(0);
  EXPECT_LT(cut.str().size(), text.size());
  std::filesystem::remove(path);
}
