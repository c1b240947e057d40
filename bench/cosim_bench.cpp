// What attaching endatsim costs an HDL simulation: examples/hdl's master running its whole
// sequence (3 delay measurements, 8 position reads at 8 MHz over 50 m, a parameter read; about
// 5 ms simulated) once against its own behavioural encoder stub and once against endatsim through
// the VPI bridge, in Icarus Verilog and in GHDL; and the Verilated master inside endatsim.
// Each iteration is one whole simulation (a process for Icarus and GHDL), wall time.
//   build/bench/endatsim_cosim_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include "endatsim/cosim/bench.hpp"
#include "endat_master_run.hpp"
#include "endatsim/scenarios/loader.hpp"

namespace {

namespace fs = std::filesystem;
using namespace endatsim;

const std::string kSource = ENDATSIM_SOURCE_DIR;
const std::string kVpi = ENDATSIM_VPI_DIR;

// A private directory with every testbench compiled once.
class Compiled {
 public:
  Compiled() : dir_(fs::temp_directory_path() / ("endatsim_cosim_bench_" + std::to_string(::getpid()))) {
    fs::create_directories(dir_);
    const std::string v = kSource + "/examples/hdl/verilog/", h = kSource + "/examples/hdl/vhdl/";
    shell("iverilog -g2012 -s tb_stub -o stub.vvp " + v + "tb_stub.v " + v + "encoder_stub.v " + v + "endat_master.v");
    shell("iverilog -g2012 -s tb_endatsim -o endatsim.vvp " + v + "tb_endatsim.v " + v + "endat_master.v");
    shell("ghdl -a --std=08 " + h + "endat_master.vhd " + h + "encoder_stub.vhd " + h + "tb_stub.vhd " + h +
          "tb_endatsim.vhd && ghdl -e --std=08 tb_stub && ghdl -e --std=08 tb_endatsim");
  }
  ~Compiled() {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  void shell(const std::string& command) const {
    const std::string line = "cd " + dir_.string() + " && " + command + " > /dev/null 2>&1";
    if (std::system(line.c_str()) != 0) throw std::runtime_error("failed: " + command);
  }

 private:
  fs::path dir_;
};

const Compiled& compiled() {
  static const Compiled c;
  return c;
}

void run_process(benchmark::State& state, const std::string& command) {
  const auto& c = compiled();
  for (auto _ : state) c.shell(command);
}

void BM_Cosim_Icarus_Stub(benchmark::State& state) { run_process(state, "vvp -n stub.vvp"); }
void BM_Cosim_Icarus_Endatsim(benchmark::State& state) {
  run_process(state, "vvp -n -M " + kVpi + " -m endatsim_vpi endatsim.vvp +endatsim_config=" + kSource +
                         "/examples/hdl/verilog/cosim.json");
}
void BM_Cosim_GHDL_Stub(benchmark::State& state) { run_process(state, "ghdl -r --std=08 tb_stub"); }
void BM_Cosim_GHDL_Endatsim(benchmark::State& state) {
  run_process(state, "ghdl -r --std=08 tb_endatsim --vpi=" + kVpi + "/endatsim_vpi_ghdl.so +endatsim_config=" +
                         kSource + "/examples/hdl/vhdl/cosim.json");
}

// The Verilated master inside endatsim, in this process: the same sequence as above.
void BM_Cosim_Verilator_Endatsim(benchmark::State& state) {
  const auto bench_file = scenarios::load_scenario_file(kSource + "/examples/hdl/bench_8mhz_50m.json",
                                                        scenarios::ScenarioKind::Bench);
  for (auto _ : state) {
    cosim::Bench bench(bench_file);
    run_endat_master(bench);
    const auto r = bench.finish();
    if (!r.passed()) state.SkipWithError("the Verilated master did not pass");
    benchmark::DoNotOptimize(r.events);
  }
}

}  // namespace

BENCHMARK(BM_Cosim_Icarus_Stub)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Cosim_Icarus_Endatsim)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Cosim_GHDL_Stub)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Cosim_GHDL_Endatsim)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Cosim_Verilator_Endatsim)->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
