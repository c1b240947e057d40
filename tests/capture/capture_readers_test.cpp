// The capture readers read one waveform the same from a VCD, from sigrok session files that
// Debian's sigrok-cli makes of that VCD, from the CSV sigrok-cli writes of those sessions and
// from a Saleae Logic 2 style CSV; bad files give CaptureError naming the file and the problem.
#include <gtest/gtest.h>

#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <climits>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <utility>

#include "endatsim/capture/capture.hpp"
#include "../sigrok_cli.hpp"

namespace fs = std::filesystem;
using endatsim::capture::Change;
using endatsim::capture::CaptureError;
using endatsim::capture::Reader;
using endatsim::sim::Time;
namespace capture = endatsim::capture;

namespace {

// One waveform: the clock and data of a short transfer, in nanoseconds. The capture runs on to
// 1000 ns, past the last change, so that sigrok's samples hold every change.
const char* const kVcd = R"($date today $end
$timescale 1 ns $end
$scope module top $end
$var wire 1 ! clock $end
$var wire 1 " data $end
$upscope $end
$enddefinitions $end
#0
$dumpvars
1!
0"
$end
#100
0!
#200
1!
1"
#350
0"
#500
0!
#600
1!
#640
1"
#700
0!
#800
1!
#1000
)";

struct Level {
  std::int64_t ps;
  char value;
};
// The changes of each signal, by its name without scopes.
using Waveform = std::map<std::string, std::vector<Level>>;

Waveform expected_waveform() {
  return {{"clock", {{0, '1'}, {100'000, '0'}, {200'000, '1'}, {500'000, '0'}, {600'000, '1'}, {700'000, '0'}, {800'000, '1'}}},
          {"data", {{0, '0'}, {200'000, '1'}, {350'000, '0'}, {640'000, '1'}}}};
}

std::string short_name(const std::string& full) {
  const auto dot = full.rfind('.');
  return dot == std::string::npos ? full : full.substr(dot + 1);
}

Waveform read_all(Reader& reader) {
  Waveform w;
  for (const auto& name : reader.signals()) w[short_name(name)];
  Change c;
  Time previous{INT64_MIN};
  while (reader.next(c)) {
    EXPECT_GE(c.time, previous) << reader.path() << ": changes out of time order";
    previous = c.time;
    w[short_name(reader.signals().at(c.signal))].push_back({c.time.count(), c.value});
  }
  return w;
}

// Each signal changes to the same levels, at times no more than `tolerance` earlier than wanted
// (a sample covers the time up to the next one) and never later.
void expect_same(const Waveform& want, const Waveform& got, Time tolerance, const std::string& what) {
  ASSERT_EQ(want.size(), got.size()) << what;
  for (const auto& [name, levels] : want) {
    const auto it = got.find(name);
    ASSERT_NE(it, got.end()) << what << ": no signal " << name;
    ASSERT_EQ(levels.size(), it->second.size()) << what << ": changes of " << name;
    for (std::size_t i = 0; i < levels.size(); ++i) {
      EXPECT_EQ(levels[i].value, it->second[i].value) << what << ": " << name << " change " << i;
      const std::int64_t early = levels[i].ps - it->second[i].ps;
      if (tolerance == Time{0}) {
        EXPECT_EQ(levels[i].ps, it->second[i].ps) << what << ": " << name << " change " << i;
      } else {
        EXPECT_GE(early, 0) << what << ": " << name << " change " << i << " at " << it->second[i].ps << " ps";
        EXPECT_LT(early, tolerance.count()) << what << ": " << name << " change " << i << " at " << it->second[i].ps << " ps";
      }
    }
  }
}

std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const CaptureError& e) {
    return e.what();
  }
  return "(no CaptureError)";
}

void read_to_end(const std::string& path) {
  auto reader = capture::open(path);
  Change c;
  while (reader->next(c)) {
  }
}

void expect_mentions(const std::string& message, const std::vector<std::string>& parts) {
  for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

using endatsim::test_support::kNoSigrokCli;
using endatsim::test_support::sigrok_cli;

// Zip entries (name, bytes), deflated unless `store`.
void write_zip(const std::string& path, const std::vector<std::pair<std::string, std::string>>& entries, bool store = false) {
  int code = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
  ASSERT_NE(z, nullptr) << "zip_open " << path << ": error " << code;
  for (const auto& [name, bytes] : entries) {
    zip_source_t* source = zip_source_buffer(z, bytes.data(), bytes.size(), 0);
    ASSERT_NE(source, nullptr) << zip_strerror(z);
    const zip_int64_t index = zip_file_add(z, name.c_str(), source, ZIP_FL_OVERWRITE);
    ASSERT_GE(index, 0) << zip_strerror(z);
    if (store) {
      ASSERT_EQ(zip_set_file_compression(z, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0), 0);
    }
  }
  ASSERT_EQ(zip_close(z), 0) << zip_strerror(z);
}

std::string metadata(const std::string& device_keys) {
  return "[global]\nsigrok version=0.5.2\n\n[device 1]\n" + device_keys;
}

// Samples of `unitsize` bytes, little-endian.
std::string samples(const std::vector<std::uint64_t>& values, unsigned unitsize) {
  std::string out;
  for (auto v : values)
    for (unsigned b = 0; b < unitsize; ++b) out.push_back(static_cast<char>((v >> (8 * b)) & 0xff));
  return out;
}

class CaptureReaders : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("endatsim_capture_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }
  // Runs sigrok-cli; its messages go to a log that a failure shows.
  ::testing::AssertionResult sigrok(const std::string& args) const {
    const std::string cli = sigrok_cli();
    if (cli.empty()) return ::testing::AssertionFailure() << kNoSigrokCli;
    const std::string log = file("sigrok-cli.log");
    const int status = std::system((cli + " " + args + " >" + log + " 2>&1").c_str());
    if (status == 0) return ::testing::AssertionSuccess();
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    return ::testing::AssertionFailure() << "sigrok-cli " << args << " failed (" << status << "): " << text.str();
  }
  // The session sigrok-cli makes of the VCD, at the VCD's 1 GHz or divided by `downsample`.
  std::string session_from_vcd(const std::string& name, int downsample = 1) const {
    const std::string vcd = write("wave.vcd", kVcd);
    const std::string sr = file(name);
    const std::string input = downsample == 1 ? "-I vcd" : "-I vcd:downsample=" + std::to_string(downsample);
    EXPECT_TRUE(sigrok(input + " -i " + vcd + " -o " + sr));
    return sr;
  }
  fs::path dir_;
};

TEST_F(CaptureReaders, VcdGivesTheWaveformWritten) {
  auto reader = capture::open(write("wave.vcd", kVcd));
  EXPECT_EQ(reader->signals(), (std::vector<std::string>{"top.clock", "top.data"}));
  EXPECT_EQ(reader->resolution(), Time{1000});
  expect_same(expected_waveform(), read_all(*reader), Time{0}, "VCD");
}

TEST_F(CaptureReaders, SigrokCliSessionOfTheVcdReadsTheSame) {
  ASSERT_FALSE(sigrok_cli().empty()) << kNoSigrokCli;
  const std::string sr = session_from_vcd("wave.sr");
  auto reader = capture::open(sr);  // by its zip signature
  EXPECT_EQ(reader->signals(), (std::vector<std::string>{"clock", "data"}));
  EXPECT_EQ(reader->resolution(), Time{1000});  // 1 GHz, from the VCD's 1 ns
  expect_same(expected_waveform(), read_all(*reader), Time{0}, "sigrok session");
  auto vcd = capture::open_vcd(file("wave.vcd"));
  auto session = capture::open_sigrok(sr);
  expect_same(read_all(*vcd), read_all(*session), Time{0}, "VCD reader against sigrok reader");
  EXPECT_GT(session->bytes_read(), 0u);
  EXPECT_LE(session->bytes_read(), session->bytes_total());
  EXPECT_EQ(session->bytes_total(), fs::file_size(sr));
}

TEST_F(CaptureReaders, SigrokCliSessionAt25MHzIsWithinOneSamplePeriod) {
  ASSERT_FALSE(sigrok_cli().empty()) << kNoSigrokCli;
  const std::string sr = session_from_vcd("wave25.sr", 40);
  auto reader = capture::open(sr);
  EXPECT_EQ(reader->resolution(), Time{40'000});
  expect_same(expected_waveform(), read_all(*reader), Time{40'000}, "25 MHz session");
}

TEST_F(CaptureReaders, SigrokCliCsvOfTheSessionReadsTheSame) {
  ASSERT_FALSE(sigrok_cli().empty()) << kNoSigrokCli;
  for (int downsample : {1, 40}) {
    const std::string sr = session_from_vcd("wave" + std::to_string(downsample) + ".sr", downsample);
    auto session = capture::open(sr);
    const Waveform from_session = read_all(*session);
    // The default (a row per sample, columns headed by unit, names in a comment), a time column,
    // rows only where a level changes, names in the header, no header line, a trigger column.
    const std::vector<std::string> variants{"", ":time=true", ":time=true:dedup=true", ":label=channel",
                                            ":label=channel:time=true:dedup=true", ":label=off", ":label=off:time=true",
                                            ":time=true:trigger=true"};
    for (std::size_t v = 0; v < variants.size(); ++v) {
      const std::string& options = variants[v];
      const std::string csv = file("wave" + std::to_string(downsample) + "_" + std::to_string(v) + ".csv");
      ASSERT_TRUE(sigrok("-i " + sr + " -O csv" + options + " -o " + csv));
      const std::string what = "sigrok-cli -O csv" + options + " of a session downsampled by " + std::to_string(downsample);
      auto reader = capture::open(csv);  // by its extension
      EXPECT_EQ(reader->signals(), (std::vector<std::string>{"clock", "data"})) << what;
      EXPECT_EQ(reader->resolution(), session->resolution()) << what;
      expect_same(from_session, read_all(*reader), Time{0}, what);
    }
  }
}

TEST_F(CaptureReaders, SaleaeExportOfTheWaveformReadsTheSame) {
  // Logic 2's digital export: a row at the start and at each change, channels renamed.
  const std::string csv = write("saleae.csv",
                                "Time [s],clock,data\n"
                                "0.000000000,1,0\n"
                                "0.000000100,0,0\n"
                                "0.000000200000,1,1\n"
                                "0.000000350,1,0\n"
                                "0.000000500,0,0\n"
                                "0.000000600,1,0\n"
                                "0.000000640,1,1\n"
                                "0.000000700,0,1\n"
                                "0.000000800000,1,1\n");
  auto reader = capture::open(csv);
  EXPECT_EQ(reader->signals(), (std::vector<std::string>{"clock", "data"}));
  // No sample rate in the export: the greatest common step of its times, 10 ns, is taken as the
  // sample period.
  EXPECT_EQ(reader->resolution(), Time{10'000});
  EXPECT_TRUE(reader->sampled());
  EXPECT_NE(reader->timescale().find("inferred"), std::string::npos);
  expect_same(expected_waveform(), read_all(*reader), Time{0}, "Saleae CSV");
}

TEST_F(CaptureReaders, SaleaeTimesAreExactPicoseconds) {
  const std::string csv = write("times.csv",
                                "Time[s], Channel 0, Channel 1\r\n"  // Logic 1.x spelling, CRLF
                                "-0.000001,0,0\r\n"                  // before the trigger
                                "0.000000000001,1,0\r\n"
                                "1.000000000001,1,1\r\n"
                                "1.0000000000024,0,1\r\n"   // finer than a picosecond: rounds down
                                "1.0000000000025,0,0\r\n"   // and up
                                "2.5e0,1,0\r\n"
                                "9223372.036854775807,1,1\r\n");  // the last picosecond of Time
  auto reader = capture::open(csv);
  EXPECT_EQ(reader->signals(), (std::vector<std::string>{"Channel 0", "Channel 1"}));
  std::vector<std::tuple<std::int64_t, std::uint32_t, char>> got;
  Change c;
  while (reader->next(c)) got.emplace_back(c.time.count(), c.signal, c.value);
  const std::vector<std::tuple<std::int64_t, std::uint32_t, char>> want{
      {-1'000'000, 0, '0'},          {-1'000'000, 1, '0'},         {1, 0, '1'},
      {1'000'000'000'001, 1, '1'},   {1'000'000'000'002, 0, '0'},  {1'000'000'000'003, 1, '0'},
      {2'500'000'000'000, 0, '1'},   {INT64_MAX, 1, '1'}};
  EXPECT_EQ(got, want);
}

TEST_F(CaptureReaders, SaleaeSamplerateCommentSetsTheResolution) {
  auto reader = capture::open(write("rate.csv", "; Samplerate: 500 MHz\nTime [s],Channel 0\n0.0,1\n0.000000002,0\n"));
  EXPECT_EQ(reader->resolution(), Time{2000});
  const Waveform w = read_all(*reader);
  ASSERT_EQ(w.at("Channel 0").size(), 2u);
  EXPECT_EQ(w.at("Channel 0")[1].ps, 2000);
}

TEST_F(CaptureReaders, SigrokCsvWithChannelsNamedByNumbers) {
  // label=channel for channels named "0" and "1": the header line is told from a row of levels
  // by the "Channels" comment; with label=off the same first line is a row.
  const std::string comments = "; CSV generated by libsigrok 0.5.2\n; Channels (2/2): 0, 1\n; Samplerate: 1 MHz\n";
  auto named = capture::open(write("named.csv", comments + "0,1\n1,0\n1,1\n"));
  EXPECT_EQ(named->signals(), (std::vector<std::string>{"0", "1"}));
  const Waveform with_header = read_all(*named);
  ASSERT_EQ(with_header.at("1").size(), 2u);
  EXPECT_EQ(with_header.at("1")[1].ps, 1'000'000);  // the second row is sample 1
  auto rows = capture::open(write("rows.csv", comments + "1,1\n1,0\n"));
  const Waveform without_header = read_all(*rows);
  ASSERT_EQ(without_header.at("1").size(), 2u);
  EXPECT_EQ(without_header.at("1")[0].value, '1');
  EXPECT_EQ(without_header.at("1")[1].ps, 1'000'000);
}

TEST_F(CaptureReaders, SelectReportsOnlyTheChosenSignals) {
  for (const std::string name : {"wave.vcd", "saleae.csv"}) {
    const std::string path =
        name == "wave.vcd" ? write(name, kVcd)
                           : write(name, "Time [s],clock,data\n0,1,0\n0.0000001,0,0\n0.0000002,1,1\n0.00000035,1,0\n");
    auto reader = capture::open(path);
    const std::uint32_t data = capture::find_signal(*reader, "data");
    reader->select({data});
    Change c;
    std::vector<std::int64_t> times;
    while (reader->next(c)) {
      EXPECT_EQ(c.signal, data) << name;
      times.push_back(c.time.count());
    }
    ASSERT_GE(times.size(), 3u) << name;
    EXPECT_EQ(std::vector<std::int64_t>(times.begin(), times.begin() + 3), (std::vector<std::int64_t>{0, 200'000, 350'000}))
        << name;
  }
}

TEST_F(CaptureReaders, SessionWithTwoByteSamplesChunksAndAnUnevenPeriod) {
  // 12 probes in 2-byte samples, three of them named (the others were disabled), 3 MHz: the
  // period is 333333.3 ps, so each time is computed from the sample number, never summed.
  const std::string md = metadata(
      "capturefile=logic-1\ntotal probes=12\nsamplerate=3 MHz\ntotal analog=0\nprobe1=A0\nprobe10=A9\nprobe12=A11\n"
      "unitsize=2\n");
  const std::string sr = file("uneven.sr");
  write_zip(sr, {{"version", "2"},
                 {"metadata", md},
                 {"logic-1-1", samples({0x0000, 0x0001, 0x0003}, 2)},  // bit 1 is a disabled probe
                 {"logic-1-2", samples({0x0201, 0x0800}, 2)}});
  auto reader = capture::open(sr);
  EXPECT_EQ(reader->signals(), (std::vector<std::string>{"A0", "A9", "A11"}));
  EXPECT_EQ(reader->resolution(), Time{333'334});
  std::vector<std::tuple<std::int64_t, std::uint32_t, char>> got;
  Change c;
  while (reader->next(c)) got.emplace_back(c.time.count(), c.signal, c.value);
  const std::vector<std::tuple<std::int64_t, std::uint32_t, char>> want{
      {0, 0, '0'},         {0, 1, '0'},         {0, 2, '0'},         {333'333, 0, '1'},
      {1'000'000, 1, '1'}, {1'333'333, 0, '0'}, {1'333'333, 1, '0'}, {1'333'333, 2, '1'}};
  EXPECT_EQ(got, want);
}

TEST_F(CaptureReaders, UnchunkedSessionIsReadToo) {
  // A session whose samples are one entry named by capturefile itself, without a chunk number.
  const std::string sr = file("single.sr");
  write_zip(sr, {{"version", "2"},
                 {"metadata", metadata("capturefile=logic-1\ntotal probes=2\nsamplerate=1 MHz\nprobe2=b\nunitsize=1\n")},
                 {"logic-1", samples({0x00, 0x01, 0x02, 0x02}, 1)}});
  auto reader = capture::open(sr);
  EXPECT_EQ(reader->signals(), (std::vector<std::string>{"b"}));
  const Waveform w = read_all(*reader);
  ASSERT_EQ(w.at("b").size(), 2u);
  EXPECT_EQ(w.at("b")[0].value, '0');
  EXPECT_EQ(w.at("b")[1].ps, 2'000'000);
  EXPECT_EQ(w.at("b")[1].value, '1');
}

TEST_F(CaptureReaders, SessionSampleratesInEachForm) {
  const std::vector<std::pair<std::string, std::int64_t>> rates{
      {"25 MHz", 40'000}, {"100 kHz", 10'000'000}, {"1 GHz", 1'000}, {"200 Hz", 5'000'000'000},
      {"1.5 MHz", 666'667}, {"12500000", 80'000}};
  for (const auto& [rate, period] : rates) {
    const std::string sr = file("rate.sr");
    write_zip(sr, {{"version", "2"},
                   {"metadata", metadata("capturefile=logic-1\ntotal probes=1\nsamplerate=" + rate + "\nprobe1=x\nunitsize=1\n")},
                   {"logic-1-1", samples({0, 0, 1}, 1)}});
    auto reader = capture::open(sr);
    EXPECT_EQ(reader->resolution(), Time{period}) << rate;
    const Waveform w = read_all(*reader);
    ASSERT_EQ(w.at("x").size(), 2u) << rate;
    // Sample 2: exactly 2e12 / rate picoseconds, rounded down.
    EXPECT_EQ(w.at("x")[1].ps, rate == "1.5 MHz" ? 1'333'333 : 2 * period) << rate;
  }
}

// 50 million samples, generated while libzip compresses them: the test never holds them either.
struct Generated {
  std::uint64_t first = 0;  // sample number of the chunk's first byte
  std::uint64_t count = 0;
  std::uint64_t at = 0;
};

char level_at(std::uint64_t sample) {
  // clk (bit 0) high from 12345678 to 49999998; data (bit 1) high throughout.
  return static_cast<char>(0x02 | (sample >= 12'345'678 && sample < 49'999'999 ? 0x01 : 0x00));
}

zip_int64_t generate(void* state, void* data, zip_uint64_t len, zip_source_cmd_t cmd) {
  auto* g = static_cast<Generated*>(state);
  switch (cmd) {
    case ZIP_SOURCE_OPEN: g->at = 0; return 0;
    case ZIP_SOURCE_READ: {
      const std::uint64_t n = std::min<std::uint64_t>(len, g->count - g->at);
      auto* out = static_cast<char*>(data);
      for (std::uint64_t i = 0; i < n; ++i) out[i] = level_at(g->first + g->at + i);
      g->at += n;
      return static_cast<zip_int64_t>(n);
    }
    case ZIP_SOURCE_CLOSE: return 0;
    case ZIP_SOURCE_STAT: {
      if (len < sizeof(zip_stat_t)) return -1;
      auto* st = static_cast<zip_stat_t*>(data);
      zip_stat_init(st);
      st->size = g->count;
      st->valid |= ZIP_STAT_SIZE;
      return sizeof(zip_stat_t);
    }
    case ZIP_SOURCE_ERROR: {
      if (len < 2 * sizeof(int)) return -1;
      auto* e = static_cast<int*>(data);
      e[0] = e[1] = 0;
      return 2 * sizeof(int);
    }
    case ZIP_SOURCE_FREE: return 0;
    case ZIP_SOURCE_SUPPORTS:
      return zip_source_make_command_bitmap(ZIP_SOURCE_OPEN, ZIP_SOURCE_READ, ZIP_SOURCE_CLOSE, ZIP_SOURCE_STAT,
                                            ZIP_SOURCE_ERROR, ZIP_SOURCE_FREE, -1);
    default: return -1;
  }
}

std::int64_t peak_rss_kib() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stoll(line.substr(6));
  return -1;
}

TEST_F(CaptureReaders, LargeSessionIsStreamed) {
  const std::uint64_t total = 50'000'000;
  const std::string sr = file("large.sr");
  {
    int code = 0;
    zip_t* z = zip_open(sr.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
    ASSERT_NE(z, nullptr);
    const std::string version = "2";
    const std::string md = metadata("capturefile=logic-1\ntotal probes=2\nsamplerate=25 MHz\nprobe1=clk\nprobe2=data\nunitsize=1\n");
    ASSERT_GE(zip_file_add(z, "version", zip_source_buffer(z, version.data(), version.size(), 0), 0), 0);
    ASSERT_GE(zip_file_add(z, "metadata", zip_source_buffer(z, md.data(), md.size(), 0), 0), 0);
    // A 40 M and a 10 M sample chunk: a reader that took a chunk whole would need 40 MB.
    Generated chunks[2] = {{0, 40'000'000, 0}, {40'000'000, 10'000'000, 0}};
    for (int i = 0; i < 2; ++i) {
      zip_source_t* source = zip_source_function(z, generate, &chunks[i]);
      ASSERT_NE(source, nullptr) << zip_strerror(z);
      ASSERT_GE(zip_file_add(z, ("logic-1-" + std::to_string(i + 1)).c_str(), source, 0), 0) << zip_strerror(z);
    }
    ASSERT_EQ(zip_close(z), 0) << zip_strerror(z);
  }
  ASSERT_LT(fs::file_size(sr), 1'000'000u);  // compressed: the test file itself is small

  // Peak memory from here on (clear_refs 5 resets the peak where the kernel allows it).
  std::ofstream("/proc/self/clear_refs") << "5";
  const std::int64_t peak_before = peak_rss_kib();
  auto reader = capture::open(sr);
  std::vector<std::tuple<std::int64_t, std::uint32_t, char>> got;
  Change c;
  while (reader->next(c)) got.emplace_back(c.time.count(), c.signal, c.value);
  const std::int64_t peak_after = peak_rss_kib();
  const std::vector<std::tuple<std::int64_t, std::uint32_t, char>> want{
      {0, 0, '0'}, {0, 1, '1'}, {12'345'678LL * 40'000, 0, '1'}, {49'999'999LL * 40'000, 0, '0'}};
  EXPECT_EQ(got, want);
  EXPECT_LE(reader->bytes_read(), reader->bytes_total());
  EXPECT_GT(reader->bytes_read(), 0u);
  ASSERT_GT(peak_before, 0);
  EXPECT_LT(peak_after - peak_before, 16 * 1024) << "peak RSS grew by " << peak_after - peak_before << " KiB reading "
                                                  << total << " samples";
}

// --- Bad sigrok session files --------------------------------------------------------------

TEST_F(CaptureReaders, TruncatedSessionIsRefused) {
  std::string bytes;
  {
    const std::string sr = file("whole.sr");
    write_zip(sr, {{"version", "2"},
                   {"metadata", metadata("capturefile=logic-1\ntotal probes=1\nsamplerate=1 MHz\nprobe1=x\nunitsize=1\n")},
                   {"logic-1-1", std::string(4096, '\x01')}});
    std::ifstream in(sr, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string cut = write("cut.sr", bytes.substr(0, bytes.size() / 2));
  const std::string message = error_of([&] { read_to_end(cut); });
  expect_mentions(message, {cut + ": ", "truncated", "zip"});
}

TEST_F(CaptureReaders, CorruptSampleEntryIsRefusedWhenRead) {
  std::string noise;
  std::uint32_t x = 12345;
  for (int i = 0; i < 100'000; ++i) {
    x = x * 1103515245u + 12345u;
    noise.push_back(static_cast<char>(x >> 24));
  }
  const std::string sr = file("corrupt.sr");
  write_zip(sr, {{"logic-1-1", noise},
                 {"version", "2"},
                 {"metadata", metadata("capturefile=logic-1\ntotal probes=8\nsamplerate=1 MHz\nprobe1=x\nunitsize=1\n")}},
            true);
  // The first entry's data follows its local header: 30 bytes, the name and the extra field.
  std::fstream f(sr, std::ios::in | std::ios::out | std::ios::binary);
  unsigned char header[30];
  f.read(reinterpret_cast<char*>(header), sizeof header);
  const std::size_t data = 30 + (header[26] | header[27] << 8) + (header[28] | header[29] << 8);
  f.seekp(static_cast<std::streamoff>(data + 50'000));
  f.put('\x5a').put('\xa5');
  f.close();
  const std::string message = error_of([&] { read_to_end(sr); });
  expect_mentions(message, {sr + ": ", "'logic-1-1'", "corrupt"});
}

TEST_F(CaptureReaders, ZipThatIsNoSessionIsRefused) {
  const std::string sr = file("other.sr");
  write_zip(sr, {{"hello.txt", "not a capture\n"}});
  expect_mentions(error_of([&] { capture::open(sr); }), {sr + ": ", "without a 'metadata' entry", "not a sigrok session file"});
  const std::string text = write("text.sr", "just text\n");
  expect_mentions(error_of([&] { capture::open_sigrok(text); }), {text + ": ", "not a zip archive"});
}

TEST_F(CaptureReaders, AFileThatCannotBeOpenedSaysWhy) {
  const std::string missing = file("missing.vcd");
  for (const auto& opener : {+[](const std::string& p) { capture::open(p); }, +[](const std::string& p) { capture::open_vcd(p); },
                             +[](const std::string& p) { capture::open_csv(p); },
                             +[](const std::string& p) { capture::open_sigrok(p); }})
    expect_mentions(error_of([&] { opener(missing); }),
                    {missing + ": cannot open the capture for reading: No such file or directory"});
}

TEST_F(CaptureReaders, BadSessionMetadataIsRefused) {
  struct Case {
    std::string keys;
    std::vector<std::pair<std::string, std::string>> chunks;
    std::vector<std::string> mentions;
  };
  const std::string one = std::string(4, '\x01');
  const std::vector<Case> cases{
      {"capturefile=logic-1\ntotal probes=1\nprobe1=x\nunitsize=1\n", {{"logic-1-1", one}}, {"no samplerate"}},
      {"capturefile=logic-1\ntotal probes=1\nsamplerate=fast\nprobe1=x\nunitsize=1\n", {{"logic-1-1", one}},
       {"samplerate 'fast'"}},
      {"capturefile=logic-1\ntotal probes=1\nsamplerate=25 MHzz\nprobe1=x\nunitsize=1\n", {{"logic-1-1", one}},
       {"samplerate '25 MHzz'"}},
      {"capturefile=logic-1\ntotal probes=1\nsamplerate=1 MHz\nprobe1=x\nunitsize=9\n", {{"logic-1-1", one}},
       {"unitsize '9'", "1 .. 8"}},
      {"capturefile=logic-1\ntotal probes=1\nsamplerate=1 MHz\nprobe1=x\nunitsize=0\n", {{"logic-1-1", one}},
       {"unitsize '0'"}},
      {"capturefile=logic-1\ntotal probes=4\nsamplerate=1 MHz\nprobe1=x\nprobe5=y\nunitsize=1\n", {{"logic-1-1", one}},
       {"probe5=y", "total probes=4"}},
      {"capturefile=logic-1\ntotal probes=12\nsamplerate=1 MHz\nprobe1=x\nunitsize=1\n", {{"logic-1-1", one}},
       {"total probes=12", "unitsize=1"}},
      {"capturefile=logic-1\nsamplerate=1 MHz\nprobe1=x\nunitsize=1\n", {{"logic-1-1", one}}, {"total probes is missing"}},
      {"capturefile=logic-1\ntotal probes=9\nsamplerate=1 MHz\nprobe1=x\nunitsize=2\n", {{"logic-1-1", "abc"}},
       {"'logic-1-1'", "3 bytes", "multiple of 2"}},
      {"total probes=0\nsamplerate=1 MHz\ntotal analog=1\nanalog1=CH1\n", {{"analog-1-1-1", "abcd"}},
       {"analog-only", "capturefile"}},
      {"capturefile=logic-1\ntotal probes=1\nsamplerate=1 MHz\nprobe1=x\nunitsize=1\n",
       {{"logic-1-1", one}, {"logic-1-3", one}}, {"'logic-1-3'", "missing 'logic-1-2'"}},
      {"capturefile=logic-1\ntotal probes=1\nsamplerate=1 MHz\nprobe1=x\nunitsize=1\n", {}, {"no sample data", "logic-1-1"}},
  };
  for (const auto& c : cases) {
    const std::string sr = file("bad.sr");
    std::vector<std::pair<std::string, std::string>> entries{{"version", "2"}, {"metadata", metadata(c.keys)}};
    entries.insert(entries.end(), c.chunks.begin(), c.chunks.end());
    write_zip(sr, entries);
    SCOPED_TRACE(c.keys);
    auto mentions = c.mentions;
    mentions.push_back(sr + ": ");
    expect_mentions(error_of([&] { read_to_end(sr); }), mentions);
  }
  const std::string sr = file("version.sr");
  write_zip(sr, {{"version", "3"}, {"metadata", metadata("capturefile=logic-1\n")}});
  expect_mentions(error_of([&] { read_to_end(sr); }), {sr + ": ", "version '3'", "expected version 1 or 2"});
}

// --- Bad CSV -------------------------------------------------------------------------------

TEST_F(CaptureReaders, BadCsvIsRefusedWithTheLine) {
  struct Case {
    std::string text;
    std::vector<std::string> mentions;
  };
  const std::vector<Case> cases{
      {"", {"empty file"}},
      {"; Samplerate: 1 MHz\n; just comments\n", {"no header"}},
      {"0,1\n1,1\n", {"line 1: no header", "'0,1' is a data row"}},
      {"Time [s],clock,data\n0,1,0\n0.1,1,2\n", {"line 3: ", "value '2' for 'data' is not 0 or 1"}},
      {"Time [s],clock,data\n0,1,0\n0.1,x,0\n", {"line 3: ", "value 'x' for 'clock'"}},
      {"Time [s],clock,data\n0,1,0\n\n0.1,1\n", {"line 4: ", "2 fields", "3 columns"}},
      {"Time [s],clock,data\n0,1,0\n0.2,1,1\n0.1,0,1\n", {"line 4: ", "goes backwards"}},
      {"Time [s],clock,data\nsoon,1,0\n", {"line 2: ", "time 'soon'", "seconds"}},
      {"Time [s],clock,data\n", {"no data rows"}},
      {"clock,data\n1,0\n", {"line 1: ", "Samplerate"}},
      {"; Samplerate: 1 MHz\nlogic,logic\n1,0\n", {"'logic'", "no \"; Channels\" comment"}},
      {"; Samplerate: 3 MHz\nnanoseconds,a\n333,1\n500,0\n", {"line 4: ", "multiple of the sample period"}},
      {"Time [s],a\n9223372.036854775808,1\n", {"line 2: ", "time '9223372.036854775808'"}},
      {"; Samplerate: 1 MHz\nnanoseconds,a\n1000,1\n", {"line 2: ", "in nanoseconds", "microseconds"}},
      {"; Samplerate: quick\nTime [s],a\n0,1\n", {"line 1: ", "samplerate 'quick'"}},
      {"Time [s],a,a\n0,1,1\n", {"two columns named 'a'"}},
  };
  for (const auto& c : cases) {
    const std::string csv = write("bad.csv", c.text);
    SCOPED_TRACE(c.text);
    auto mentions = c.mentions;
    mentions.push_back(csv + ": ");
    expect_mentions(error_of([&] { read_to_end(csv); }), mentions);
  }
}

// --- Inputs found by fuzzing (fuzz/fuzz_capture.cpp) ----------------------------------------

// The name of each signal, or the CaptureError reading the VCD to the end gave.
std::string vcd_signals_or_error(const std::string& path) {
  try {
    auto reader = capture::open_vcd(path);
    Change c;
    while (reader->next(c)) {
    }
    std::string names;
    for (const auto& n : reader->signals()) names += (names.empty() ? "" : " ") + n;
    return names;
  } catch (const CaptureError& e) {
    return e.what();
  }
}

TEST_F(CaptureReaders, VcdBitRangePastTheIndexRangeIsRefused) {
  const auto vcd = [&](const std::string& width, const std::string& range) {
    return write("range.vcd", "$timescale 1 ns $end\n$var wire " + width + " ! v " + range +
                                  " $end\n$enddefinitions $end\n#0\nb" + std::string(std::stoul(width), '1') + " !\n");
  };
  EXPECT_EQ(vcd_signals_or_error(vcd("2", "[9223372036854775806:9223372036854775807]")),
            "v[9223372036854775806] v[9223372036854775807]");
  EXPECT_EQ(vcd_signals_or_error(vcd("2", "[-9223372036854775807:-9223372036854775808]")),
            "v[-9223372036854775807] v[-9223372036854775808]");
  for (const auto& [width, range] : std::vector<std::pair<std::string, std::string>>{
           {"2", "[-9223372036854775808]"},
           {"4", "[9223372036854775806:9223372036854775807]"},
           {"3", "[-9223372036854775807:-9223372036854775808]"}}) {
    const std::string path = vcd(width, range);
    SCOPED_TRACE(range);
    expect_mentions(vcd_signals_or_error(path),
                    {path + ": line ", "variable 'v'", "bit range '" + range + "'", "no room for its " + width + " bits"});
  }
}

TEST_F(CaptureReaders, VcdTimestampAtTheEndOfThePicosecondRange) {
  const auto vcd = [&](const std::string& stamp) {
    return write("late.vcd", "$timescale 1 fs $end\n$var wire 1 ! a $end\n$enddefinitions $end\n#0\n0!\n" + stamp +
                                 "\n1!\n");
  };
  auto reader = capture::open_vcd(vcd("#9223372036854775307"));
  Change c;
  ASSERT_TRUE(reader->next(c));
  ASSERT_TRUE(reader->next(c));
  EXPECT_EQ(c.time, Time{INT64_MAX / 1000});
  EXPECT_EQ(c.value, '1');
  for (const std::string stamp : {"#9223372036854775308", "#9223372036854775807"}) {
    const std::string path = vcd(stamp);
    expect_mentions(vcd_signals_or_error(path), {path + ": line ", "timestamp '" + stamp + "' beyond the picosecond range"});
  }
}

// A time stamp is "#" and decimal digits, nothing else, up to the largest 64-bit value; each
// bad one is refused with its line and its text.
TEST_F(CaptureReaders, VcdBadTimestampsAreRefusedWithTheirLine) {
  for (const std::string stamp :
       {"#", "#12a", "#-5", "#+5", "#1.5", "#0x10", "#9223372036854775808", "#99999999999999999999"}) {
    const std::string path = write("stamp.vcd", "$timescale 1 ps $end\n$var wire 1 ! a $end\n$enddefinitions $end\n#0\n0!\n" +
                                                    stamp + "\n1!\n");
    SCOPED_TRACE(stamp);
    expect_mentions(vcd_signals_or_error(path), {path + ": line 6: ", "bad timestamp '" + stamp + "'"});
  }
  // Leading zeros are digits like any other.
  const std::string path = write("stamp.vcd", "$timescale 1 fs $end\n$var wire 1 ! a $end\n$enddefinitions $end\n#0\n0!\n"
                                              "#0009223372036854775307\n1!\n");
  auto reader = capture::open_vcd(path);
  Change c;
  ASSERT_TRUE(reader->next(c));
  ASSERT_TRUE(reader->next(c));
  EXPECT_EQ(c.time, Time{INT64_MAX / 1000});
}

// Every declared bit is kept by its full name. A header that asks for gigabytes of names with a
// few hundred kilobytes (5 000 vectors of 4 096 bits; 20 000 nested scopes, each name carrying the
// path before it) is refused at the variable that passes the budget, with its line, in well under
// a second; a header of 1 000 vectors of 64 bits is read.
TEST_F(CaptureReaders, AVcdHeaderWhoseNamesWouldTakeGigabytesIsRefusedWithItsLine) {
  const auto ident = [](std::size_t i) {
    std::string id;
    for (i += 1000; i != 0; i /= 94) id += static_cast<char>('!' + i % 94);
    return id;
  };
  const auto header = [&](std::size_t vars, unsigned width, bool nested) {
    std::string text = "$timescale 1ps $end\n$scope module endat $end\n$var wire 1 ! clock $end\n";
    for (std::size_t i = 0; i < vars; ++i) {
      if (nested) text += "$scope module s $end\n";
      text += "$var wire " + std::to_string(width) + " " + ident(i) + " v" + std::to_string(i) + " $end\n";
    }
    for (std::size_t i = 0; i < (nested ? vars : 0); ++i) text += "$upscope $end\n";
    return text + "$upscope $end\n$enddefinitions $end\n#0\n1!\n";
  };
  const auto started = std::chrono::steady_clock::now();
  expect_mentions(vcd_signals_or_error(write("wide.vcd", header(5000, 4096, false))),
                  {": line 333: variable 'v329': ", "64 MiB", "record the EnDat lines"});
  expect_mentions(vcd_signals_or_error(write("deep.vcd", header(20000, 1, true))), {"64 MiB", "one-bit names so far"});
  EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(20));  // a hang, not a speed
  const auto reader = capture::open_vcd(write("fine.vcd", header(1000, 64, false)));
  EXPECT_EQ(reader->signals().size(), 1U + 1000U * 64U);
}

// Tokens that run across the end of the reader's 64 KiB buffer: time stamps and value changes
// read as they do anywhere else, a word of the longest length is taken and one character more
// refused with its line, and a file cut inside a token is truncated.
TEST_F(CaptureReaders, VcdTokensAcrossTheBufferEnd) {
  const std::string head = "$timescale 1 ps $end\n$var wire 1 ! a $end\n$enddefinitions $end\n";
  // A comment of words that makes the file `size` bytes long, on one line.
  const auto up_to = [&](std::size_t size) {
    std::string text = head + "$comment";
    while (text.size() + 9 < size - 6) text += " cccccccc";
    text += std::string(size - 6 - text.size(), ' ') + " $end\n";
    return text;
  };
  for (std::size_t shift = 0; shift < 24; ++shift) {
    const std::string text = up_to(65536 - 12 + shift) + "#123456\n1!\n#123457\n0!\n";
    const std::string path = write("across.vcd", text);
    SCOPED_TRACE(shift);
    auto reader = capture::open_vcd(path);
    Change c;
    ASSERT_TRUE(reader->next(c));
    EXPECT_EQ(c.time, Time{123456});
    EXPECT_EQ(c.value, '1');
    ASSERT_TRUE(reader->next(c));
    EXPECT_EQ(c.time, Time{123457});
    EXPECT_EQ(c.value, '0');
    EXPECT_FALSE(reader->next(c));
  }
  for (std::size_t at : {std::size_t{200}, std::size_t{65536 - 2000}, std::size_t{65536 - 4000}}) {
    const std::string text = up_to(at);
    SCOPED_TRACE(at);
    const std::string ok = write("long.vcd", text + "$comment " + std::string(4096, 'w') + " $end\n#5\n1!\n");
    auto reader = capture::open_vcd(ok);
    Change c;
    ASSERT_TRUE(reader->next(c));
    EXPECT_EQ(c.time, Time{5});
    const std::string bad = write("too_long.vcd", text + "#1\n1!\n" + std::string(4097, '1') + "\n");
    expect_mentions(vcd_signals_or_error(bad), {bad + ": line 7: ", "a token longer than 4096 characters"});
  }
  const std::string cut = write("cut.vcd", up_to(65536 - 3) + "#12345");
  expect_mentions(vcd_signals_or_error(cut), {cut + ": line 5: ", "truncated: the file ends inside '#12345'"});
}

TEST_F(CaptureReaders, SaleaeTimeWithTwoExponentSignsIsRefused) {
  for (const std::string time : {"1e--5", "1e+-5", "1e-+5", "0.0000000000001e+-2147483648", "1e--2147483648", "1e-"}) {
    const std::string csv = write("signs.csv", "Time [s],a\n0,0\n" + time + ",1\n");
    SCOPED_TRACE(time);
    expect_mentions(error_of([&] { read_to_end(csv); }),
                    {csv + ": line 3: ", "time '" + time + "' is not a decimal number of seconds"});
  }
  const std::string csv = write("one_sign.csv", "Time [s],a\n0,0\n1.5e-6,1\n25E+0,0\n");
  auto reader = capture::open_csv(csv);
  Change c;
  std::vector<std::int64_t> times;
  while (reader->next(c)) times.push_back(c.time.count());
  EXPECT_EQ(times, (std::vector<std::int64_t>{0, 1'500'000, 25'000'000'000'000}));
}

// --- Signal names --------------------------------------------------------------------------

TEST_F(CaptureReaders, FindSignalNamesTheCandidates) {
  const std::string csv = write("names.csv", "Time [s],u1.clk,u2.clk,u1.data\n0,0,0,1\n");
  auto reader = capture::open(csv);
  EXPECT_EQ(capture::find_signal(*reader, "u2.clk"), 1u);
  EXPECT_EQ(capture::find_signal(*reader, "data"), 2u);
  expect_mentions(error_of([&] { capture::find_signal(*reader, "strobe"); }),
                  {csv + ": ", "no signal named 'strobe'", "u1.clk, u2.clk, u1.data"});
  expect_mentions(error_of([&] { capture::find_signal(*reader, "clk"); }),
                  {csv + ": ", "'clk' is ambiguous", "u1.clk, u2.clk"});
}

}  // namespace

namespace {

// One identifier under three names, as Icarus, Verilator and VCS declare a port and its net.
const char* const kAliasedVcd = R"($timescale 1 ns $end
$scope module tb $end
$var wire 1 ! clk $end
$var wire 2 " bus [1:0] $end
$scope module dut $end
$var wire 1 ! clock $end
$var wire 2 " data [5:4] $end
$scope module phy $end
$var wire 1 ! clk_in $end
$var wire 1 # enable $end
$upscope $end
$upscope $end
$upscope $end
$enddefinitions $end
#0
1!
b01 "
0#
#10
0!
)";

}  // namespace

TEST_F(CaptureReaders, EveryNameOfAVcdIdentifierSelectsItsSignal) {
  const std::string vcd = write("aliased.vcd", kAliasedVcd);
  auto reader = capture::open(vcd);
  EXPECT_EQ(reader->signals(), (std::vector<std::string>{"tb.clk", "tb.bus[1]", "tb.bus[0]", "tb.dut.phy.enable"}));
  for (const char* name : {"tb.clk", "clk", "dut.clock", "clock", "tb.dut.phy.clk_in", "clk_in"})
    EXPECT_EQ(capture::find_signal(*reader, name), 0U) << name;
  EXPECT_EQ(capture::find_signal(*reader, "dut.data[5]"), 1U);
  EXPECT_EQ(capture::find_signal(*reader, "data[4]"), 2U);
  // Changes of the identifier come as the one signal's, whichever name selected it.
  reader->select({capture::find_signal(*reader, "dut.clock")});
  Change c;
  std::vector<std::pair<std::int64_t, char>> seen;
  while (reader->next(c)) {
    EXPECT_EQ(c.signal, 0U);
    seen.emplace_back(c.time.count(), c.value);
  }
  EXPECT_EQ(seen, (std::vector<std::pair<std::int64_t, char>>{{0, '1'}, {10'000, '0'}}));
  // The candidates of a name that matches nothing, or several signals, include the aliases.
  expect_mentions(error_of([&] { capture::find_signal(*reader, "strobe"); }),
                  {vcd + ": ", "no signal named 'strobe'", "tb.dut.clock", "tb.dut.phy.clk_in", "tb.dut.data[5]"});
  expect_mentions(error_of([&] { capture::find_signal(*reader, "dut.data"); }), {vcd + ": ", "no signal named"});
  const std::string two = write("two.vcd", "$timescale 1 ns $end\n$scope module a $end\n$var wire 1 ! clk $end\n"
                                           "$upscope $end\n$scope module b $end\n$var wire 1 \" x $end\n"
                                           "$var wire 1 ! y $end\n$scope module c $end\n$var wire 1 \" clk $end\n"
                                           "$upscope $end\n$upscope $end\n$enddefinitions $end\n#0\n1!\n0\"\n");
  auto both = capture::open(two);
  expect_mentions(error_of([&] { capture::find_signal(*both, "clk"); }),
                  {two + ": ", "'clk' is ambiguous", "a.clk, b.c.clk"});
  EXPECT_EQ(capture::find_signal(*both, "b.y"), 0U);
  // An identifier declared again with another width is no alias.
  const std::string wide = write("wide.vcd", "$timescale 1 ns $end\n$var wire 1 ! a $end\n$var wire 2 ! b $end\n"
                                             "$enddefinitions $end\n#0\n1!\n");
  expect_mentions(error_of([&] { capture::open(wide); }), {wide + ": line 3: ", "variable 'b': 2 bits", "declared first with 1"});
}

// GHDL writes every VCD in femtoseconds and a vector's range into its name ("bus[3:0]"): each
// bit is found by its index, and times on whole picoseconds are exact until one is not.
TEST_F(CaptureReaders, GhdlVectorRangeInTheNameAndFemtosecondTimes) {
  const std::string vcd = write("ghdl.vcd", "$timescale 1 fs $end\n$scope module tb $end\n"
                                            "$var reg 4 ! bus[3:0] $end\n$var reg 1 \" clk $end\n"
                                            "$upscope $end\n$enddefinitions $end\n#0\nb0101 !\n1\"\n"
                                            "#2000\n0\"\n#2500\n1\"\n");
  auto reader = capture::open(vcd);
  EXPECT_EQ(reader->signals(), (std::vector<std::string>{"tb.bus[3]", "tb.bus[2]", "tb.bus[1]", "tb.bus[0]", "tb.clk"}));
  EXPECT_EQ(capture::find_signal(*reader, "bus[0]"), 3U);
  reader->select({capture::find_signal(*reader, "clk")});
  Change c;
  ASSERT_TRUE(reader->next(c));
  ASSERT_TRUE(reader->next(c));
  EXPECT_EQ(c.time, Time{2});
  EXPECT_EQ(reader->uncertainty(), Time::zero()) << "2000 fs is a whole picosecond";
  ASSERT_TRUE(reader->next(c));
  EXPECT_EQ(c.time, Time{3});  // 2.5 ps rounds to the nearest
  EXPECT_EQ(reader->uncertainty(), Time{1});
}

// Identifiers of one, two and three characters (a slot each for the short ones, a hash for the
// rest), tokens that straddle the reader's 64 KiB buffer, and every kind of separator a writer may
// use (space, tab, CR LF, form feed, NUL): each change reaches its signal at its time, and an error
// after the buffer's first refill names the right line.
TEST_F(CaptureReaders, VcdOfManyIdentifiersReadsTheSameAcrossItsBuffer) {
  std::vector<std::string> ids;
  for (char a = '!'; a <= '~' && ids.size() < 40; ++a) ids.emplace_back(1, a);
  for (char a = '!'; a <= '~' && ids.size() < 80; a = static_cast<char>(a + 7))
    for (char b = '!'; b <= '~' && ids.size() < 80; b = static_cast<char>(b + 11)) ids.push_back({a, b});
  for (char a = 'A'; ids.size() < 100; ++a) ids.push_back({a, '%', '~'});
  std::string text = "$timescale 1 ps $end\n$scope module top $end\n";
  Waveform want;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    text += "$var wire 1 " + ids[i] + " s" + std::to_string(i) + " $end\n";
    want["s" + std::to_string(i)];
  }
  text += "$upscope $end\n$enddefinitions $end\n";
  const std::array<std::string, 5> separators{" ", "\t", "\r\n", "\f", std::string(1, '\0')};
  std::vector<char> level(ids.size(), '?');
  for (std::int64_t t = 0; text.size() < 3 * 65536 + 1000; ++t) {
    text += "#" + std::to_string(t * 1000) + "\n";
    for (std::size_t k = 0; k < 7; ++k) {
      const std::size_t i = static_cast<std::size_t>(t * 7 + static_cast<std::int64_t>(k) * 13) % ids.size();
      const char v = level[i] == '1' ? '0' : '1';
      level[i] = v;
      want["s" + std::to_string(i)].push_back({t * 1000, v});
      text += std::string(1, v) + ids[i] + separators[(static_cast<std::size_t>(t) + k) % separators.size()];
    }
    text += "\n";
  }
  const auto lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  auto reader = capture::open(write("many.vcd", text));
  EXPECT_EQ(reader->signals().size(), ids.size());
  expect_same(want, read_all(*reader), Time{0}, "many identifiers");

  const std::string bad = write("bad.vcd", text + "1?!\n");  // never declared
  expect_mentions(error_of([&] { read_to_end(bad); }),
                  {bad + ": line " + std::to_string(lines + 1) + ": ", "undeclared identifier '?!'"});
}
