#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>

#include "endatsim/scenarios/json_tokens.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/report.hpp"
#include "endatsim/scenarios/transaction_log.hpp"
#include "scenario_support.hpp"

using endatsim::scenarios::JsonTokens;
using nlohmann::json;

namespace {

// `text` with every line after the first shifted right by `indent`: what sorted_indented()
// writes, found here from the dump alone.
std::string shifted_right(const std::string& text, std::size_t indent) {
  std::string out;
  for (char c : text) {
    out += c;
    if (c == '\n') out.append(indent, ' ');
  }
  return out;
}

// Every kind of value, nested, with keys out of order, strings that need escaping (quotes, a
// backslash, control characters, UTF-8, invalid UTF-8, DEL) and empty containers.
JsonTokens every_kind() {
  JsonTokens t;
  t.begin_object();
  t.member("zeta", -42);
  t.member("alpha", std::numeric_limits<std::uint64_t>::max());
  t.member("min", std::numeric_limits<std::int64_t>::min());
  t.member("text", "plain");
  t.member("quoted", "a \"b\" \\ c\n\t\x01 end");
  t.member("utf8", "25 \xc2\xb0" "C");
  t.member("broken", std::string("x\xff\xfey"));
  t.member("del", std::string("a\x7f" "b"));
  t.member("ratio", 0.1);
  t.member("whole", 16000000.0);
  t.member("flag", true);
  t.member("off", false);
  t.member("none", nullptr);
  t.key("empty_object").begin_object().end_object();
  t.key("empty_array").begin_array().end_array();
  t.key("list").begin_array();
  t.value(1U).value("two").begin_object().member("b", 2).member("a", 1).end_object().begin_array().end_array();
  t.end_array();
  t.key("nested").begin_object().member("y", "1").key("x").begin_object().member("k", std::uint8_t{7}).end_object().end_object();
  t.member("q\"key", 3);
  t.end_object();
  return t;
}

}  // namespace

TEST(JsonTokens, CompactTextIsNlohmannsDumpOfTheOrderedTree) {
  const JsonTokens t = every_kind();
  EXPECT_EQ(t.compact(), t.ordered().dump(-1, ' ', false, json::error_handler_t::replace));
  EXPECT_EQ(t.ordered().begin().key(), "zeta");  // built order kept
}

TEST(JsonTokens, SortedIndentedTextIsNlohmannsIndentedDumpOfTheSortedTree) {
  const JsonTokens t = every_kind();
  std::string text;
  t.sorted_indented(text, 0);
  EXPECT_EQ(text, t.sorted().dump(2, ' ', false, json::error_handler_t::replace));
  EXPECT_EQ(t.sorted().begin().key(), "alpha");
  // Shifted right: every line after the first.
  std::string shifted;
  t.sorted_indented(shifted, 8);
  EXPECT_EQ(shifted, shifted_right(text, 8));
}

TEST(JsonTokens, ReadsMembersBack) {
  const JsonTokens t = every_kind();
  const std::size_t nested = t.find(0, "nested");
  ASSERT_NE(nested, JsonTokens::npos);
  EXPECT_EQ(t.at(t.find(nested, "y")).text, "1");
  EXPECT_EQ(t.find(nested, "z"), JsonTokens::npos);
  EXPECT_EQ(t.members(nested).size(), 2U);
  std::string number;
  t.scalar(number, t.find(0, "zeta"));
  EXPECT_EQ(number, "-42");
}

// The outputs written from tokens are the trees' dumps for every frame of every bundled, field
// and safety scenario.
TEST(JsonTokens, FramesAndTransactionsOfEveryScenarioAreTheirTreesDumps) {
  std::size_t frames = 0;
  for (const auto& file : endatsim::test_support::scenario_files()) {
    const auto r = endatsim::scenarios::run_scenario(endatsim::scenarios::load_scenario_file(file.string()), {});
    for (const auto& f : r.frames) {
      const JsonTokens record = endatsim::scenarios::transaction_tokens(f, r.violations, &r.name);
      auto tree = endatsim::scenarios::transaction_of(f, r.violations);
      tree["scenario"] = r.name;
      ASSERT_EQ(record.compact(), tree.dump(-1, ' ', false, json::error_handler_t::replace)) << file;
      std::string text;
      endatsim::scenarios::frame_tokens(r, f).sorted_indented(text, 8);
      const json tree_of_frame = endatsim::scenarios::frame_json(r, f);
      ASSERT_EQ(text, shifted_right(tree_of_frame.dump(2, ' ', false, json::error_handler_t::replace), 8)) << file;
      ++frames;
    }
  }
  EXPECT_GT(frames, 1000U);
}

// The master reads the information code off the wire: a misread status can bring one code twice
// in a frame. Its name is in the record once, with the later value in the earlier one's place (as
// in a JSON object), and a flag the earlier one raised stays.
TEST(JsonTokens, AnInformationReadTwiceInAFrameIsOneFieldWithTheLaterValue) {
  namespace pr = endatsim::protocol;
  endatsim::master::FrameResult f;
  f.command = pr::ModeCommand::EncoderSendPositionValuesWithAdditionalData;
  f.outcome = endatsim::master::FrameOutcome::CrcError;
  const auto commutation = static_cast<std::uint8_t>(pr::Information::Commutation);
  endatsim::master::AdditionalDatum first, later;
  first.status = later.status = commutation;
  first.data = 0x1111;
  first.crc_ok = false;
  later.data = 0x2222;
  later.crc_ok = true;
  f.additional_data = {first, later};
  const JsonTokens record = endatsim::scenarios::transaction_tokens(f, {});
  const std::string text = record.compact();
  const std::string key = "\"" + std::string(pr::info(pr::Information::Commutation).key) + "\":";
  ASSERT_NE(text.find(key + "\"0x2222\""), std::string::npos) << text;
  EXPECT_EQ(text.find(key, text.find(key) + 1), std::string::npos) << text;
  EXPECT_NE(text.find(".crc_ok\":false"), std::string::npos) << text;
  EXPECT_EQ(text, endatsim::scenarios::transaction_of(f, {}).dump(-1, ' ', false, json::error_handler_t::replace));
  const std::string line = endatsim::scenarios::transaction_line(record);
  EXPECT_EQ(line.find("=0x1111"), std::string::npos) << line;
}
