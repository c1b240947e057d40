// Throughput benchmarks.
//   --benchmark_filter=Kernel  synthetic workload on sim/ alone (clock bursts, delays, LFSR)
//   --benchmark_filter=Frame   full model: EnDat 2.2 position reads at 16 MHz, 10 m, checker on;
//                              Frame_AdditionalData: the same with additional data 1 and 2
//                              (bench/scenarios/additional_data_loop_1s.json, cut to 0.1 s)
// Rates are per wall-clock second (UseRealTime). sim_s_per_wall_s is simulated seconds per wall
// second; wall_s_per_sim_s is its reciprocal (the slowdown against real time).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "endatsim/scenarios/capture_check.hpp"
#include "endatsim/scenarios/declarations.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/runner.hpp"
#include "endatsim/sim/delay.hpp"
#include "endatsim/sim/kernel.hpp"
#include "endatsim/sim/signal.hpp"

namespace {

namespace sim = endatsim::sim;
namespace scenarios = endatsim::scenarios;
namespace master = endatsim::master;
using sim::Time;

double seconds(Time t) { return static_cast<double>(t.count()) * 1e-12; }

void report_sim_rate(benchmark::State& state, double sim_s_per_iteration) {
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(sim_s_per_iteration, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["wall_s_per_sim_s"] = benchmark::Counter(
      sim_s_per_iteration, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// ---- Kernel: master clock -> 500 ns -> encoder LFSR -> 10 ns -> 500 ns -> master sampling ----

constexpr Time kHalfPeriod = sim::ps(31'250);  // 16 MHz, 50 % duty
constexpr int kEdgesPerBurst = 2 * 60;
constexpr Time kBurstCycle = sim::ps(62'500'000);
constexpr Time kKernelSimTime = sim::ms(10);

class SyntheticLink {
 public:
  explicit SyntheticLink(sim::Kernel& kernel)
      : clock_master_(kernel, "clock_master", true),
        clock_encoder_(kernel, "clock_encoder", true),
        data_logic_(kernel, "data_logic", false),
        data_encoder_(kernel, "data_encoder", false),
        data_master_(kernel, "data_master", false),
        clock_cable_(kernel, clock_master_, clock_encoder_, sim::ns(500)),
        output_delay_(kernel, data_logic_, data_encoder_, sim::ns(10)),
        data_cable_(kernel, data_encoder_, data_master_, sim::ns(500)),
        edge_timer_(kernel, sim::bind<&SyntheticLink::clock_edge>(this)) {
    clock_encoder_.on_change(sim::bind<&SyntheticLink::encoder_edge>(this));
    clock_master_.on_change(sim::bind<&SyntheticLink::master_edge>(this));
    edge_timer_.start(Time::zero());
  }

  std::uint64_t checksum() const { return checksum_; }

 private:
  // CLOCK idles HIGH; a burst is 60 periods, the next one starts 62.5 us after this one did.
  void clock_edge() {
    clock_master_.write(!clock_master_.read());
    if (++edge_ < kEdgesPerBurst) {
      edge_timer_.start(kHalfPeriod);
    } else {
      edge_ = 0;
      edge_timer_.start(kBurstCycle - (kEdgesPerBurst - 1) * kHalfPeriod);
    }
  }

  void encoder_edge() {
    // 16-bit Galois LFSR, taps 16 14 13 11 (maximal length).
    const unsigned lsb = lfsr_ & 1u;
    lfsr_ = static_cast<std::uint16_t>((lfsr_ >> 1) ^ (lsb ? 0xB400u : 0u));
    data_logic_.write((lfsr_ & 1u) != 0);
  }

  void master_edge(std::uint64_t level) {
    if (level == 0) checksum_ = checksum_ * 0x100000001B3ull + (data_master_.read() ? 1u : 0u);
  }

  sim::Signal clock_master_, clock_encoder_, data_logic_, data_encoder_, data_master_;
  sim::TransportDelay clock_cable_, output_delay_, data_cable_;
  sim::Timer edge_timer_;
  int edge_ = 0;
  std::uint16_t lfsr_ = 0xACE1;
  std::uint64_t checksum_ = 0;
};

void BM_Kernel_Synthetic16MHzBursts(benchmark::State& state) {
  std::uint64_t events = 0;
  for (auto _ : state) {
    sim::Kernel kernel;
    SyntheticLink link(kernel);
    kernel.run(kKernelSimTime);
    std::uint64_t checksum = link.checksum();
    benchmark::DoNotOptimize(checksum);
    if (checksum == 0) {
      state.SkipWithError("checksum is zero: DATA never reached the master");
      break;
    }
    events = kernel.events_processed();
  }
  if (state.error_occurred()) return;
  report_sim_rate(state, seconds(kKernelSimTime));
  state.counters["events"] = static_cast<double>(events);
  state.counters["events_per_s"] =
      benchmark::Counter(static_cast<double>(events), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Kernel_Synthetic16MHzBursts)->UseRealTime()->Unit(benchmark::kMillisecond);

// ---- Frame: the full model, like scenarios/bundled/endat22_16mhz_20m_tst1us.json over 10 m ----

constexpr unsigned kFrames = 1600;  // 0.1 s of 62.5 us cycles

scenarios::Scenario frame_scenario() {
  scenarios::Scenario s;
  s.name = "bench_endat22_16mhz_10m_tst1us";
  s.seed = 4;
  s.line.cable_length_m = 10;
  s.encoder.version = endatsim::protocol::EndatVersion::V2_2;
  s.encoder.position_bits = 25;
  s.encoder.t_cal = sim::us(5);
  s.encoder.t_m_short = sim::us(2);
  s.encoder.motion.start = 7777;
  s.master.f_c = sim::MHz(16);
  s.master.t_st = sim::us(1);
  s.master.delay_compensation = true;
  s.master.position_bits = 25;
  s.master.measurement.f_c = sim::kHz(200);
  s.master.measurement.f_e = sim::MHz(128);
  s.master.measurement.count = 3;

  master::Operation measure;
  measure.kind = master::Operation::Kind::MeasureDelay;
  master::Operation read;
  read.kind = master::Operation::Kind::ReadPosition;
  read.command = master::ModeCommand::EncoderSendPositionValuesWithAdditionalData;
  read.count = kFrames;
  read.cycle = kBurstCycle;
  s.script = {measure, read};
  return s;
}

// The position loop of bench/scenarios/additional_data_loop_1s.json (additional data 2 and 1
// selected), cut to kFrames reads.
scenarios::Scenario additional_data_scenario() {
  scenarios::Scenario s = scenarios::load_scenario_file(ENDATSIM_SOURCE_DIR "/bench/scenarios/additional_data_loop_1s.json");
  s.script.back().count = kFrames;
  s.max_time = sim::ms(101);
  return s;
}

// The Frame benchmarks run every edge as an event (Engine::Event), unless `fast` (the default of
// the command line): frames that repeat are played from recordings (scenarios/frame_replay.hpp).
void run_frames(benchmark::State& state, const scenarios::Scenario& scenario, bool vcd, bool fast = false,
                unsigned frames = kFrames, scenarios::RunOptions options = {}) {
  options.engine = fast ? scenarios::Engine::Auto : scenarios::Engine::Event;
  if (vcd) options.vcd_path = "/tmp/endatsim_bench_" + std::to_string(::getpid()) + ".vcd";

  double simulated_s = 0;
  std::uint64_t events = 0;
  for (auto _ : state) {
    const scenarios::ScenarioResult r = scenarios::run_scenario(scenario, options);
    // Every frame but the delay measurement's read Ok, the reads among them (counted, whatever was kept).
    const std::uint64_t ok = r.tally.outcome(master::FrameOutcome::Ok);
    if (!r.finished || ok != r.tally.frames() || ok < frames) {
      state.SkipWithError("not every ReadPosition frame was read Ok");
      break;
    }
    simulated_s = seconds(r.simulated);
    events = r.events;
  }
  if (vcd) {
    std::error_code ec;
    if (!state.error_occurred())
      state.counters["vcd_bytes"] = static_cast<double>(std::filesystem::file_size(*options.vcd_path, ec));
    std::filesystem::remove(*options.vcd_path, ec);
  }
  if (state.error_occurred()) return;
  state.counters["frames_per_s"] = benchmark::Counter(frames, benchmark::Counter::kIsIterationInvariantRate);
  report_sim_rate(state, simulated_s);
  state.counters["events"] = static_cast<double>(events);
}

void BM_Frame_EnDat22_16MHz_10m(benchmark::State& state, bool vcd, bool fast) { run_frames(state, frame_scenario(), vcd, fast); }
BENCHMARK_CAPTURE(BM_Frame_EnDat22_16MHz_10m, no_vcd, false, false)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame_EnDat22_16MHz_10m, vcd, true, false)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame_EnDat22_16MHz_10m, fast_no_vcd, false, true)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame_EnDat22_16MHz_10m, fast_vcd, true, true)->UseRealTime()->Unit(benchmark::kMillisecond);

void BM_Frame_AdditionalData_EnDat22_16MHz_10m(benchmark::State& state, bool vcd, bool fast) {
  run_frames(state, additional_data_scenario(), vcd, fast);
}
BENCHMARK_CAPTURE(BM_Frame_AdditionalData_EnDat22_16MHz_10m, no_vcd, false, false)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame_AdditionalData_EnDat22_16MHz_10m, vcd, true, false)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame_AdditionalData_EnDat22_16MHz_10m, fast_no_vcd, false, true)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Frame_AdditionalData_EnDat22_16MHz_10m, fast_vcd, true, true)->UseRealTime()->Unit(benchmark::kMillisecond);

// ---- Loop: the one-second loop of bench/scenarios/additional_data_loop_1s.json for 10 s, through
// the fast path (the command line's default), without outputs ----

constexpr unsigned kLoopFrames = 160'000;

void BM_Loop_AdditionalData_10s_fast(benchmark::State& state) {
  scenarios::Scenario s = scenarios::load_scenario_file(ENDATSIM_SOURCE_DIR "/bench/scenarios/additional_data_loop_1s.json");
  s.script.back().count = kLoopFrames;
  s.max_time = sim::ms(10'010);
  // As `endatsim run` with raised limits and its default --examples 1000.
  scenarios::RunOptions options;
  options.kept = 1000;
  options.limits.kernel_events = UINT64_MAX;
  options.limits.script_frames = UINT64_MAX;
  options.limits.records = UINT64_MAX;
  run_frames(state, s, false, true, kLoopFrames, options);
}
BENCHMARK(BM_Loop_AdditionalData_10s_fast)->UseRealTime()->Unit(benchmark::kMillisecond);

// ---- Check: the same 0.1 s read back from its VCD and judged from the wires (endatsim check) ----

void BM_Check_Capture_EnDat22_16MHz_10m(benchmark::State& state) {
  const scenarios::Scenario scenario = frame_scenario();
  scenarios::RunOptions options;
  options.vcd_path = "/tmp/endatsim_bench_check_" + std::to_string(::getpid()) + ".vcd";
  scenarios::run_scenario(scenario, options);
  scenarios::CaptureCheckOptions o;
  o.file = *options.vcd_path;
  o.clock = "encoder_clock";
  o.data = "encoder_data";
  o.data_enable = "encoder_data_driver_enable";
  o.encoder = scenarios::declared_encoder(scenario.encoder);
  o.encoder.output_delay = scenario.line.encoder.receiver_delay + scenario.encoder.output_delay + scenario.line.encoder.driver_delay;
  std::size_t frames = 0;
  for (auto _ : state) {
    const auto r = scenarios::check_capture(o);
    frames = r.frames.size();
    if (!r.conforms()) {
      state.SkipWithError("the capture of a clean run does not conform");
      break;
    }
  }
  std::error_code ec;
  std::filesystem::remove(*options.vcd_path, ec);
  if (state.error_occurred()) return;
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_Check_Capture_EnDat22_16MHz_10m)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
