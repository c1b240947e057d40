#include "endatsim/cosim/main.hpp"

#include <charconv>
#include <iostream>
#include <stdexcept>
#include <string>

#include "endatsim/cosim/report.hpp"
#include "endatsim/scenarios/exit_status.hpp"
#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/limits.hpp"
#include "endatsim/scenarios/loader.hpp"
#include "endatsim/scenarios/output_file.hpp"

namespace endatsim::cosim {
namespace {

constexpr const char* kUsage =
    "usage: PROGRAM BENCH.json [--json FILE] [--junit FILE] [--log FILE] [--vcd FILE] [--seed N] [--verbose]\n"
    "       [--max-time TIME] [--max-kernel-events N] [--max-records N]";

struct MainOptions {
  std::string bench;
  OutputPaths outputs;
  BenchOptions bench_options;
  bool verbose = false;
};

MainOptions parse(int argc, const char* const* argv) {
  MainOptions o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value; " + kUsage);
      return argv[++i];
    };
    if (arg == "--json") o.outputs.json = value();
    else if (arg == "--junit") o.outputs.junit = value();
    else if (arg == "--log") o.outputs.log = value();
    else if (arg == "--vcd") o.bench_options.vcd_path = value();
    else if (arg == "--verbose") o.verbose = true;
    else if (arg == "--max-time" || arg == "--max-kernel-events" || arg == "--max-records")
      scenarios::set_limit(o.bench_options.limits, arg.substr(2), value());
    else if (arg == "--seed") {
      const std::string s = value();
      std::uint64_t seed = 0;
      const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), seed);
      if (ec != std::errc{} || end != s.data() + s.size() || s.empty())
        throw std::invalid_argument("--seed " + s + ": expected a whole number");
      o.bench_options.seed = seed;
    } else if (!arg.empty() && arg[0] == '-') throw std::invalid_argument("unknown option " + arg + "; " + kUsage);
    else if (o.bench.empty()) o.bench = arg;
    else throw std::invalid_argument("one bench file, not also " + arg + "; " + kUsage);
  }
  if (o.bench.empty()) throw std::invalid_argument(std::string("no bench file given; ") + kUsage);
  return o;
}

}  // namespace

namespace {

int run_bench(int argc, const char* const* argv, const std::function<void(Bench&)>& drive) {
  scenarios::install_interrupt_handlers();
  MainOptions o;
  scenarios::Scenario bench_file;
  try {
    o = parse(argc, argv);
    bench_file = scenarios::load_scenario_file(o.bench, scenarios::ScenarioKind::Bench);
    check_outputs(o.bench, o.outputs, o.bench_options.vcd_path, "--");
  } catch (const std::exception& e) {
    std::cerr << "endatsim: " << e.what() << std::endl;
    return scenarios::exit_status::kBadInput;
  }
  try {
    Bench bench(bench_file, o.bench_options);
    drive(bench);
    return report(bench.finish(), o.outputs, o.verbose, std::cout, std::cerr);
  } catch (const std::exception& e) {  // an output that cannot be opened, a model that cannot be connected
    std::cerr << "endatsim: " << e.what() << std::endl;
    return scenarios::exit_status::kBadInput;
  }
}

}  // namespace

int run_bench_program(int argc, const char* const* argv, const std::function<void(Bench&)>& drive) {
  scenarios::CheckedStdout out(argc > 0 ? argv[0] : "endatsim");
  return out.finish(run_bench(argc, argv, drive));
}

}  // namespace endatsim::cosim
