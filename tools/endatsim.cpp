// endatsim — command-line front end: runs scenarios and writes summaries, VCD and JSON results;
// sweeps one scenario over a grid of parameters and writes CSV, JSON and an SVG chart.
// Exit codes: 0 every expectation holds (sweep: the sweep ran), 1 one does not, 2 bad input or usage.
#include <unistd.h>

#include <boost/program_options.hpp>
#include <charconv>
#include <set>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include "scenarios/scenarios.hpp"
#include "scenarios/sweep.hpp"

namespace po = boost::program_options;
using namespace endatsim;

namespace {

constexpr int kPass = 0;
constexpr int kFail = 1;
constexpr int kBadInput = 2;

const char* const kUsage =
    "usage: endatsim run FILE... [--vcd PATH] [--json PATH] [--seed N] [--verbose|--quiet]\n"
    "       endatsim sweep FILE --grid POINTER=V1,V2,...|START:STOP:STEP [--grid ...] [--maximize POINTER]\n"
    "                      [--csv PATH] [--json PATH] [--svg PATH] [--jobs N] [--quiet]\n"
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

const char* const kSweepHelp =
    "sweep runs one scenario at every point of a grid: each --grid names a key by JSON pointer\n"
    "(/line/cable_length_m, /master/f_c, /master/delay_compensation, ...) and its values, parsed as\n"
    "JSON when they parse (numbers, true, false, \"quoted\", [...], {...}) and taken as strings\n"
    "otherwise (\"2 MHz\"); commas inside JSON strings, arrays and objects do not split values;\n"
    "START:STOP:STEP is a range. A pointer names an existing array element or a key of an existing\n"
    "object, and no pointer lies inside another. The grid is the Cartesian product; the output\n"
    "files are opened before it runs. A point is clean when the script finished, every read is ok\n"
    "and equals the encoder's position, and no check reported anything.\n"
    "--maximize POINTER prints, for each combination of the other keys, the largest clean value of\n"
    "POINTER; --svg draws it over the one other numeric key. Exit status: 0 when the sweep ran,\n"
    "2 for bad input (the message names the grid point) or usage.\n";

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

struct SweepArgs {
  std::string file;
  std::vector<std::string> grid;
  std::optional<std::string> maximize;
  std::optional<std::string> csv;
  std::optional<std::string> json;
  std::optional<std::string> svg;
  unsigned jobs = 1;
  bool quiet = false;
};

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write '" + path + "'");
}

scenarios::SweepOptions sweep_run_options(const SweepArgs& o) {
  scenarios::SweepOptions so;
  so.jobs = o.jobs;
  // A progress counter only where someone watches it: not in logs, pipes or CI.
  if (!o.quiet && isatty(STDERR_FILENO) != 0)
    so.progress = [](std::size_t done, std::size_t total) { std::cerr << "\r" << done << "/" << total << std::flush; };
  return so;
}

void write_sweep_outputs(const SweepArgs& o, const scenarios::Sweep& result,
                         const std::optional<scenarios::MaximumTable>& table) {
  if (o.csv) write_file(*o.csv, scenarios::sweep_csv(result));
  if (o.json) {
    auto j = scenarios::sweep_json(result, table ? &*table : nullptr);
    j["endatsim"] = ENDATSIM_VERSION;
    write_file(*o.json, j.dump(2) + "\n");
  }
  if (o.svg) write_file(*o.svg, scenarios::maximum_svg(result, *table));
}

// Every output path is opened before the sweep runs, so that a typo in a directory shows at
// once and not after all the points ran. Opened for appending, which leaves an existing file as
// it is; a file the probe created goes again.
void check_sweep_outputs(const SweepArgs& o) {
  namespace fs = std::filesystem;
  std::vector<std::pair<std::string, std::string>> outputs;  // option, path
  if (o.csv) outputs.emplace_back("--csv", *o.csv);
  if (o.json) outputs.emplace_back("--json", *o.json);
  if (o.svg) outputs.emplace_back("--svg", *o.svg);
  const auto same = [](const std::string& a, const std::string& b) {
    std::error_code ea, eb;
    const auto ca = fs::weakly_canonical(a, ea), cb = fs::weakly_canonical(b, eb);
    return ea || eb ? a == b : ca == cb;
  };
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const auto& [option, path] = outputs[i];
    for (std::size_t j = 0; j < i; ++j)
      if (same(outputs[j].second, path))
        throw std::runtime_error(outputs[j].first + " " + outputs[j].second + " and " + option + " " + path +
                                 ": the same file");
    if (same(o.file, path)) throw std::runtime_error(option + " " + path + ": that is the scenario file");
    std::error_code ec;
    const bool existed = fs::exists(path, ec);
    bool ok = false;
    {
      std::ofstream probe(path, std::ios::binary | std::ios::app);
      ok = static_cast<bool>(probe);
    }
    if (!ok) throw std::runtime_error(option + " " + path + ": cannot open the file for writing");
    if (!existed) fs::remove(path, ec);
  }
}

int sweep(const SweepArgs& o) {
  std::vector<scenarios::GridAxis> grid;
  for (const auto& g : o.grid) grid.push_back(scenarios::parse_grid_axis(g));
  const auto base = scenarios::read_scenario_json(o.file);
  scenarios::check_grid(base, o.file, grid);
  if (o.maximize) {
    // A bad --maximize or chart shape stops the sweep before it runs, not after.
    const scenarios::Sweep empty{o.file, "", grid, {}};
    const auto table = scenarios::maximize(empty, *o.maximize);
    if (o.svg) (void)scenarios::maximum_svg(empty, table);
  }
  check_sweep_outputs(o);
  const auto options = sweep_run_options(o);
  const auto result = scenarios::run_sweep(base, o.file, grid, options);
  if (options.progress) std::cerr << "\n";
  std::optional<scenarios::MaximumTable> table;
  if (o.maximize) table = scenarios::maximize(result, *o.maximize);
  write_sweep_outputs(o, result, table);
  const auto clean = std::count_if(result.points.begin(), result.points.end(), [](const auto& p) { return p.clean; });
  if (!o.quiet) std::cout << result.points.size() << " points, " << clean << " clean\n";
  if (table) std::cout << scenarios::maximum_text(result, *table);
  return kPass;
}

std::optional<unsigned> parse_jobs(const std::string& text) {
  unsigned jobs = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), jobs);
  if (ec != std::errc{} || end != text.data() + text.size() || jobs == 0 || jobs > 1024) return std::nullopt;
  return jobs;
}

// Options of the other command are usage errors, not silently ignored.
std::optional<std::string> foreign_option(const po::variables_map& vm, const std::string& command) {
  const std::vector<std::string> run_only{"vcd", "seed", "verbose"}, sweep_only{"grid", "maximize", "csv", "svg", "jobs"};
  for (const auto& name : command == "run" ? sweep_only : run_only)
    if (vm.count(name) != 0) return name;
  return std::nullopt;
}

int sweep_command(const po::variables_map& vm) {
  SweepArgs o;
  const auto files = vm.count("files") != 0 ? vm["files"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (files.size() != 1 || vm.count("grid") == 0) {
    std::cerr << "endatsim sweep: expected one scenario file and at least one --grid\n" << kUsage;
    return kBadInput;
  }
  o.file = files.front();
  o.grid = vm["grid"].as<std::vector<std::string>>();
  const auto string_option = [&](const char* name) -> std::optional<std::string> {
    if (vm.count(name) == 0) return std::nullopt;
    return vm[name].as<std::string>();
  };
  o.maximize = string_option("maximize");
  o.csv = string_option("csv");
  o.json = string_option("json");
  o.svg = string_option("svg");
  if (o.svg && !o.maximize) {
    std::cerr << "endatsim sweep: --svg draws the --maximize table; give --maximize POINTER\n";
    return kBadInput;
  }
  o.jobs = std::max(1U, std::thread::hardware_concurrency());
  if (vm.count("jobs") != 0) {
    const auto jobs = parse_jobs(vm["jobs"].as<std::string>());
    if (!jobs) {
      std::cerr << "endatsim sweep: --jobs expects an integer 1 .. 1024, got '" << vm["jobs"].as<std::string>() << "'\n";
      return kBadInput;
    }
    o.jobs = *jobs;
  }
  o.quiet = vm.count("quiet") != 0;
  return sweep(o);
}

int run_command(const po::variables_map& vm) {
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
  return run(o);
}

}  // namespace

int main(int argc, char** argv) {
  po::options_description common("Options");
  common.add_options()("help,h", "show this help")("version", "print the version")(
      "json", po::value<std::string>(), "write results as JSON to this file")(
      "quiet,q", "run: print only failing scenarios; sweep: no progress and no point count");
  po::options_description run_options("run");
  run_options.add_options()("vcd", po::value<std::string>(),
                            "write waveforms (VCD; a directory when several files are given)")(
      "seed", po::value<std::string>(), "override every scenario's seed (0 .. 2^64-1)")(
      "verbose,v", "list every frame and expectation");
  po::options_description sweep_options("sweep");
  sweep_options.add_options()("grid", po::value<std::vector<std::string>>(),
                              "POINTER=V1,V2,... or POINTER=START:STOP:STEP (repeat for more keys)")(
      "maximize", po::value<std::string>(), "print the largest clean value of this grid key per other combination")(
      "csv", po::value<std::string>(), "write one row per grid point to this file")(
      "svg", po::value<std::string>(), "write a chart of the --maximize table to this file")(
      "jobs", po::value<std::string>(), "threads (default: the number of cores)");
  po::options_description visible;
  visible.add(common).add(run_options).add(sweep_options);
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
    std::cout << kUsage << "\n" << kRunHelp << "\n" << kSweepHelp << visible;
    return kPass;
  }
  if (command != "run" && command != "sweep") {
    std::cerr << (command.empty() ? "endatsim: no command given\n" : "endatsim: unknown command '" + command + "'\n")
              << kUsage;
    return kBadInput;
  }
  if (const auto name = foreign_option(vm, command)) {
    std::cerr << "endatsim " << command << ": --" << *name << " is not an option of " << command << "\n" << kUsage;
    return kBadInput;
  }
  try {
    return command == "run" ? run_command(vm) : sweep_command(vm);
  } catch (const std::exception& e) {  // ScenarioError included: bad input
    std::cerr << "endatsim: " << e.what() << "\n";
    return kBadInput;
  }
}
