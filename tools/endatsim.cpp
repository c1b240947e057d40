// endatsim — command-line front end: runs scenarios and writes summaries, VCD and JSON results.
// Exit codes: 0 every expectation holds, 1 one does not, 2 bad input or usage.
#include <boost/program_options.hpp>
#include <charconv>
#include <set>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "scenarios/scenarios.hpp"

namespace po = boost::program_options;
using namespace endatsim;

namespace {

constexpr int kPass = 0;
constexpr int kFail = 1;
constexpr int kBadInput = 2;

const char* const kUsage =
    "usage: endatsim run FILE... [--vcd PATH] [--json PATH] [--seed N] [--verbose|--quiet]\n"
    "       endatsim --help | --version\n";

const char* const kRunHelp =
    "Runs EnDat scenarios (JSON files) through the cycle-accurate model of master, line and\n"
    "encoder, checks the timing conditions of spec 2.3.2 and judges each scenario's expectations.\n"
    "\n"
    "Prints a summary per scenario on stdout: frames and their outcomes, positions, CRC errors,\n"
    "the measured propagation delay t_D, timing violations (time, measured value, limit, spec\n"
    "section) and every expectation that failed.\n"
    "\n"
    "Exit status: 0 when every expectation of every scenario holds, 1 when one does not,\n"
    "2 for bad input (the message names the file, the JSON path and what was expected) or usage.\n";

struct Options {
  std::vector<std::string> files;
  std::optional<std::string> vcd;
  std::optional<std::string> json;
  std::optional<std::uint64_t> seed;
  bool verbose = false;
  bool quiet = false;
};

std::string output_path(const std::string& base, const std::string& name, const std::string& ext, bool many) {
  if (!many) return base;
  std::filesystem::create_directories(base);
  return (std::filesystem::path(base) / (name + ext)).string();
}

int run(const Options& o) {
  std::vector<scenarios::Scenario> loaded;
  std::set<std::string> names;
  for (const auto& file : o.files) {
    loaded.push_back(scenarios::load_scenario_file(file));
    if (!names.insert(loaded.back().name).second && o.vcd)
      throw scenarios::ScenarioError(file + ": at /name: another scenario is also named \"" + loaded.back().name +
                                     "\"; their waveforms would overwrite each other in " + *o.vcd);
  }
  const bool many = loaded.size() > 1;
  nlohmann::json all = nlohmann::json::array();
  bool passed = true;
  for (const auto& s : loaded) {
    scenarios::RunOptions ro;
    ro.seed = o.seed;
    if (o.vcd) ro.vcd_path = output_path(*o.vcd, s.name, ".vcd", many);
    const auto result = scenarios::run_scenario(s, ro);
    passed = passed && result.passed();
    if (!o.quiet || !result.passed()) scenarios::write_summary(std::cout, result, o.verbose);
    all.push_back(scenarios::to_json(result));
  }
  if (o.json) {
    std::ofstream out(*o.json);
    out << nlohmann::json{{"endatsim", ENDATSIM_VERSION}, {"passed", passed}, {"scenarios", all}}.dump(2) << "\n";
    if (!out) throw std::runtime_error("cannot write '" + *o.json + "'");
  }
  if (!o.quiet) std::cout << (passed ? "all scenarios passed" : "some scenarios failed") << "\n";
  return passed ? kPass : kFail;
}

}  // namespace

int main(int argc, char** argv) {
  po::options_description visible("Options");
  visible.add_options()("help,h", "show this help")("version", "print the version")(
      "vcd", po::value<std::string>(), "write waveforms (VCD; a directory when several files are given)")(
      "json", po::value<std::string>(), "write results as JSON to this file")(
      "seed", po::value<std::string>(), "override every scenario's seed (0 .. 2^64-1)")("verbose,v", "list every frame and expectation")(
      "quiet,q", "print only failing scenarios");
  po::options_description hidden;
  hidden.add_options()("command", po::value<std::string>())("files", po::value<std::vector<std::string>>());
  po::options_description all;
  all.add(visible).add(hidden);
  po::positional_options_description positional;
  positional.add("command", 1).add("files", -1);

  po::variables_map vm;
  try {
    po::store(po::command_line_parser(argc, argv).options(all).positional(positional).run(), vm);
    po::notify(vm);
  } catch (const po::error& e) {
    std::cerr << "endatsim: " << e.what() << "\n" << kUsage;
    return kBadInput;
  }
  if (vm.count("version") != 0) {
    std::cout << "endatsim " << ENDATSIM_VERSION << "\n";
    return kPass;
  }
  const std::string command = vm.count("command") != 0 ? vm["command"].as<std::string>() : "";
  if (vm.count("help") != 0) {
    std::cout << kUsage << "\n" << kRunHelp << "\n" << visible;
    return kPass;
  }
  if (command != "run") {
    std::cerr << (command.empty() ? "endatsim: no command given\n" : "endatsim: unknown command '" + command + "'\n")
              << kUsage;
    return kBadInput;
  }
  Options o;
  if (vm.count("files") != 0) o.files = vm["files"].as<std::vector<std::string>>();
  if (o.files.empty()) {
    std::cerr << "endatsim run: no scenario file given\n" << kUsage;
    return kBadInput;
  }
  if (vm.count("vcd") != 0) o.vcd = vm["vcd"].as<std::string>();
  if (vm.count("json") != 0) o.json = vm["json"].as<std::string>();
  if (vm.count("seed") != 0) {
    const std::string text = vm["seed"].as<std::string>();
    std::uint64_t seed = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), seed);
    if (ec != std::errc{} || end != text.data() + text.size()) {
      std::cerr << "endatsim run: --seed expects an integer 0 .. 18446744073709551615, got '" << text << "'\n";
      return kBadInput;
    }
    o.seed = seed;
  }
  o.verbose = vm.count("verbose") != 0;
  o.quiet = vm.count("quiet") != 0;
  try {
    return run(o);
  } catch (const scenarios::ScenarioError& e) {
    std::cerr << "endatsim: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "endatsim: " << e.what() << "\n";
    return kBadInput;
  }
}
