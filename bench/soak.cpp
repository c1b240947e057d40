// Soak benchmark (not in ctest): millions of frames through master, line, encoder and checker with
// random faults - clock jitter, disturbed mode bits (type I error handling), cable changes while
// running (scenario events) and delay re-measurements at random points - and the process's
// resident memory before, during and after, which must stay flat from one chunk to the next.
//
//   endatsim_soak                              2,000,000 frames in 20 chunks of 100,000
//   endatsim_soak --benchmark_filter=200k     the same with 2 chunks (a quick look)
//   endatsim_soak --benchmark_filter=Soak_10M  one run of 10,000,000 frames with random faults and a
//                                             violation on every frame, streamed as by run --json
//                                             --log --log-json: the resident memory at every
//                                             millionth frame must grow by less than 1 MiB
//                                             (Soak_2M_frames_flood: the same for 2,000,000)
//   endatsim_soak --benchmark_filter=Streamed  one run of 1,000,000 frames (16 MHz, 16 kHz) with its results file,
//                                             log and JSON lines written as it goes (what
//                                             `endatsim run --json --log --log-json` does): the
//                                             resident memory at every 100,000th frame
//
// Each iteration runs one chunk: a scenario drawn from a seeded generator (chunk i uses seed i,
// so a run is reproducible). Counters: frames and frame outcomes in all, median and slowest
// frames per wall second over the chunks, RSS after the first and the last chunk (MiB), the
// growth between them, and the peak RSS.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <ostream>
#include <random>
#include <streambuf>
#include <vector>

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include "endatsim/scenarios/junit.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/runner.hpp"
#include "endatsim/scenarios/streamed_outputs.hpp"

namespace {

namespace sim = endatsim::sim;
namespace scenarios = endatsim::scenarios;
namespace master = endatsim::master;
using sim::Time;

constexpr unsigned kFramesPerChunk = 100'000;

// Resident memory once freed heap pages went back to the system (malloc_trim), so that what
// is left is what the process still holds, not what glibc keeps cached from the last chunk.
double rss_mib() {
  malloc_trim(0);
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

// One chunk: kFramesPerChunk position reads in blocks, with faults drawn from `seed`.
scenarios::Scenario soak_scenario(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto pick = [&](std::uint64_t lo, std::uint64_t hi) { return std::uniform_int_distribution<std::uint64_t>(lo, hi)(rng); };
  scenarios::Scenario s;
  s.name = "soak_" + std::to_string(seed);
  s.seed = seed;
  s.max_time = sim::ms(60'000);
  const std::array<sim::Hertz, 3> f_cs{sim::MHz(2), sim::MHz(4), sim::MHz(8)};
  s.master.f_c = f_cs[pick(0, f_cs.size() - 1)];
  s.master.t_st = sim::us(2);
  s.master.delay_compensation = true;
  s.master.measurement.f_c = sim::kHz(200);
  s.master.measurement.f_e = 8 * s.master.f_c;
  // Up to a fifth of the shorter clock phase: sometimes harmless, sometimes a sampling error.
  s.master.jitter = sim::period_of(s.master.f_c) / 10 * static_cast<std::int64_t>(pick(0, 2)) / 2;
  s.line.cable_length_m = static_cast<double>(pick(0, 150));
  s.encoder.motion.start = pick(0, (1U << 25) - 1);
  s.encoder.motion.counts_per_s = static_cast<std::int64_t>(pick(0, 2'000'000)) - 1'000'000;
  s.encoder.t_m_short = sim::us(2);

  const Time cycle = sim::us(60);
  master::Operation measure;
  measure.kind = master::Operation::Kind::MeasureDelay;
  s.script.push_back(measure);
  unsigned frames = 0;
  while (frames < kFramesPerChunk) {
    master::Operation read;
    read.kind = master::Operation::Kind::ReadPosition;
    read.command = pick(0, 1) == 0 ? master::ModeCommand::EncoderSendPositionValues
                                   : master::ModeCommand::EncoderSendPositionValuesWithAdditionalData;
    read.count = std::min<unsigned>(static_cast<unsigned>(pick(200, 3000)), kFramesPerChunk - frames);
    read.cycle = cycle;
    s.script.push_back(read);
    frames += read.count;
    if (frames < kFramesPerChunk && pick(0, 2) == 0) {  // a disturbed mode command
      master::Operation bad = read;
      bad.count = 1;
      bad.mode_bits = static_cast<std::uint8_t>(pick(0, 63));
      s.script.push_back(bad);
      ++frames;
    }
    if (pick(0, 4) == 0) s.script.push_back(measure);  // re-measure t_D now and then
  }
  // Faults at random times within the expected run (a frame per cycle): glitches on either wire
  // at either end, power interruptions, cable changes; random bit errors throughout.
  const std::int64_t span = (cycle * kFramesPerChunk).count();
  std::vector<std::int64_t> at;
  for (std::uint64_t n = pick(5, 20); n > 0; --n) at.push_back(static_cast<std::int64_t>(pick(0, static_cast<std::uint64_t>(span))));
  std::sort(at.begin(), at.end());
  using K = scenarios::Event::Kind;
  scenarios::Event noise;  // random bit errors on DATA at the master end for the whole chunk
  noise.kind = K::RandomBitErrors;
  noise.at = Time::zero();
  noise.end = endatsim::line::ObservationPoint::MasterPins;
  noise.rate = 1e-4;
  s.events.push_back(noise);
  for (const auto t : at) {
    scenarios::Event e;
    e.at = Time{t};
    switch (pick(0, 3)) {
      case 0:
        e.kind = K::Glitch;
        e.wire = pick(0, 1) == 0 ? endatsim::line::Wire::Clock : endatsim::line::Wire::Data;
        e.end = pick(0, 1) == 0 ? endatsim::line::ObservationPoint::MasterPins : endatsim::line::ObservationPoint::EncoderPins;
        e.width = sim::ns(static_cast<std::int64_t>(pick(5, 200)));
        break;
      case 1:
        e.kind = K::PowerInterruption;
        e.duration = sim::us(static_cast<std::int64_t>(pick(10, 2000)));
        break;
      default:
        e.kind = K::SetCable;
        e.cable_length_m = static_cast<double>(pick(0, 150));
        e.cable_delay_per_m = sim::ns(5);
        break;
    }
    s.events.push_back(e);
  }
  return s;
}

void BM_Soak_RandomFaults(benchmark::State& state) {
  std::uint64_t chunk = 0, frames = 0, events = 0, violations = 0, unfinished = 0;
  std::array<std::uint64_t, 5> outcomes{};
  std::vector<double> rates;
  const double rss_start = rss_mib();
  double rss_first = 0, rss_last = 0;
  for (auto _ : state) {
    const scenarios::Scenario s = soak_scenario(++chunk);
    const auto t0 = std::chrono::steady_clock::now();
    std::uint64_t chunk_frames = 0;
    {
      const scenarios::ScenarioResult r = scenarios::run_scenario(s);
      for (const auto& f : r.frames) {
        if (f.measurement) continue;
        ++chunk_frames;
        ++outcomes[std::min<std::size_t>(static_cast<std::size_t>(f.outcome), outcomes.size() - 1)];
      }
      events += r.events;
      violations += r.violations.size();
      unfinished += r.finished ? 0 : 1;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    rates.push_back(static_cast<double>(chunk_frames) / wall);
    frames += chunk_frames;
    (chunk == 1 ? rss_first : rss_last) = rss_mib();
    if (std::getenv("ENDATSIM_SOAK_TRACE") != nullptr)
      std::fprintf(stderr, "chunk %llu: %llu frames, %.0f frames/s, rss %.1f MiB, peak %.1f MiB\n",
                   static_cast<unsigned long long>(chunk), static_cast<unsigned long long>(chunk_frames),
                   rates.back(), chunk == 1 ? rss_first : rss_last, peak_rss_mib());
  }
  if (rates.empty()) return;
  if (chunk == 1) rss_last = rss_first;
  std::sort(rates.begin(), rates.end());
  state.counters["frames"] = static_cast<double>(frames);
  state.counters["frames_per_s_median"] = rates[rates.size() / 2];
  state.counters["frames_per_s_min"] = rates.front();
  state.counters["events"] = static_cast<double>(events);
  state.counters["violations"] = static_cast<double>(violations);
  state.counters["ok"] = static_cast<double>(outcomes[0]);
  state.counters["crc_error"] = static_cast<double>(outcomes[1]);
  state.counters["no_start_bit"] = static_cast<double>(outcomes[2]);
  state.counters["type1_error"] = static_cast<double>(outcomes[3]);
  state.counters["other_error"] = static_cast<double>(outcomes[4]);
  state.counters["unfinished_chunks"] = static_cast<double>(unfinished);
  state.counters["rss_start_mib"] = rss_start;
  state.counters["rss_first_chunk_mib"] = rss_first;
  state.counters["rss_last_chunk_mib"] = rss_last;
  state.counters["rss_growth_mib"] = rss_last - rss_first;
  state.counters["peak_rss_mib"] = peak_rss_mib();
  if (frames != chunk * kFramesPerChunk) state.SkipWithError("a chunk lost frames: the script did not run to its end");
  else if (rss_last - rss_first > 64.0) state.SkipWithError("resident memory grew by more than 64 MiB between chunks");
}
BENCHMARK(BM_Soak_RandomFaults)->Name("Soak_2M_frames")->Iterations(20)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_Soak_RandomFaults)->Name("Soak_200k_frames")->Iterations(2)->Unit(benchmark::kSecond)->UseRealTime();

// Resident memory at every `every`-th frame of a run, as the frames are written out.
class RssProbe final : public scenarios::RunSink {
 public:
  explicit RssProbe(std::uint64_t every) : every_(every) {}
  void begin(const scenarios::ScenarioResult&) override {}
  void frame(const scenarios::ScenarioResult&, const master::FrameResult& f, std::span<const endatsim::checker::Violation>) override {
    if (f.index % every_ == every_ - 1) samples.push_back(rss_mib());
  }
  void end(const scenarios::ScenarioResult&) override {}
  std::vector<double> samples;

 private:
  std::uint64_t every_;
};

// What `endatsim run --json --log --log-json` writes while a run goes, into the streams given,
// and the run's options: `examples` frames and findings of each check kept (--examples, default
// 1000), limits out of the way.
struct StreamedRun {
  StreamedRun(std::ostream& json, std::ostream& log, std::ostream& jsonl, RssProbe& probe, std::size_t examples = 1000)
      : json_writer(json, "soak"), log_writer(log, scenarios::TransactionLogWriter::Format::Text),
        jsonl_writer(jsonl, scenarios::TransactionLogWriter::Format::JsonLines) {
    options.kept = examples;
    options.sinks = {&json_writer, &log_writer, &jsonl_writer, &probe};
    options.limits.kernel_events = UINT64_MAX;
    options.limits.script_frames = UINT64_MAX;
    options.limits.events = UINT64_MAX;
  }
  // Runs `s`, closes the results file and writes the JUnit file to `junit`.
  scenarios::ScenarioResult run(const scenarios::Scenario& s, std::ostream& junit) {
    scenarios::ScenarioResult r = scenarios::run_scenario(s, options);
    json_writer.finish(r.passed(), r.incomplete, {});
    r.frames = {};
    junit << scenarios::junit_xml({r}, "soak", {}, scenarios::JunitCases::Scenario);
    return r;
  }
  scenarios::ResultsJsonWriter json_writer;
  scenarios::TransactionLogWriter log_writer, jsonl_writer;
  scenarios::RunOptions options;
};

// The position loop of bench/scenarios/additional_data_loop_1s.json (EnDat 2.2 at 16 MHz over
// 10 m, additional data 2 and 1 every 62.5 us, an f_c warning on every frame) for 1,000,000
// reads: every frame and finding goes to the outputs, which keep 1000 of each in memory.
void BM_Streamed_1M_frames(benchmark::State& state) {
  constexpr unsigned kFrames = 1'000'000;
  scenarios::Scenario s = scenarios::load_scenario_file(ENDATSIM_SOURCE_DIR "/bench/scenarios/additional_data_loop_1s.json");
  s.script.back().count = kFrames;
  s.max_time = sim::ms(62'600);
  const std::string base = "/tmp/endatsim_soak_" + std::to_string(::getpid());
  double peak = 0, growth = 0, first = 0, last = 0;
  std::uint64_t frames = 0;
  for (auto _ : state) {
    RssProbe probe(100'000);
    {
      std::ofstream json(base + ".json"), log(base + ".log"), jsonl(base + ".jsonl"), junit(base + ".xml");
      frames = StreamedRun(json, log, jsonl, probe).run(s, junit).tally.frames();
    }
    if (probe.samples.size() < 2) {
      state.SkipWithError("fewer than 200,000 frames ran");
      break;
    }
    first = probe.samples.front();
    last = probe.samples.back();
    growth = last - first;
    peak = peak_rss_mib();
  }
  for (const char* ext : {".json", ".log", ".jsonl", ".xml"}) std::remove((base + ext).c_str());
  state.counters["frames"] = static_cast<double>(frames);
  state.counters["rss_at_100k_mib"] = first;
  state.counters["rss_at_1m_mib"] = last;
  state.counters["rss_growth_mib"] = growth;
  state.counters["peak_rss_mib"] = peak;
  if (frames < kFrames) state.SkipWithError("the script did not run to its end");
}
BENCHMARK(BM_Streamed_1M_frames)->Name("Streamed_1M_frames")->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

// Counts what it is given and keeps nothing: the outputs' formatting runs, without the disk.
class NullBuffer final : public std::streambuf {
 public:
  std::uint64_t bytes = 0;

 protected:
  int_type overflow(int_type c) override {
    ++bytes;
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char*, std::streamsize n) override {
    bytes += static_cast<std::uint64_t>(n);
    return n;
  }
};

// One run of `frames` reads at 8 MHz with the faults of soak_scenario spread over all of it
// (glitches, power interruptions, cable changes, random bit errors, disturbed mode commands,
// re-measurements of t_D) and a violation on every frame: t_ST of 1 us, half the 2 us that
// D297403 2.3.2 note 8 asks for at f_c of 2 to 8 MHz.
scenarios::Scenario flood_scenario(std::uint64_t frames, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto pick = [&](std::uint64_t lo, std::uint64_t hi) { return std::uniform_int_distribution<std::uint64_t>(lo, hi)(rng); };
  scenarios::Scenario s = soak_scenario(seed);
  s.name = "flood";
  s.master.f_c = sim::MHz(8);
  s.master.measurement.f_e = 8 * s.master.f_c;
  s.master.jitter = Time::zero();
  s.master.t_st = sim::us(1);
  s.line.cable_length_m = 20;
  const Time cycle = sim::us(40);
  s.max_time = cycle * static_cast<std::int64_t>(frames + frames / 100 + 1000);
  s.script.clear();
  master::Operation measure;
  measure.kind = master::Operation::Kind::MeasureDelay;
  s.script.push_back(measure);
  for (std::uint64_t done = 0; done < frames;) {
    master::Operation read;
    read.kind = master::Operation::Kind::ReadPosition;
    read.command = master::ModeCommand::EncoderSendPositionValues;
    read.count = static_cast<unsigned>(std::min<std::uint64_t>(pick(2'000, 20'000), frames - done));
    read.cycle = cycle;
    s.script.push_back(read);
    done += read.count;
    if (done < frames && pick(0, 2) == 0) {
      master::Operation bad = read;
      bad.count = 1;
      bad.mode_bits = static_cast<std::uint8_t>(pick(0, 63));
      s.script.push_back(bad);
      ++done;
    }
    if (pick(0, 4) == 0) s.script.push_back(measure);
  }
  // The faults of soak_scenario, one per 20,000 frames on average, at times over the whole run.
  std::vector<scenarios::Event> faults;
  for (const auto& e : s.events)
    if (e.kind != scenarios::Event::Kind::RandomBitErrors) faults.push_back(e);
  s.events.erase(std::remove_if(s.events.begin(), s.events.end(),
                                [](const auto& e) { return e.kind != scenarios::Event::Kind::RandomBitErrors; }),
                 s.events.end());
  s.events.front().rate = 1e-5;
  const std::int64_t span = (cycle * static_cast<std::int64_t>(frames)).count();
  std::vector<std::int64_t> at;
  for (std::uint64_t n = frames / 20'000; n > 0; --n) at.push_back(static_cast<std::int64_t>(pick(0, static_cast<std::uint64_t>(span))));
  std::sort(at.begin(), at.end());
  for (std::size_t i = 0; i < at.size() && !faults.empty(); ++i) {
    scenarios::Event e = faults[i % faults.size()];
    e.at = Time{at[i]};
    s.events.push_back(e);
  }
  return s;
}

// 10,000,000 reads in one run with random faults and a violation on every frame, every frame
// and finding formatted by the results file, the log and the JSON lines as `endatsim run
// --json --log --log-json --examples N` writes them (into a counter, not the disk), and a JUnit
// file at the end: resident memory at every millionth frame; it must not grow by 1 MiB from the
// first to the last. What is kept is bounded, but not filled at once: a check that fires rarely
// adds its examples (up to N) over the whole run, so with the default of 1000 the memory rises
// towards that bound for millions of frames (3.3 MiB over 10 million here); the benchmark keeps
// 100, which the rare checks of this run fill early.
void BM_Soak_Flood(benchmark::State& state) {
  const auto frames = static_cast<std::uint64_t>(state.range(0));
  const auto examples = static_cast<std::size_t>(state.range(1));
  const scenarios::Scenario s = flood_scenario(frames, 1);
  double first = 0, last = 0, peak = 0;
  std::uint64_t done = 0, findings = 0, bytes = 0;
  std::array<std::uint64_t, 5> outcomes{};
  for (auto _ : state) {
    RssProbe probe(1'000'000);
    NullBuffer null;
    std::ostream out(&null);
    const scenarios::ScenarioResult r = StreamedRun(out, out, out, probe, examples).run(s, out);
    done = r.tally.frames();
    for (const auto& [check, count] : scenarios::finding_counts(r.conformance)) findings += count;
    for (std::size_t o = 0; o < outcomes.size(); ++o) outcomes[o] = r.tally.outcomes[o];
    bytes = null.bytes;
    if (probe.samples.size() < 2) {
      state.SkipWithError("fewer than 2,000,000 frames ran");
      break;
    }
    first = probe.samples.front();
    last = probe.samples.back();
    peak = peak_rss_mib();
    // Every sample, for a run that fails the bound (its counters are not printed then).
    for (std::size_t i = 0; i < probe.samples.size(); ++i)
      std::fprintf(stderr, "frame %zu000000: rss %.3f MiB\n", i + 1, probe.samples[i]);
  }
  state.counters["frames"] = static_cast<double>(done);
  state.counters["findings"] = static_cast<double>(findings);
  state.counters["ok"] = static_cast<double>(outcomes[0]);
  state.counters["crc_error"] = static_cast<double>(outcomes[1]);
  state.counters["other_outcomes"] = static_cast<double>(outcomes[2] + outcomes[3] + outcomes[4]);
  state.counters["output_bytes"] = static_cast<double>(bytes);
  state.counters["rss_first_chunk_mib"] = first;
  state.counters["rss_last_chunk_mib"] = last;
  state.counters["rss_growth_mib"] = last - first;
  state.counters["peak_rss_mib"] = peak;
  if (done < frames) state.SkipWithError("the script did not run to its end");
  else if (findings < done) state.SkipWithError("fewer findings than frames: no flood");
  else if (last - first >= 1.0) state.SkipWithError("resident memory grew by 1 MiB or more from the first millionth frame to the last");
}
BENCHMARK(BM_Soak_Flood)->Name("Soak_10M_frames_flood")->Args({10'000'000, 100})->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();
BENCHMARK(BM_Soak_Flood)->Name("Soak_2M_frames_flood")->Args({2'000'000, 100})->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
