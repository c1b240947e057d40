// The VCD lint: each kind of malformed file is named with its line; a file from the
// simulator's writer is clean and its edges are counted as a viewer would.
#include <gtest/gtest.h>

#include <filesystem>

#include "endatsim/scenarios/vcd_reader.hpp"
#include "endatsim/sim/sim.hpp"

using namespace endatsim;
using scenarios::parse_vcd;

namespace {

const std::string kHeader =
    "$timescale 1ps $end\n$scope module top $end\n$var wire 1 ! clk $end\n$var wire 4 \" bus $end\n"
    "$upscope $end\n$enddefinitions $end\n";

std::string issues(const scenarios::VcdFile& f) {
  std::string s;
  for (const auto& i : f.issues) s += std::to_string(i.line) + ": " + i.message + "\n";
  return s;
}

bool has_issue(const scenarios::VcdFile& f, std::size_t line, const std::string& text) {
  for (const auto& i : f.issues)
    if (i.line == line && i.message.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(VcdLint, CleanFileCountsEdgesAndCollapsesOneTimestamp) {
  const auto f = parse_vcd(kHeader + "#0\n$dumpvars\n0!\nb0000 \"\n$end\n1!\n#10\n0!\n#20\n1!\nb1x01 \"\n#30\n0!\n");
  EXPECT_TRUE(f.issues.empty()) << issues(f);
  ASSERT_NE(f.find("top.clk"), nullptr);
  // 0 then 1 at #0 is one value, 1: falls at 10 and 30, rises at 20.
  EXPECT_EQ(f.find("top.clk")->rising, 1U);
  EXPECT_EQ(f.find("top.clk")->falling, 2U);
  EXPECT_EQ(f.find("top.bus")->width, 4U);
  EXPECT_EQ(f.end_time, 30);
  EXPECT_EQ(f.timescale_ps, 1);
}

TEST(VcdLint, TimeGoingBackwardsOrRepeated) {
  const auto f = parse_vcd(kHeader + "#0\n1!\n#20\n0!\n#10\n1!\n#10\n");
  EXPECT_TRUE(has_issue(f, 11, "time does not increase: #10 after #20")) << issues(f);
  EXPECT_TRUE(has_issue(f, 13, "time does not increase: #10 after #20")) << issues(f);
}

TEST(VcdLint, UndeclaredIdentifiersAndBadValues) {
  const auto f = parse_vcd(kHeader + "#0\n1?\nq!\nb012 \"\nb10101 \"\nrabc \"\n#x\n");
  EXPECT_TRUE(has_issue(f, 8, "undeclared identifier '?'")) << issues(f);
  EXPECT_TRUE(has_issue(f, 9, "not a value change")) << issues(f);
  EXPECT_TRUE(has_issue(f, 10, "vector value must be b followed by 0, 1, x or z")) << issues(f);
  EXPECT_TRUE(has_issue(f, 11, "5 bits for top.bus of width 4")) << issues(f);
  EXPECT_TRUE(has_issue(f, 12, "real value must be r and a number")) << issues(f);
  EXPECT_TRUE(has_issue(f, 13, "timestamp must be # and a non-negative integer")) << issues(f);
}

TEST(VcdLint, HeaderStructure) {
  const auto f = parse_vcd("$scope module a $end\n$var wire 0 ! x $end\n$var wire 1 ! y\n");
  EXPECT_TRUE(has_issue(f, 2, "width must be a positive integer")) << issues(f);
  EXPECT_TRUE(has_issue(f, 3, "$var without $end")) << issues(f);
  EXPECT_TRUE(has_issue(f, 4, "no $enddefinitions")) << issues(f);
  EXPECT_TRUE(has_issue(f, 1, "no $timescale")) << issues(f);
  const auto g = parse_vcd("$timescale 3 ns $end\n$scope module a $end\n$enddefinitions $end\n#0\n$upscope $end\n$upscope $end\n");
  EXPECT_TRUE(has_issue(g, 1, "$timescale expects 1, 10 or 100")) << issues(g);
  EXPECT_TRUE(has_issue(g, 3, "inside an open $scope a")) << issues(g);
  EXPECT_TRUE(has_issue(g, 5, "$upscope after $enddefinitions")) << issues(g);
  EXPECT_TRUE(has_issue(g, 6, "$upscope without an open $scope")) << issues(g);
  const auto h = parse_vcd(kHeader + "1!\n#5\n");
  EXPECT_TRUE(has_issue(h, 7, "value change before the first timestamp")) << issues(h);
}

TEST(VcdLint, SigrokProfileRejectsVectorsAndTrailingComments) {
  const std::string text = kHeader + "$comment written after the definitions $end\n#0\n1!\n";
  EXPECT_TRUE(parse_vcd(text).issues.empty()) << issues(parse_vcd(text));
  const auto f = parse_vcd(text, {.sigrok = true});
  EXPECT_TRUE(has_issue(f, 4, "vector variable top.bus (width 4)")) << issues(f);
  EXPECT_TRUE(has_issue(f, 7, "$comment after $enddefinitions")) << issues(f);
}

TEST(VcdLint, TheSimulatorsWriterIsClean) {
  const std::string path = (std::filesystem::temp_directory_path() / "endatsim_vcdlint_writer.vcd").string();
  {
    sim::Kernel k;
    sim::Signal a(k, "a", true);
    sim::VcdWriter vcd(k, path);
    vcd.add(a, "top", "a");
    vcd.start();
    struct Toggle {
      sim::Signal* s;
      void go() { s->write(!s->read()); }
    } toggle{&a};
    for (int i = 1; i <= 7; ++i) k.schedule(sim::ns(i), sim::bind<&Toggle::go>(&toggle));
    k.run();
    vcd.finish();
  }
  const auto f = scenarios::read_vcd_file(path, {.sigrok = true});
  EXPECT_TRUE(f.issues.empty()) << issues(f);
  ASSERT_NE(f.find("top.a"), nullptr);
  EXPECT_EQ(f.find("top.a")->falling, 4U);
  EXPECT_EQ(f.find("top.a")->rising, 3U);
  EXPECT_EQ(f.end_time, 7000);
  std::filesystem::remove(path);
}

TEST(VcdLint, UnreadableFileThrows) {
  EXPECT_THROW(scenarios::read_vcd_file("/nonexistent/x.vcd"), std::runtime_error);
}
