#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <vector>

#include <unistd.h>

#include "endatsim/sim/sim.hpp"
#include "scenario_support.hpp"

using namespace endatsim::sim;

namespace {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Driver {
  Signal* a;
  Signal* b;
  void step1() { a->write(true); }
  void glitch() {  // b goes up and, one delta later, down again: not a committed change of the step
    b->write(true);
  }
  void glitch_back() { b->write(false); }
};

}  // namespace

TEST(VcdWriter, WritesOnlyCommittedChangesAtTheEndOfEachTimeStep) {
  const std::string path = (std::filesystem::temp_directory_path() / "endatsim_vcd_test.vcd").string();
  {
    Kernel k;
    Signal a(k, "a", false);
    Signal b(k, "b", false);
    VcdWriter vcd(k, path);
    vcd.add(a, "top", "a");
    vcd.add(b, "top", "b");
    vcd.start();
    Driver d{&a, &b};
    k.schedule(ns(1), bind<&Driver::step1>(&d));
    k.schedule(ns(2), bind<&Driver::glitch>(&d));
    struct Later {
      Kernel* k;
      Driver* d;
      void go() { k->schedule(Time::zero(), bind<&Driver::glitch_back>(d)); }
    } later{&k, &d};
    k.schedule(ns(2), bind<&Later::go>(&later));
    k.run();
    vcd.finish();
  }
  const std::string text = read_file(path);
  const auto defs = text.find("$enddefinitions $end");
  ASSERT_NE(defs, std::string::npos);
  EXPECT_EQ(text.find("$comment", defs), std::string::npos);
  EXPECT_NE(text.find("$var wire 1 ! a $end"), std::string::npos);
  // b rose and fell inside the step at 2 ns: nothing is written for it; finish() closes at 2 ns.
  const auto body = text.substr(text.find("$end\n", text.find("$dumpvars")) + 5);
  EXPECT_EQ(body, "#1000\n1!\n#2000\n");
  endatsim::test_support::expect_clean_vcd(text, path);
  std::filesystem::remove(path);
}

TEST(VcdWriter, ReportsAnUnwritablePath) {
  Kernel k;
  EXPECT_THROW(VcdWriter(k, "/nonexistent-dir/x.vcd"), std::runtime_error);
}

// The part file is made afresh: a symlink planted where it goes is refused, not written through.
TEST(VcdWriter, RefusesALinkPlantedWhereItsPartFileGoes) {
  const auto dir = std::filesystem::temp_directory_path() / ("endatsim_vcd_link_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto victim = dir / "victim", out = dir / "out.vcd";
  std::ofstream(victim) << "precious";
  std::filesystem::create_symlink(victim, dir / ("out.vcd.part-" + std::to_string(::getpid())));
  Kernel k;
  EXPECT_THROW(VcdWriter(k, out.string()), std::runtime_error);
  std::ifstream in(victim);
  const std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(kept, "precious");
  EXPECT_FALSE(std::filesystem::exists(out));
  std::filesystem::remove_all(dir);
}

TEST(VcdWriter, ChangesAtTimeZeroAreStampedZero) {
  const std::string path = (std::filesystem::temp_directory_path() / "endatsim_vcd_zero.vcd").string();
  {
    Kernel k;
    Signal a(k, "a", false);
    VcdWriter vcd(k, path);
    vcd.add(a, "top", "a");
    vcd.start();
    a.write(true);  // before run(): committed in the first step, at 0 ps
    struct Low {
      Signal* s;
      void go() { s->write(false); }
    } low{&a};
    k.schedule(ns(3), bind<&Low::go>(&low));
    k.run();
    vcd.finish();
  }
  const std::string text = read_file(path);
  const auto body = text.substr(text.find("$end\n", text.find("$dumpvars")) + 5);
  EXPECT_EQ(body, "1!\n#3000\n0!\n");
  endatsim::test_support::expect_clean_vcd(text, path);
  std::filesystem::remove(path);
}

// Every time stamp is the time in decimal, whatever its digits: below 10^8 ps, where the leading
// digits are kept from the stamp before, across their changes, up to 19 digits, and at 2 000
// random times that step by 1 ps to 10^12 ps.
TEST(VcdWriter, StampsEachTimeStepWithItsTimeInDecimal) {
  std::vector<std::int64_t> times{1, 9, 10, 99'999'999, 100'000'000, 100'000'001, 109'999'999, 110'000'000,
                                  123'456'789, 987'654'321, 1'000'000'000'000, 1'000'000'099'999'990};
  std::mt19937_64 random(17);
  for (int k = 0; k < 2000; ++k) {
    const std::int64_t scale = std::int64_t{1} << (random() % 40);
    times.push_back(times.back() + 1 + static_cast<std::int64_t>(random() % static_cast<std::uint64_t>(scale)));
  }
  times.push_back(Time::max().count() - 1);
  const std::string path = (std::filesystem::temp_directory_path() / "endatsim_vcd_stamps.vcd").string();
  {
    Kernel k;
    Signal a(k, "a", false);
    VcdWriter vcd(k, path);
    vcd.add(a, "top", "a");
    vcd.start();
    struct Toggle {
      Signal* s;
      void go() { s->write(!s->read()); }
    } toggle{&a};
    for (std::int64_t t : times) k.schedule(Time{t}, bind<&Toggle::go>(&toggle));
    k.run();
    vcd.finish();
  }
  const std::string text = read_file(path);
  std::istringstream body(text.substr(text.find("$end\n", text.find("$dumpvars")) + 5));
  std::vector<std::int64_t> stamps;
  for (std::string line; std::getline(body, line);)
    if (!line.empty() && line[0] == '#') stamps.push_back(std::stoll(line.substr(1)));
  EXPECT_EQ(stamps, times);
  std::filesystem::remove(path);
}

// A text trace (GTKWave's "string" variable): declared after the wires of its scope, "-" until
// set, written at the end of the time step it was set in (the last text of a step counts), each
// run of spaces one '_'. The lint reads it; for sigrok it is an issue, since sigrok skips it.
TEST(VcdWriter, TextTracesAreStringVariablesWrittenAtTheirTimeStep) {
  const std::string path = (std::filesystem::temp_directory_path() / "endatsim_vcd_text_test.vcd").string();
  {
    Kernel k;
    Signal a(k, "a", false);
    VcdWriter vcd(k, path);
    vcd.add(a, "top", "a");
    const auto trace = vcd.add_text("top", "decoded");
    vcd.start();
    struct Texts {
      VcdWriter* vcd;
      std::size_t trace;
      Signal* a;
      void first() {
        vcd->set_text(trace, "ignored: a later text in the same step counts");
        vcd->set_text(trace, "#0  mode   bits");
      }
      void second() {
        a->write(true);
        vcd->set_text(trace, "");
      }
    } texts{&vcd, trace, &a};
    k.schedule(ns(1), bind<&Texts::first>(&texts));
    k.schedule(ns(2), bind<&Texts::second>(&texts));
    k.run();
    vcd.finish();
  }
  const std::string text = read_file(path);
  EXPECT_NE(text.find("$var wire 1 ! a $end\n$var string 1 \" decoded $end\n"), std::string::npos) << text;
  EXPECT_NE(text.find("0!\ns- \"\n$end\n"), std::string::npos) << text;
  const auto body = text.substr(text.find("$end\n", text.find("$dumpvars")) + 5);
  EXPECT_EQ(body, "#1000\ns#0_mode_bits \"\n#2000\ns- \"\n1!\n");
  EXPECT_TRUE(endatsim::scenarios::parse_vcd(text, {}).issues.empty());
  endatsim::scenarios::VcdLintOptions sigrok;
  sigrok.sigrok = true;
  const auto issues = endatsim::scenarios::parse_vcd(text, sigrok).issues;
  ASSERT_EQ(issues.size(), 1U);
  EXPECT_NE(issues[0].message.find("text variable top.decoded: sigrok-cli skips its values"), std::string::npos);
  std::filesystem::remove(path);
}

namespace {

// Changes of two wires a stretch apart: a rises at +1 ns; at +2 ns b rises while a falls and, one
// delta later, rises again (no line); at +3 ns both fall (two lines in one step, a first).
struct Activity {
  Kernel* k;
  Signal* a;
  Signal* b;
  void a_up() { a->write(true); }
  void a_down() { a->write(false); }
  void b_up() { b->write(true); }
  void b_down() { b->write(false); }
  void a_blip() {
    a->write(false);
    k->schedule(Time::zero(), bind<&Activity::a_up>(this));
  }
  void schedule(Time origin) {
    k->schedule_at(origin + ns(1), bind<&Activity::a_up>(this));
    k->schedule_at(origin + ns(2), bind<&Activity::b_up>(this));
    k->schedule_at(origin + ns(2), bind<&Activity::a_blip>(this));
    k->schedule_at(origin + ns(3), bind<&Activity::a_down>(this));
    k->schedule_at(origin + ns(3), bind<&Activity::b_down>(this));
  }
};

// Wires a and b with a VCD writer to `path`, and the activity above on them.
struct TwoWires {
  explicit TwoWires(const std::string& path) : vcd(k, path) {
    vcd.add(a, "top", "a");
    vcd.add(b, "top", "b");
    vcd.start();
  }
  Kernel k;
  Signal a{k, "a", false}, b{k, "b", false};
  VcdWriter vcd;
  Activity act{&k, &a, &b};
};

}  // namespace

// The fast path's VCD: a stretch recorded on a tape, prepared and played later gives the bytes of
// running it there, with stamps whose leading digits change in the middle of the stretch.
TEST(VcdWriter, APreparedStretchPlayedLaterWritesTheBytesOfRunningIt) {
  const Time first = ns(10);
  const Time second = ps(199'999'998'000);  // its +2 ns step is the first stamp of 2000 x 10^8 ps
  const auto dir = std::filesystem::temp_directory_path();
  const std::string ran = (dir / ("endatsim_vcd_ran_" + std::to_string(::getpid()) + ".vcd")).string();
  const std::string played = (dir / ("endatsim_vcd_played_" + std::to_string(::getpid()) + ".vcd")).string();
  {
    TwoWires w(ran);
    w.act.schedule(first);
    w.act.schedule(second);
    w.k.run();
    w.vcd.finish();
  }
  {
    TwoWires w(played);
    w.act.schedule(first);
    Tape tape;
    ASSERT_TRUE(w.vcd.quiet());
    w.k.record_to(&tape);
    w.k.run();
    w.k.record_to(nullptr);
    const VcdWriter::Stretch stretch = w.vcd.prepare(tape, first);
    ASSERT_EQ(stretch.steps.size(), 3U);
    EXPECT_EQ(stretch.steps[1].at, ns(2));
    EXPECT_EQ(stretch.lines, "1!\n1\"\n0!\n0\"\n");
    EXPECT_EQ(stretch.covered, tape.items.size());
    w.k.replay_time(second + ns(3));
    w.vcd.play_steps(stretch, 0, stretch.steps.size(), second);
    w.vcd.play_end(stretch);
    w.vcd.finish();
  }
  const std::string text = read_file(played);
  EXPECT_NE(text.find("#199999999000\n1!\n#200000000000\n1\"\n#200000001000\n0!\n0\"\n"), std::string::npos) << text;
  EXPECT_EQ(text, read_file(ran));
  endatsim::test_support::expect_clean_vcd(text, played);
  std::filesystem::remove(ran);
  std::filesystem::remove(played);
}
