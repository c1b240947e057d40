#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scenario_support.hpp"

using namespace endatsim;

namespace {

std::string run_to_vcd(const scenarios::Scenario& s, std::uint64_t seed, const std::string& name) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  scenarios::RunOptions o;
  o.vcd_path = path;
  o.seed = seed;
  scenarios::run_scenario(s, o);
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::filesystem::remove(path);
  test_support::expect_clean_vcd(ss.str(), name);
  return ss.str();
}

}  // namespace

TEST(Determinism, SameScenarioAndSeedGiveByteIdenticalVcd) {
  auto s = test_support::make_scenario(30, sim::MHz(4), true, 10);
  s.master.jitter = sim::ns(5);
  s.encoder.motion.counts_per_s = 100'000;
  const std::string a = run_to_vcd(s, 42, "endatsim_det_a.vcd");
  const std::string b = run_to_vcd(s, 42, "endatsim_det_b.vcd");
  ASSERT_GT(a.size(), 1000U);
  EXPECT_TRUE(a == b);
  const std::string c = run_to_vcd(s, 43, "endatsim_det_c.vcd");
  EXPECT_FALSE(a == c) << "the seed drives the jitter, so another seed must give another trace";
}
