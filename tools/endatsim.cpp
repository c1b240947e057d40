// endatsim — command-line front end: runs scenarios and writes summaries, VCD, JSON and JUnit
// results and decoded transaction logs; sweeps one scenario over a grid of parameters (CSV,
// JSON, SVG chart); validates scenario files; draws frame diagrams (SVG); prints the timing table.
// Results go to stdout, errors and progress to stderr; colour only on a terminal.
// Exit codes: 0 every expectation holds (sweep, validate, diagram: done), 1 one does not,
// 2 bad input or usage, 3 a limit ended a run early (its results are marked incomplete),
// 128 + N interrupted by signal N (130 SIGINT, 143 SIGTERM; the outputs say incomplete or are removed).
#include <unistd.h>

#include <boost/program_options.hpp>
#include <charconv>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <chrono>
#include <filesystem>
#include <future>
#include <iomanip>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "endatsim/capture/capture.hpp"
#include "endatsim/input/json_input.hpp"
#include "endatsim/input/suggest.hpp"
#include "endatsim/slave/profile.hpp"
#include "endatsim/protocol/timing.hpp"
#include "endatsim/scenarios/decoder_tables.hpp"
#include "endatsim/scenarios/declarations.hpp"
#include "endatsim/scenarios/diagram.hpp"
#include "endatsim/scenarios/parameter_docs.hpp"
#include "endatsim/scenarios/gtkw.hpp"
#include "endatsim/scenarios/interrupt.hpp"
#include "endatsim/scenarios/junit.hpp"
#include "endatsim/scenarios/output_file.hpp"
#include "endatsim/scenarios/merge.hpp"
#include "endatsim/scenarios/scenarios.hpp"
#include "endatsim/scenarios/shard.hpp"
#include "endatsim/scenarios/sweep.hpp"
#include "endatsim/scenarios/streamed_outputs.hpp"
#include "endatsim/scenarios/transaction_log.hpp"
#include "exit_status.hpp"

namespace po = boost::program_options;
using namespace endatsim;
using scenarios::StreamedFile;
using scenarios::write_file;

namespace {

using tools::kBadInput;
using tools::report_failure;
using scenarios::exit_status::kFail;
using scenarios::exit_status::kIncomplete;
using scenarios::exit_status::kPass;
constexpr int interrupted_status(int signal) { return scenarios::exit_status::interrupted(signal); }

const char* const kRunUsage =
    "usage: endatsim run FILE... [--vcd PATH [--gtkw]] [--json PATH] [--junit PATH [--junit-cases scenario|expectation]]\n"
    "                    [--log PATH] [--log-json PATH] [--examples N]\n"
    "                    [--seed N] [--engine auto|event|fast] [--shard K/N] [--verbose|--quiet] [--color auto|always|never]\n"
    "                    [--max-time TIME] [--max-kernel-events N] [--max-script-frames N] [--max-events N] [--max-records N]\n";
const char* const kSweepUsage =
    "usage: endatsim sweep FILE --grid POINTER=V1,V2,...|START:STOP:STEP [--grid ...] [--maximize POINTER]\n"
    "                      [--csv PATH] [--json PATH] [--svg PATH] [--jobs N] [--engine auto|event|fast] [--shard K/N]\n"
    "                      [--verbose|--quiet] [limits as run]\n";
const char* const kMergeUsage =
    "usage: endatsim merge PARTIAL... [--json PATH] [--junit PATH] [--log PATH] [--log-json PATH] [--quiet]\n"
    "       endatsim merge PARTIAL... [--csv PATH] [--json PATH] [--svg PATH] [--maximize POINTER] [--verbose|--quiet]\n";
const char* const kValidateUsage = "usage: endatsim validate FILE... [--quiet] [limits as run]\n";
const char* const kDiagramUsage =
    "usage: endatsim diagram FILE --svg PATH [--frame N | --from TIME --to TIME] [--seed N] [--quiet] [limits as run]\n";
const char* const kChecksUsage = "usage: endatsim checks [--json | --python]\n";
const char* const kParametersUsage = "usage: endatsim parameters [--schema]\n";
const char* const kCheckUsage =
    "usage: endatsim check FILE... --clock NAME (--data NAME | --data-out NAME --data-in NAME)\n"
    "                      [--data-enable NAME [--master-data-enable NAME [--master-data-enable-at encoder|master]]\n"
    "                      [--enable-active-low]] [--power NAME]\n"
    "                      [--encoder PROFILE|SCENARIO.json] [--clock-to-data TIME] [--t-st-reduced-for-cable]\n"
    "                      [--at encoder|master] [--cable LENGTH] [--t-d TIME] [--resolution TIME]\n"
    "                      [--json PATH] [--junit PATH] [--log PATH] [--verbose|--quiet]\n";

std::string usage() {
  return std::string(kRunUsage) + kSweepUsage + kMergeUsage + kValidateUsage + kDiagramUsage + kCheckUsage + kChecksUsage + kParametersUsage +
         "       endatsim --help | --version | COMMAND --help | COMMAND --version\n";
}

// Every command: an exception that no input can cause (a bug) exits with its own status.
#define ENDATSIM_INTERNAL_EXIT " 70 for an internal error (a bug: the message asks for a report).\n"

const char* const kRunHelp =
    "run: runs EnDat scenarios (JSON files) through the cycle-accurate model of master, line and\n"
    "encoder, checks the timing conditions of spec 2.3.2 and judges each scenario's expectations.\n"
    "\n"
    "Prints a summary per scenario on stdout: frames and their outcomes, positions, CRC errors,\n"
    "the measured propagation delay t_D, timing violations (time, measured value, limit, spec\n"
    "section) and every expectation that failed. A progress line (scenario, simulated time, frames, time left) goes to\n"
    "stderr when stderr is a terminal.\n"
    "--log writes the decoded transaction log (one line per frame: time, mode command, fields\n"
    "sent and received, CRC, additional data, outcome, violations), --log-json the same as JSON\n"
    "lines. --junit writes JUnit XML, one test case per scenario. For every output PATH - is stdout\n"
    "(one output at most; the summary then goes to stderr). A folder as FILE stands for every\n"
    "scenario (*.json) under it; --vcd PATH is a folder (NAME.vcd each) for several scenarios and\n"
    "whenever PATH exists as one or ends in /.\n"
    "Outputs are written while a scenario runs, and memory does not grow with its length: every\n"
    "frame goes to --json, --log and --log-json, every finding is counted (the conformance table,\n"
    "--junit), and the summary, --json's violations and --gtkw keep the first --examples N frames\n"
    "and findings of each check (default 1000).\n"
    "\n"
    "\n"
    "Limits: every run is bounded. --max-time caps each scenario's max_time; --max-kernel-events\n"
    "(default 20000000), --max-script-frames (frames and polls the script asks for, default 100000),\n"
    "--max-events (entries of the events list, default 1000) and --max-records (frames,\n"
    "measurements and violations kept, default 50000) grant what a scenario may use; its \"limits\"\n"
    "key may lower them. A file that asks for more is refused before anything runs (exit 2); a run\n"
    "that reaches a limit ends there, its results marked incomplete (exit 3).\n"
    "SIGINT or SIGTERM stops at the next event boundary: the outputs say incomplete (exit 128 + N).\n"
    "--shard K/N runs the K-th of N contiguous slices of the scenario files (every shard given the\n"
    "same FILE... and options) and marks each output as a partial; endatsim merge joins the N\n"
    "partials into the outputs of the whole run, byte for byte.\n"
    "Output paths are checked before anything runs: not an input, not given twice, not a directory\n"
    "or FIFO, writable; each output replaces its file only when complete.\n"
    "\n"
    "Exit status: 0 when every expectation of every scenario holds, 1 when one does not,\n"
    "2 for bad input (the message names the file, the JSON path and what was expected) or usage,\n"
    "3 when a limit ended a run, 130 (SIGINT) or 143 (SIGTERM) when interrupted," ENDATSIM_INTERNAL_EXIT;

const char* const kSweepHelp =
    "sweep: runs one scenario at every point of a grid: each --grid names a key by JSON pointer\n"
    "(/line/cable_length_m, /master/f_c, /master/delay_compensation, ...) and its values, parsed as\n"
    "JSON when they parse (numbers, true, false, \"quoted\", [...], {...}) and taken as strings\n"
    "otherwise (\"2 MHz\"); commas inside JSON strings, arrays and objects do not split values;\n"
    "START:STOP:STEP is a range. A pointer names an existing array element or a key of an existing\n"
    "object, and no pointer lies inside another. The grid is the Cartesian product; the output\n"
    "files are opened before it runs. A point is clean when the script finished, every read is ok\n"
    "and equals the encoder's position, and no check reported anything.\n"
    "--maximize POINTER prints, for each combination of the other keys, the largest clean value of\n"
    "POINTER; --svg draws it over the one other numeric key. --verbose lists every point. A\n"
    "progress counter goes to stderr when stderr is a terminal. Every point runs within the limits of\n"
    "run (--max-* options); a point that reaches one is not clean and marked incomplete in --json.\n"
    "--shard K/N loads and runs only the K-th of N contiguous slices of the grid's points and writes\n"
    "them to --json as a partial (no --csv, --svg or --maximize); endatsim merge joins the N\n"
    "partials and writes those outputs, byte for byte as the whole sweep would.\n"
    "Exit status: 0 when the sweep ran, 2 for bad input (the message names the grid point) or usage,\n"
    "3 when a limit ended a point's run, 128 + N when interrupted by signal N (the outputs are removed),\n"
    ENDATSIM_INTERNAL_EXIT;

const char* const kMergeHelp =
    "merge: joins the partial results that run --shard K/N or sweep --shard K/N wrote, one per\n"
    "shard, into the outputs of the whole run, byte for byte as an unsharded run writes them.\n"
    "PARTIAL... are the shards' output files in any order (a folder stands for every file in it):\n"
    "each says which shard of which run it is. Of a run: its --json, --junit, --log and --log-json\n"
    "files; each output asked for needs that file of every shard. Of a sweep: its --json files,\n"
    "from which --csv, --json, --svg and the --maximize table are written as sweep writes them.\n"
    "Partials of different runs, versions, options or numbers of shards are refused, naming them.\n"
    "Prints the run's verdict (a sweep: its point count and maximum table).\n"
    "Exit status: as the whole run's: 0 passed, 1 a scenario failed, 3 a shard's run was incomplete;\n"
    "2 for a partial that cannot be read or does not fit the others, or usage," ENDATSIM_INTERNAL_EXIT;

const char* const kValidateHelp =
    "validate: loads scenario files without running them, as run would, and prints 'valid FILE'\n"
    "for each good one on stdout; errors (file, JSON path, what was expected) go to stderr.\n"
    "The JSON Schema schema/scenario.schema.json describes the same format for editors. A file that\n"
    "asks for more than the limits (--max-* options, as run) grant is not valid.\n"
    "Exit status: 0 when every file is valid, 2 when one is not or for usage errors," ENDATSIM_INTERNAL_EXIT;

const char* const kDiagramHelp =
    "diagram: runs a scenario and draws one frame (--frame N, the index in the run's frame list,\n"
    "default the first frame that is not a delay measurement) or a time window (--from, --to)\n"
    "as an SVG timing diagram: CLOCK and DATA at the master's and the encoder's pins, driver\n"
    "enables, the master's sampling instants, the fields (mode bits, start bit, F1, F2, position,\n"
    "CRC), the timing parameters t_ST, t_cal, t_D and t_m as dimension arrows with their measured\n"
    "values, and the checker's violations in red. The same input gives the same bytes. The run's\n"
    "waveform goes through a temporary directory private to the process, removed afterwards.\n"
    "Exit status: 0 when the diagram was written, 2 for bad input or usage, 3 when a limit (as run)\n"
    "ended the run, 128 + N when interrupted by signal N (no diagram is written)," ENDATSIM_INTERNAL_EXIT;

const char* const kChecksHelp =
    "checks: prints the checker's timing table as Markdown: one row per check name (the names\n"
    "scenarios use under expect.violations) with its spec symbol, section, minimum, maximum, how\n"
    "it is read, where it is observed and whether the wires alone decide it or the master must\n"
    "declare its sampling. docs/checks.md is this output. --json prints, instead, the tables an\n"
    "EnDat decoder needs as data: frame positions, limits, mode commands, bit layouts, the CRC,\n"
    "additional data, MRS codes, these rows and the frame decoder's defaults; --python prints the\n"
    "same as the Python module tools/sigrok/endat/tables.py, which the sigrok decoder reads.\n"
    "Exit status: 0.\n";

const char* const kParametersHelp =
    "parameters: prints the scenario parameters defined as rows (key, type, range, default, spec\n"
    "section, meaning) as Markdown tables; docs/parameters.md is this output. --schema prints,\n"
    "instead, the JSON Schema properties these rows make, as schema/scenario.schema.json holds them.\n"
    "Exit status: 0.\n";

const char* const kCheckHelp =
    "check: judges a waveform recorded elsewhere against the timing conditions of spec 2.3.2, from\n"
    "the wires alone: a VCD from any HDL simulator, a sigrok session (.sr) as PulseView and\n"
    "sigrok-cli save it, or logic-analyzer CSV (sigrok-cli, Saleae Logic). CLOCK and DATA are the\n"
    "levels at the encoder's connector (signals by full name or an unambiguous suffix; a wrong\n"
    "name lists the candidates); --data-enable is the encoder's DATA driver enable, if recorded\n"
    "(without it t_z, t_OE and floating data are not observable); --master-data-enable the\n"
    "master's, taken at the same instants (with both, a bus contention shows), or one cable delay\n"
    "later with --master-data-enable-at master (recorded at the master's connector). Frames are found\n"
    "and decoded on the wires (mode command, payload, start bit, answer, CRC, additional data,\n"
    "command supplement); --encoder takes the encoder's declared position width, t_m and t_R\n"
    "from a profile or a scenario (default: the model's encoder), --clock-to-data its delay from\n"
    "CLOCK to DATA at the connector (default 60 ns). With --at master the signals are the levels\n"
    "at the master's connector: --cable gives the cable's length, and the encoder's bits are read\n"
    "one round trip (--t-d, default from --cable) after each rising edge; t_D is then judged, which\n"
    "a capture at the encoder's connector cannot show. --data-out, --data-in and --data-enable\n"
    "name an RTL master's data_out, data_in and data_oe (at the master: --cable is needed).\n"
    "--power names the encoder's supply (HIGH while powered): after each switch-on it shows, the\n"
    "power-on conditions of 2.3.3 are judged again.\n"
    "--log writes the decoded frames as they are found, --junit a test case per row of the timing\n"
    "table and capture; with several captures --json holds {\"captures\": [...]}, an unreadable\n"
    "one as {\"file\", \"error\"}. A scenario given as --encoder also gives its cable.\n"
    "Each finding counts against the spec envelope (what any compliant encoder may do), the\n"
    "declared encoder, or both; the verdict line says which. A limit closer to the measured value\n"
    "than the capture's resolution (the sample period of .sr and CSV; VCD times are exact unless\n"
    "--resolution says otherwise) is undecided, never passed or failed.\n"
    "Exit status: 0 when every row conforms, 1 when one is broken or undecided, 2 for bad input\n"
    "(a capture that cannot be read, or in which CLOCK never begins a frame) or usage, 128 + N when\n"
    "interrupted by signal N (the captures not judged are listed as such in --json and --junit),\n"
    ENDATSIM_INTERNAL_EXIT;

enum class Command { Run, Sweep, Merge, Validate, Diagram, Check, Checks, Parameters };

struct CommandInfo {
  Command command;
  const char* name;
  const char* usage;
  const char* help;
};

const CommandInfo kCommands[] = {
    {Command::Run, "run", kRunUsage, kRunHelp},
    {Command::Sweep, "sweep", kSweepUsage, kSweepHelp},
    {Command::Merge, "merge", kMergeUsage, kMergeHelp},
    {Command::Validate, "validate", kValidateUsage, kValidateHelp},
    {Command::Diagram, "diagram", kDiagramUsage, kDiagramHelp},
    {Command::Check, "check", kCheckUsage, kCheckHelp},
    {Command::Checks, "checks", kChecksUsage, kChecksHelp},
    {Command::Parameters, "parameters", kParametersUsage, kParametersHelp},
};

void add_limit_options(po::options_description& o) {
  o.add_options()("max-time", po::value<std::string>(), "cap each scenario's max_time (simulated)")(
      "max-kernel-events", po::value<std::string>(), "kernel events a run may take (default 20000000)")(
      "max-script-frames", po::value<std::string>(), "frames and polls a script may ask for (default 100000)")(
      "max-events", po::value<std::string>(), "entries a scenario's events list may have (default 1000)")(
      "max-records", po::value<std::string>(), "frames, measurements and violations a run may keep (default 50000)");
}

// What --quiet leaves out, for each command.
const char* quiet_help(Command c) {
  switch (c) {
    case Command::Run: return "print only the scenarios that fail: no progress, shard line or overall verdict";
    case Command::Sweep: return "print no progress, shard line or point count";
    case Command::Merge: return "print no summary and no note of partials given without their option";
    case Command::Validate: return "print nothing for a valid file";
    case Command::Diagram: return "print no caption";
    case Command::Check: return "print only the captures that do not conform, and no progress";
    default: return "accepted; this command prints only what it is asked for";
  }
}

// Each command's own options; --help, --version, --quiet everywhere.
po::options_description options_of(Command c) {
  po::options_description o(std::string("Options"));
  o.add_options()("help,h", "show this help")("version", "print the version")("quiet,q", quiet_help(c));
  switch (c) {
    case Command::Run:
      o.add_options()("verbose,v", "list every frame and expectation")(
          "vcd", po::value<std::string>(), "write waveforms (VCD; a directory when several files are given)")(
          "gtkw", "also write a GTKWave save file (.gtkw) beside each VCD, signals grouped by end")(
          "json", po::value<std::string>(), "write results as JSON to this file")(
          "junit", po::value<std::string>(), "write JUnit XML (one test case per scenario) to this file")(
          "junit-cases", po::value<std::string>(),
          "scenario (default): a JUnit test case per scenario; expectation: one per group of its expectations")(
          "log", po::value<std::string>(), "write the decoded transaction log (text; - for stdout)")(
          "log-json", po::value<std::string>(), "write the transaction log as JSON lines (- for stdout)")(
          "examples", po::value<std::string>(),
          "frames and findings of each check kept for the summary and --json's violations (default 1000; all are counted)")(
          "seed", po::value<std::string>(), "override every scenario's seed (0 .. 2^64-1)")(
          "engine", po::value<std::string>(),
          "auto (default): frames that repeat are played from recordings, with the same results; event: every edge as an "
          "event; fast: as auto, and say how many frames were played")(
          "shard", po::value<std::string>(), "run the K-th of N slices of the files; outputs are partials for merge")(
          "color", po::value<std::string>(), "auto (default: only on a terminal, not with NO_COLOR), always, never");
      add_limit_options(o);
      break;
    case Command::Sweep:
      o.add_options()("verbose,v", "list every grid point")(
          "grid", po::value<std::vector<std::string>>(), "POINTER=V1,V2,... or POINTER=START:STOP:STEP (repeat for more keys)")(
          "maximize", po::value<std::string>(), "print the largest clean value of this grid key per other combination")(
          "csv", po::value<std::string>(), "write one row per grid point to this file")(
          "json", po::value<std::string>(), "write the points as JSON to this file")(
          "svg", po::value<std::string>(), "write a chart of the --maximize table to this file")(
          "jobs", po::value<std::string>(), "threads (default: the number of cores)")(
          "engine", po::value<std::string>(), "auto (default) or fast: frames that repeat are played from recordings; event: every edge as an event")(
          "shard", po::value<std::string>(), "run the K-th of N slices of the grid; --json is a partial for merge");
      add_limit_options(o);
      break;
    case Command::Merge:
      o.add_options()("verbose,v", "a sweep: list every grid point")(
          "json", po::value<std::string>(), "write the whole run's (or sweep's) JSON results to this file")(
          "junit", po::value<std::string>(), "a run: write its JUnit XML to this file")(
          "log", po::value<std::string>(), "a run: write its transaction log (text)")(
          "log-json", po::value<std::string>(), "a run: write its transaction log as JSON lines")(
          "csv", po::value<std::string>(), "a sweep: write one row per grid point to this file")(
          "svg", po::value<std::string>(), "a sweep: write a chart of the --maximize table to this file")(
          "maximize", po::value<std::string>(), "a sweep: print the largest clean value of this grid key per other combination");
      break;
    case Command::Check:
      o.add_options()("verbose,v", "print every decoded frame and every violation")(
          "clock", po::value<std::string>(), "the CLOCK signal at the encoder's connector")(
          "data", po::value<std::string>(), "the DATA signal at the encoder's connector")(
          "data-enable", po::value<std::string>(), "the encoder's DATA driver enable, if recorded")(
          "master-data-enable", po::value<std::string>(),
          "the master's DATA driver enable, if recorded too (with --data-enable: bus contention)")(
          "master-data-enable-at", po::value<std::string>(),
          "where the master's enable was recorded: encoder (default: as the capture shows it) or master (moved by "
          "the cable's one-way delay, --cable)")(
          "enable-active-low", "the enable is LOW while the encoder drives")(
          "power", po::value<std::string>(), "the encoder's supply, HIGH while powered, if recorded")(
          "encoder", po::value<std::string>(), "the declared encoder: a profile or a scenario (JSON)")(
          "clock-to-data", po::value<std::string>(), "the encoder's CLOCK-to-DATA delay at its connector")(
          "t-st-reduced-for-cable", "accept a t_ST shorter than note 8 for a cable shorter than 100 m")(
          "junit", po::value<std::string>(), "write JUnit XML (a test case per row and capture) to this file")(
          "data-out", po::value<std::string>(), "an RTL master's data_out (with --data-in; --data-enable is its data_oe)")(
          "data-in", po::value<std::string>(), "an RTL master's data_in (with --data-out)")(
          "at", po::value<std::string>(), "where CLOCK and DATA were recorded: encoder (default) or master")(
          "cable", po::value<std::string>(), "the cable's length in metres (needed --at master)")(
          "t-d", po::value<std::string>(), "--at master: the round trip t_D (default from --cable)")(
          "resolution", po::value<std::string>(),
          "how far each edge may be from its true time (default: the sample period of .sr/CSV, exact for VCD)")(
          "json", po::value<std::string>(), "write the decoded frames and violations as JSON")(
          "log", po::value<std::string>(), "write the decoded frames, one line each (- for stdout)");
      break;
    case Command::Validate:
      add_limit_options(o);
      break;
    case Command::Checks:
      o.add_options()("json", "print the decoder tables as JSON")(
          "python", "print the decoder tables as the Python module of the sigrok decoder");
      break;
    case Command::Parameters:
      o.add_options()("schema", "print the JSON Schema properties of the parameters");
      break;
    case Command::Diagram:
      o.add_options()("svg", po::value<std::string>(), "write the diagram to this file (required)")(
          "frame", po::value<std::string>(), "index of the frame to draw")(
          "from", po::value<std::string>(), "start of a time window, e.g. \"1.2 ms\"")(
          "to", po::value<std::string>(), "end of the time window")(
          "seed", po::value<std::string>(), "override the scenario's seed");
      add_limit_options(o);
      break;
  }
  return o;
}

std::optional<std::uint64_t> parse_uint(const std::string& text) {
  std::uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return v;
}

// The --max-* options into `limits`; a message and false when one is not a number in range.
bool parse_limits(const po::variables_map& vm, const char* command, scenarios::Limits& limits) {
  for (const char* name : scenarios::kLimitNames) {
    if (vm.count(name) == 0) continue;
    try {
      scenarios::set_limit(limits, name, vm[name].as<std::string>());
    } catch (const std::invalid_argument& e) {
      std::cerr << "endatsim " << command << ": " << e.what() << "\n";
      return false;
    }
  }
  return true;
}

// Colour for the summary's verdicts, only where a person reads it (`fd`: where the summary goes).
bool use_color(const std::string& mode, int fd) {
  if (mode == "always") return true;
  if (mode == "never") return false;
  const char* no_color = std::getenv("NO_COLOR");
  return isatty(fd) != 0 && (no_color == nullptr || *no_color == '\0');
}

// Where the summary for a person goes: standard output, unless an output takes it ("--json -").
struct SummaryStream {
  explicit SummaryStream(const std::vector<scenarios::OutputPath>& outputs)
      : to_stderr(scenarios::writes_to_stdout(outputs)), stream(to_stderr ? std::cerr : std::cout) {}
  bool to_stderr;
  std::ostream& stream;
  int fd() const { return to_stderr ? STDERR_FILENO : STDOUT_FILENO; }
};

// Files named on the command line, in the order given; a folder stands for every file (not a
// folder) under it (`recursive`) or in it whose name ends in `extension` ("" for any), in path order.
// `kind` says what is looked for, for the message when a folder has none.
std::vector<std::string> files_named(const std::vector<std::string>& args, bool recursive, const std::string& extension,
                                     const std::string& kind) {
  std::vector<std::string> files;
  for (const auto& arg : args) {
    std::error_code ec;
    if (!std::filesystem::is_directory(arg, ec)) {
      files.push_back(arg);
      continue;
    }
    std::vector<std::string> found;
    // A file of the kind that cannot be read (a dangling link, a FIFO, a device) is taken too, so
    // that its reader refuses it by name: skipping it would drop a scenario from a CI run unseen.
    const auto take = [&](const std::filesystem::directory_entry& e) {
      std::error_code entry_ec;
      if ((extension.empty() || e.path().extension() == extension) && !e.is_directory(entry_ec))
        found.push_back(e.path().string());
    };
    if (recursive)
      for (std::filesystem::recursive_directory_iterator it(arg, ec), end; !ec && it != end; it.increment(ec)) take(*it);
    else
      for (std::filesystem::directory_iterator it(arg, ec), end; !ec && it != end; it.increment(ec)) take(*it);
    if (ec) throw std::runtime_error(arg + ": cannot read the folder: " + ec.message());
    if (found.empty()) throw std::runtime_error(arg + ": a folder with no " + kind);
    std::sort(found.begin(), found.end());
    files.insert(files.end(), found.begin(), found.end());
  }
  return files;
}

// Scenario files: a folder stands for every scenario (*.json) anywhere under it.
std::vector<std::string> scenario_files(const std::vector<std::string>& args) {
  return files_named(args, true, ".json", "scenario (*.json) in it or below it");
}

std::string colorize(const std::string& text) {
  const std::string red = "\033[31m", green = "\033[32m", yellow = "\033[33m", off = "\033[0m";
  std::istringstream in(text);
  std::string out, line;
  const std::vector<std::pair<std::string, std::string>> marks{
      {"PASS ", green}, {"FAIL ", red}, {"  FAIL ", red}, {"    error ", red}, {"    warning ", yellow}, {"  violation ", red}};
  while (std::getline(in, line)) {
    for (const auto& [prefix, colour] : marks) {
      if (line.rfind(prefix, 0) != 0) continue;
      const auto lead = prefix.find_first_not_of(' ');
      const auto word_end = prefix.size() - 1;
      line = line.substr(0, lead) + colour + line.substr(lead, word_end - lead) + off + line.substr(word_end);
      break;
    }
    out += line + "\n";
  }
  return out;
}

struct Options {
  std::vector<std::string> all_files;  // as named on the command line
  std::vector<std::string> files;      // what this process runs: all, or its shard's slice
  std::optional<scenarios::Shard> shard;
  std::optional<std::string> vcd;
  std::optional<std::string> json;
  std::optional<std::string> junit;
  std::optional<std::string> log;
  std::optional<std::string> log_json;
  std::optional<std::uint64_t> seed;
  bool gtkw = false;
  scenarios::Engine engine = scenarios::Engine::Auto;
  std::size_t examples = 1000;  // frames and findings per check kept in memory
  scenarios::JunitCases junit_cases = scenarios::JunitCases::Scenario;
  bool verbose = false;
  bool quiet = false;
  std::string color = "auto";
  scenarios::Limits limits;
};

std::string output_path(const std::string& base, const std::string& name, const std::string& ext, bool many) {
  if (!many) return base;
  std::filesystem::create_directories(base);
  return (std::filesystem::path(base) / (name + ext)).string();
}

// Runs one scenario while a line on stderr shows which one and, after a second, how far it has
// come: simulated time, frames, wall time, and the time left if the run goes on to its max_time
// (an upper bound: a script that finishes earlier ends the run sooner).
scenarios::ScenarioResult run_with_progress(const scenarios::Scenario& s, scenarios::RunOptions ro, std::size_t n,
                                            std::size_t total) {
  scenarios::RunProgress progress;
  ro.progress = &progress;
  auto future = std::async(std::launch::async, [&] { return scenarios::run_scenario(s, ro); });
  const auto begin = std::chrono::steady_clock::now();
  const std::string label = "[" + std::to_string(n) + "/" + std::to_string(total) + "] " + s.name;
  std::cerr << "\r\033[K" << label << std::flush;
  while (future.wait_for(std::chrono::milliseconds(250)) != std::future_status::ready) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    if (elapsed < 1.0) continue;
    const auto simulated = progress.simulated_ps.load(std::memory_order_relaxed);
    const auto end = progress.end_ps.load(std::memory_order_relaxed);
    std::ostringstream line;
    line << label << ": " << sim::format_time(sim::Time(simulated)) << " of " << sim::format_time(sim::Time(end))
         << " simulated, " << progress.frames.load(std::memory_order_relaxed) << " frames, " << std::fixed
         << std::setprecision(1) << elapsed << " s";
    if (simulated > 0 && end > simulated)
      line << ", at most " << elapsed * static_cast<double>(end - simulated) / static_cast<double>(simulated) << " s left";
    std::cerr << "\r\033[K" << line.str() << std::flush;
  }
  std::cerr << "\r\033[K" << std::flush;
  return future.get();
}

// Bad input found after the output paths were checked: what an earlier run left at those paths
// goes, so that no stale result looks like this run's (the paths are known not to be inputs).
template <class Load>
void load_or_clear_outputs(const char* command, const std::vector<scenarios::OutputPath>& outputs, Load load) {
  try {
    load();
  } catch (...) {
    const auto removed = scenarios::remove_outputs(outputs);
    if (!removed.empty()) {
      std::cerr << "endatsim " << command << ": no output written; removed the earlier";
      for (const auto& path : removed) std::cerr << " " << path;
      std::cerr << "\n";
    }
    throw;
  }
}

int run(const Options& o) {
  // --vcd names a folder (NAME.vcd for each scenario) for several scenarios, and whenever it
  // exists as one or ends in "/"; else the file.
  std::error_code ec;
  const bool vcd_folder = o.vcd && (o.all_files.size() > 1 || o.vcd->ends_with('/') || std::filesystem::is_directory(*o.vcd, ec));
  std::vector<scenarios::OutputPath> outputs;
  if (o.vcd) outputs.push_back({"--vcd", *o.vcd, vcd_folder});
  if (o.vcd && o.gtkw && *o.vcd == "-")
    throw std::runtime_error("--gtkw - : a GTKWave save file goes beside a VCD file; give --vcd a file or a folder");
  if (o.vcd && o.gtkw && !vcd_folder)
    outputs.push_back({"--gtkw", std::filesystem::path(*o.vcd).replace_extension(".gtkw").string()});
  if (o.json) outputs.push_back({"--json", *o.json});
  if (o.junit) outputs.push_back({"--junit", *o.junit});
  if (o.log) outputs.push_back({"--log", *o.log});
  if (o.log_json) outputs.push_back({"--log-json", *o.log_json});
  scenarios::check_output_paths(o.all_files, "a scenario file", outputs);
  std::vector<scenarios::Scenario> loaded;
  load_or_clear_outputs("run", outputs, [&] {
    std::set<std::string> names;
    for (const auto& file : o.files) {
      loaded.push_back(scenarios::load_scenario_file(file));
      (void)scenarios::resolve_limits(loaded.back(), o.limits);  // what the file shows, refused before anything runs
      if (!names.insert(loaded.back().name).second && o.vcd)
        throw scenarios::ScenarioError(file + ": at /name: another scenario is also named \"" +
                                       scenarios::trimmed(loaded.back().name) +
                                       "\"; their waveforms would overwrite each other in " + *o.vcd);
    }
  });
  const SummaryStream summary_out(outputs);
  const bool color = use_color(o.color, summary_out.fd());
  // Every file output opened before anything runs; each replaces its file only when complete.
  std::optional<StreamedFile> json_file, junit_file, log_file, log_json_file;
  if (o.json) json_file.emplace(*o.json);
  if (o.junit) junit_file.emplace(*o.junit);
  if (o.log) log_file.emplace(*o.log);
  if (o.log_json) log_json_file.emplace(*o.log_json);
  // Written while each scenario runs.
  std::optional<scenarios::ResultsJsonWriter> json_writer;
  std::optional<scenarios::TransactionLogWriter> log_writer, log_json_writer;
  std::vector<scenarios::RunSink*> sinks;
  if (json_file) sinks.push_back(&json_writer.emplace(json_file->stream(), ENDATSIM_VERSION));
  if (log_file) sinks.push_back(&log_writer.emplace(log_file->stream(), scenarios::TransactionLogWriter::Format::Text));
  if (log_json_file)
    sinks.push_back(&log_json_writer.emplace(log_json_file->stream(), scenarios::TransactionLogWriter::Format::JsonLines));
  // Progress only where someone watches it: not in logs, pipes or CI.
  const bool progress = !o.quiet && isatty(STDERR_FILENO) != 0;
  std::vector<scenarios::ScenarioResult> results;  // for --junit, without their frames
  std::vector<scenarios::NotRun> not_run;
  bool passed = true;
  std::string incomplete;  // the first reason a run ended early
  int interrupted = 0;
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    const auto& s = loaded[i];
    if (interrupted != 0 || scenarios::interrupt_signal() != 0) {
      interrupted = scenarios::interrupt_signal();
      not_run.push_back({s.file, s.name, "not run: interrupted by " + scenarios::signal_name(interrupted)});
      continue;
    }
    scenarios::RunOptions ro;
    ro.seed = o.seed;
    ro.limits = o.limits;
    ro.kept = o.examples;
    ro.sinks = sinks;
    ro.engine = o.engine;
    if (o.vcd) ro.vcd_path = output_path(*o.vcd, s.name, ".vcd", vcd_folder);
    ro.vcd_decoded = o.gtkw;  // the text trace is for GTKWave
    auto result = progress ? run_with_progress(s, ro, i + 1, loaded.size()) : scenarios::run_scenario(s, ro);
    // A GTKWave save file beside the VCD, opening on the first frame with markers at the violations.
    if (o.vcd && o.gtkw)
      write_file(std::filesystem::path(*ro.vcd_path).replace_extension(".gtkw").string(),
                 scenarios::gtkw_save_file(result, *ro.vcd_path));
    if (o.engine == scenarios::Engine::Fast)
      std::cerr << result.name << ": " << result.frames_replayed << " frames played from recordings\n";
    passed = passed && result.passed();
    if (!result.incomplete.empty() && incomplete.empty()) incomplete = result.name + ": " + result.incomplete;
    if (result.interrupted != 0) interrupted = result.interrupted;
    if (!o.quiet || !result.passed()) {
      std::ostringstream summary;
      scenarios::write_summary(summary, result, o.verbose);
      summary_out.stream << (color ? colorize(summary.str()) : summary.str()) << std::flush;
    }
    if (o.junit) {
      result.frames = {};
      result.encoder_frames = {};
      result.bus_frames = {};
      results.push_back(std::move(result));
    }
  }
  if (interrupted != 0 && incomplete.empty()) incomplete = "interrupted by " + scenarios::signal_name(interrupted);
  // A shard's outputs are partials: each ends with what `endatsim merge` needs to join them.
  std::optional<scenarios::ShardMark> mark;
  if (o.shard)
    mark = scenarios::ShardMark{ENDATSIM_VERSION, "run", *o.shard, scenarios::slice_of(*o.shard, o.all_files.size()).begin,
                                o.files.size(), o.all_files.size(), o.all_files,
                                scenarios::run_shard_options(o.seed, o.examples, o.limits, o.junit_cases),
                                passed && incomplete.empty(), incomplete, not_run};
  if (!incomplete.empty() && log_file) scenarios::TransactionLogWriter::write_incomplete(log_file->stream(), incomplete, not_run);
  if (!incomplete.empty() && log_json_file)
    scenarios::TransactionLogWriter::write_incomplete_json(log_json_file->stream(), incomplete, not_run);
  if (mark && log_file) log_file->stream() << scenarios::text_log_mark(*mark);
  if (mark && log_json_file) log_json_file->stream() << scenarios::json_lines_mark(*mark);
  if (junit_file) {
    junit_file->stream() << scenarios::junit_xml(results, "endatsim", not_run, o.junit_cases);
    if (mark) junit_file->stream() << scenarios::junit_mark(*mark);
    junit_file->commit();
  }
  if (json_file) {
    std::vector<std::string> files;
    for (const auto& n : not_run) files.push_back(n.file);
    const auto mark_json = mark ? std::optional(scenarios::to_json(*mark)) : std::nullopt;
    json_writer->finish(passed && incomplete.empty(), incomplete, files, mark_json ? &*mark_json : nullptr);
    json_file->commit();
  }
  if (log_file) log_file->commit();
  if (log_json_file) log_json_file->commit();
  if (mark && !o.quiet) {
    const auto slice = scenarios::slice_of(*o.shard, o.all_files.size());
    summary_out.stream << "shard " << o.shard->index << "/" << o.shard->count << ": "
                       << (slice.end == slice.begin ? std::string("no scenario file")
                                                    : "scenario files " + std::to_string(slice.begin + 1) + " to " +
                                                          std::to_string(slice.end))
                       << " of " << o.all_files.size() << "\n";
  }
  if (!o.quiet) {
    const std::string verdict = !incomplete.empty() ? "incomplete: " + incomplete
                                : passed            ? "all scenarios passed"
                                                    : "some scenarios failed";
    summary_out.stream << (color ? (passed && incomplete.empty() ? "\033[32m" : "\033[31m") + verdict + "\033[0m" : verdict) << "\n";
  }
  if (interrupted != 0) {
    std::cerr << "endatsim run: interrupted by " << scenarios::signal_name(interrupted) << "; the outputs say incomplete\n";
    return interrupted_status(interrupted);
  }
  if (!incomplete.empty()) {
    std::cerr << "endatsim run: " << incomplete << "\n";
    return kIncomplete;
  }
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
  std::optional<scenarios::Shard> shard;
  bool quiet = false;
  bool verbose = false;
  scenarios::Limits limits;
  scenarios::Engine engine = scenarios::Engine::Auto;
};

// --engine of run and sweep: false, after saying why, for a name it does not know.
bool engine_option(const std::optional<std::string>& text, const char* command, scenarios::Engine& engine) {
  if (!text) return true;
  const auto e = scenarios::engine_from(scenarios::trimmed(*text));
  if (!e) {
    std::cerr << "endatsim " << command << ": --engine expects auto, event or fast, got '" << scenarios::trimmed(*text) << "'\n";
    return false;
  }
  engine = *e;
  return true;
}

scenarios::SweepOptions sweep_run_options(const SweepArgs& o) {
  scenarios::SweepOptions so;
  so.jobs = o.jobs;
  so.limits = o.limits;
  so.engine = o.engine;
  // A progress counter only where someone watches it: not in logs, pipes or CI.
  if (!o.quiet && isatty(STDERR_FILENO) != 0)
    so.progress = [](std::size_t done, std::size_t total) { std::cerr << "\r" << done << "/" << total << std::flush; };
  return so;
}

void write_sweep_outputs(const SweepArgs& o, const scenarios::Sweep& result,
                         const std::optional<scenarios::MaximumTable>& table, const std::optional<scenarios::ShardMark>& mark) {
  if (o.csv) write_file(*o.csv, scenarios::sweep_csv(result));
  if (o.json) {
    auto j = scenarios::sweep_json(result, table ? &*table : nullptr);
    j["endatsim"] = ENDATSIM_VERSION;
    if (mark) j["shard"] = scenarios::to_json(*mark);
    write_file(*o.json, scenarios::json_file_text(j));
  }
  if (o.svg) write_file(*o.svg, scenarios::maximum_svg(result, *table));
}

// Every output path is checked before the sweep runs, so that a typo in a directory shows at
// once and not after all the points ran.
std::vector<scenarios::OutputPath> sweep_outputs(const SweepArgs& o) {
  std::vector<scenarios::OutputPath> outputs;
  if (o.csv) outputs.push_back({"--csv", *o.csv});
  if (o.json) outputs.push_back({"--json", *o.json});
  if (o.svg) outputs.push_back({"--svg", *o.svg});
  return outputs;
}

// What a sweep (or the merge of its shards) writes once every point ran: the outputs, then the
// point count and the maximum table on stdout; exit 3 when a point's run ended early.
int finish_sweep(const SweepArgs& o, const scenarios::Sweep& result, const std::optional<scenarios::ShardMark>& mark) {
  std::optional<scenarios::MaximumTable> table;
  if (o.maximize) table = scenarios::maximize(result, *o.maximize);
  write_sweep_outputs(o, result, table, mark);
  std::ostream& out = SummaryStream(sweep_outputs(o)).stream;
  const auto clean = std::count_if(result.points.begin(), result.points.end(), [](const auto& p) { return p.clean; });
  if (o.verbose)
    for (const auto& p : result.points) {
      std::string where;
      for (std::size_t i = 0; i < p.values.size() && i < result.grid.size(); ++i)
        where += (i == 0 ? "" : " ") + result.grid[i].pointer + "=" + p.values[i].dump();
      out << (p.clean ? "clean " : "not clean ") << where << "\n";
    }
  if (mark && !o.quiet)
    out << "shard " << mark->shard.index << "/" << mark->shard.count << ": "
        << (mark->items == 0 ? std::string("no grid point")
                             : "grid points " + std::to_string(mark->first + 1) + " to " + std::to_string(mark->first + mark->items))
        << " of " << mark->total << "\n";
  if (!o.quiet) out << result.points.size() << " points, " << clean << " clean\n";
  if (table) out << scenarios::maximum_text(result, *table);
  const auto incomplete =
      std::count_if(result.points.begin(), result.points.end(), [](const auto& p) { return !p.incomplete.empty(); });
  if (incomplete != 0) {
    const auto first = std::find_if(result.points.begin(), result.points.end(), [](const auto& p) { return !p.incomplete.empty(); });
    std::cerr << "endatsim sweep: " << incomplete << " points ended early, the first at grid point "
              << (first - result.points.begin()) + 1 + static_cast<std::ptrdiff_t>(mark ? mark->first : 0) << ": "
              << first->incomplete << "\n";
    return kIncomplete;
  }
  return kPass;
}

int sweep(const SweepArgs& o) {
  const auto outputs = sweep_outputs(o);
  scenarios::check_output_paths({o.file}, "the scenario file", outputs);
  auto options = sweep_run_options(o);
  scenarios::Sweep result;
  std::vector<scenarios::GridAxis> grid;
  std::optional<scenarios::ShardMark> mark;
  load_or_clear_outputs("sweep", outputs, [&] {
    for (const auto& g : o.grid) grid.push_back(scenarios::parse_grid_axis(g));
    const auto base = scenarios::read_scenario_json(o.file);
    scenarios::check_grid(base, o.file, grid);
    if (o.maximize) {
      // A bad --maximize or chart shape stops the sweep before it runs, not after.
      const scenarios::Sweep empty{o.file, "", grid, {}};
      const auto table = scenarios::maximize(empty, *o.maximize);
      if (o.svg) (void)scenarios::maximum_svg(empty, table);
    }
    if (o.shard) {
      const std::size_t total = scenarios::grid_size(grid);
      const auto slice = scenarios::slice_of(*o.shard, total);
      options.points = std::pair(slice.begin, slice.end);
      nlohmann::json axes = nlohmann::json::array();
      for (const auto& axis : grid) axes.push_back({{"pointer", axis.pointer}, {"values", axis.values}});
      mark = scenarios::ShardMark{ENDATSIM_VERSION, "sweep", *o.shard, slice.begin, slice.end - slice.begin, total,
                                  {{"file", o.file}, {"grid", axes}}, {{"limits", scenarios::limits_json(o.limits)}},
                                  true, "", {}};
    }
    result = scenarios::run_sweep(base, o.file, grid, options);  // every point is checked before any runs
  });
  if (options.progress) std::cerr << "\n";
  if (result.interrupted != 0) {
    // Nothing written: an earlier sweep's outputs go too, so that none looks current.
    std::cerr << "endatsim sweep: interrupted by " << scenarios::signal_name(result.interrupted) << "; no output written";
    for (const auto& path : scenarios::remove_outputs(outputs)) std::cerr << "; removed " << path;
    std::cerr << "\n";
    return interrupted_status(result.interrupted);
  }
  return finish_sweep(o, result, mark);
}

std::optional<unsigned> parse_jobs(const std::string& text) {
  unsigned jobs = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), jobs);
  if (ec != std::errc{} || end != text.data() + text.size() || jobs == 0 || jobs > 1024) return std::nullopt;
  return jobs;
}

int sweep_command(const po::variables_map& vm) {
  SweepArgs o;
  const auto files = vm.count("files") != 0 ? vm["files"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (files.size() != 1 || vm.count("grid") == 0) {
    std::cerr << "endatsim sweep: expected one scenario file and at least one --grid\n" << kSweepUsage;
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
  if (!engine_option(string_option("engine"), "sweep", o.engine)) return kBadInput;
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
  o.verbose = vm.count("verbose") != 0;
  if (!parse_limits(vm, "sweep", o.limits)) return kBadInput;
  if (const auto shard = string_option("shard")) {
    o.shard = scenarios::parse_shard(*shard);
    if (o.csv || o.svg || o.maximize) {
      std::cerr << "endatsim sweep: --shard writes its points to --json as a partial; endatsim merge writes --csv, --svg "
                   "and the --maximize table from every shard's\n";
      return kBadInput;
    }
    if (!o.json) {
      std::cerr << "endatsim sweep: --shard needs --json PATH, the partial that endatsim merge joins with the other shards'\n";
      return kBadInput;
    }
  }
  return sweep(o);
}

std::optional<std::string> string_option(const po::variables_map& vm, const char* name) {
  if (vm.count(name) == 0) return std::nullopt;
  return vm[name].as<std::string>();
}

std::vector<std::string> files_of(const po::variables_map& vm) {
  return vm.count("files") != 0 ? vm["files"].as<std::vector<std::string>>() : std::vector<std::string>{};
}

int run_command(const po::variables_map& vm) {
  Options o;
  o.all_files = scenario_files(files_of(vm));
  if (o.all_files.empty()) {
    std::cerr << "endatsim run: no scenario file given\n" << kRunUsage;
    return kBadInput;
  }
  o.files = o.all_files;
  if (const auto shard = string_option(vm, "shard")) {
    o.shard = scenarios::parse_shard(*shard);
    const auto slice = scenarios::slice_of(*o.shard, o.all_files.size());
    o.files.assign(o.all_files.begin() + static_cast<std::ptrdiff_t>(slice.begin),
                   o.all_files.begin() + static_cast<std::ptrdiff_t>(slice.end));
  }
  o.vcd = string_option(vm, "vcd");
  o.json = string_option(vm, "json");
  o.junit = string_option(vm, "junit");
  o.log = string_option(vm, "log");
  o.log_json = string_option(vm, "log-json");
  o.gtkw = vm.count("gtkw") != 0;
  if (const auto examples = string_option(vm, "examples")) {
    const auto n = parse_uint(*examples);
    if (!n || *n == 0 || *n > 1'000'000) {
      std::cerr << "endatsim run: --examples expects a whole number from 1 to 1000000, got '" << scenarios::trimmed(*examples)
                << "'\n";
      return kBadInput;
    }
    o.examples = *n;
  }
  if (const auto cases = string_option(vm, "junit-cases")) {
    if (*cases != "scenario" && *cases != "expectation") {
      std::cerr << "endatsim run: --junit-cases expects scenario or expectation, got '" << scenarios::trimmed(*cases) << "'\n";
      return kBadInput;
    }
    if (!o.junit) {
      std::cerr << "endatsim run: --junit-cases shapes the --junit file; give --junit PATH\n";
      return kBadInput;
    }
    o.junit_cases = *cases == "expectation" ? scenarios::JunitCases::Expectation : scenarios::JunitCases::Scenario;
  }
  if (o.gtkw && !o.vcd) {
    std::cerr << "endatsim run: --gtkw writes a GTKWave save file beside each --vcd file; give --vcd PATH\n";
    return kBadInput;
  }
  if (!engine_option(string_option(vm, "engine"), "run", o.engine)) return kBadInput;
  if (const auto text = string_option(vm, "seed")) {
    o.seed = parse_uint(*text);
    if (!o.seed) {
      std::cerr << "endatsim run: --seed expects an integer 0 .. 18446744073709551615, got '" << *text << "'\n";
      return kBadInput;
    }
  }
  const std::string color = string_option(vm, "color").value_or("auto");
  if (color != "auto" && color != "always" && color != "never") {
    std::cerr << "endatsim run: --color expects auto, always or never, got '" << color << "'\n";
    return kBadInput;
  }
  o.verbose = vm.count("verbose") != 0;
  o.quiet = vm.count("quiet") != 0;
  if (o.verbose && o.quiet) {
    std::cerr << "endatsim run: --verbose and --quiet exclude each other\n";
    return kBadInput;
  }
  o.color = color;
  if (!parse_limits(vm, "run", o.limits)) return kBadInput;
  return run(o);
}

// Partials: a folder stands for every file in it (not below).
std::vector<std::string> partial_files(const std::vector<std::string>& args) {
  return files_named(args, false, "", "file in it");
}

int merge_sweep_partials(const po::variables_map& vm,
                         const std::map<scenarios::PartialKind, std::vector<scenarios::Partial>>& groups) {
  for (const char* name : {"junit", "log", "log-json"})
    if (vm.count(name) != 0) {
      std::cerr << "endatsim merge: --" << name << " is an output of a run; these partials are a sweep's\n" << kMergeUsage;
      return kBadInput;
    }
  SweepArgs o;
  o.csv = string_option(vm, "csv");
  o.json = string_option(vm, "json");
  o.svg = string_option(vm, "svg");
  o.maximize = string_option(vm, "maximize");
  o.quiet = vm.count("quiet") != 0;
  o.verbose = vm.count("verbose") != 0;
  if (o.svg && !o.maximize) {
    std::cerr << "endatsim merge: --svg draws the --maximize table; give --maximize POINTER\n";
    return kBadInput;
  }
  scenarios::Sweep result;
  load_or_clear_outputs("merge", sweep_outputs(o), [&] {
    const auto& shards = groups.at(scenarios::PartialKind::Sweep);
    scenarios::require_every_shard(shards, "sweep --json");
    result = scenarios::merge_sweep(shards);
    if (o.maximize) {
      const auto table = scenarios::maximize(result, *o.maximize);
      if (o.svg) (void)scenarios::maximum_svg(result, table);
    }
  });
  return finish_sweep(o, result, std::nullopt);
}

int merge_run_partials(const po::variables_map& vm, const std::vector<scenarios::OutputPath>& outputs,
                       const std::map<scenarios::PartialKind, std::vector<scenarios::Partial>>& groups) {
  using scenarios::PartialKind;
  for (const char* name : {"csv", "svg", "maximize", "verbose"})
    if (vm.count(name) != 0) {
      std::cerr << "endatsim merge: --" << name << " is for a sweep's partials; these are a run's\n" << kMergeUsage;
      return kBadInput;
    }
  const std::pair<PartialKind, const char*> kinds[] = {
      {PartialKind::Results, "json"}, {PartialKind::Junit, "junit"}, {PartialKind::Log, "log"}, {PartialKind::LogJson, "log-json"}};
  const bool quiet = vm.count("quiet") != 0;
  const std::vector<scenarios::Partial>* verdict_from = nullptr;
  load_or_clear_outputs("merge", outputs, [&] {
    for (const auto& [kind, name] : kinds) {
      const auto group = groups.find(kind);
      if (vm.count(name) != 0) {
        scenarios::require_every_shard(group == groups.end() ? std::vector<scenarios::Partial>{} : group->second,
                                       std::string("--") + name);
      } else if (group != groups.end() && !quiet && !outputs.empty()) {  // without outputs: the verdict alone
        std::cerr << "endatsim merge: " << group->second.size() << " " << scenarios::option_of(kind)
                  << " partial(s) given without --" << name << "; not merged\n";
      }
      if (group != groups.end() && verdict_from == nullptr) {
        scenarios::require_every_shard(group->second, std::string("--") + name);
        verdict_from = &group->second;
      }
    }
  });
  load_or_clear_outputs("merge", outputs, [&] {
    std::optional<StreamedFile> out[4];
    for (std::size_t i = 0; i < 4; ++i)
      if (const auto path = string_option(vm, kinds[i].second)) out[i].emplace(*path);
    if (out[0]) scenarios::merge_results_json(groups.at(PartialKind::Results), out[0]->stream());
    if (out[1]) scenarios::merge_junit(groups.at(PartialKind::Junit), out[1]->stream());
    if (out[2]) scenarios::merge_log(groups.at(PartialKind::Log), out[2]->stream());
    if (out[3]) scenarios::merge_log_json(groups.at(PartialKind::LogJson), out[3]->stream());
    for (auto& file : out)
      if (file) file->commit();
  });
  const auto v = scenarios::run_verdict(*verdict_from);
  if (!quiet) {
    std::ostream& summary = SummaryStream(outputs).stream;
    summary << v.scenarios << " scenario files from " << verdict_from->size() << " shards\n";
    summary << (!v.incomplete.empty() ? "incomplete: " + v.incomplete
                : v.passed            ? "all scenarios passed"
                                      : "some scenarios failed")
            << "\n";
  }
  if (!v.incomplete.empty()) return kIncomplete;
  return v.passed ? kPass : kFail;
}

int merge_partials(const po::variables_map& vm) {
  const auto files = partial_files(files_of(vm));
  if (files.empty()) {
    std::cerr << "endatsim merge: no partial given\n" << kMergeUsage;
    return kBadInput;
  }
  // Every output path is checked before any partial is read; a partial that does not fit removes
  // what an earlier merge left at them.
  std::vector<scenarios::OutputPath> outputs;
  for (const char* name : {"json", "junit", "log", "log-json", "csv", "svg"})
    if (const auto path = string_option(vm, name)) outputs.push_back({std::string("--") + name, *path});
  scenarios::check_output_paths(files, "a partial", outputs);
  std::vector<scenarios::Partial> partials;
  std::map<scenarios::PartialKind, std::vector<scenarios::Partial>> groups;
  load_or_clear_outputs("merge", outputs, [&] {
    for (const auto& file : files) partials.push_back(scenarios::read_partial(file));
    groups = scenarios::group_partials(partials, ENDATSIM_VERSION);
  });
  return partials.front().mark.command == "sweep" ? merge_sweep_partials(vm, groups)
                                                  : merge_run_partials(vm, outputs, groups);
}

int merge_command(const po::variables_map& vm) {
  try {
    return merge_partials(vm);
  } catch (const scenarios::Interrupted& e) {
    std::cerr << "endatsim merge: interrupted by " << scenarios::signal_name(e.signal()) << "; no output written\n";
    return interrupted_status(e.signal());
  }
}

int validate_command(const po::variables_map& vm) {
  const auto files = scenario_files(files_of(vm));
  if (files.empty()) {
    std::cerr << "endatsim validate: no scenario file given\n" << kValidateUsage;
    return kBadInput;
  }
  scenarios::Limits limits;
  if (!parse_limits(vm, "validate", limits)) return kBadInput;
  bool ok = true;
  for (const auto& file : files) {
    try {
      const auto s = scenarios::load_scenario_file(file);
      (void)scenarios::resolve_limits(s, limits);
      if (vm.count("quiet") == 0) std::cout << "valid " << file << " (" << scenarios::trimmed(s.name) << ")\n";
    } catch (const scenarios::ScenarioError& e) {
      std::cerr << "endatsim: " << e.what() << "\n";
      ok = false;
    }
  }
  return ok ? kPass : kBadInput;
}

int diagram_command(const po::variables_map& vm) {
  const auto files = files_of(vm);
  const auto svg = string_option(vm, "svg");
  if (files.size() != 1 || !svg) {
    std::cerr << "endatsim diagram: expected one scenario file and --svg PATH\n" << kDiagramUsage;
    return kBadInput;
  }
  scenarios::DiagramOptions d;
  if (const auto f = string_option(vm, "frame")) {
    d.frame = parse_uint(*f);
    if (!d.frame) {
      std::cerr << "endatsim diagram: --frame expects a frame index, got '" << *f << "'\n";
      return kBadInput;
    }
  }
  const auto from = string_option(vm, "from"), to = string_option(vm, "to");
  if (from.has_value() != to.has_value() || (from && d.frame)) {
    std::cerr << "endatsim diagram: give --frame N, or --from and --to together\n";
    return kBadInput;
  }
  try {
    if (from) d.window = std::make_pair(sim::parse_duration(*from), sim::parse_duration(*to));
  } catch (const std::invalid_argument& e) {
    std::cerr << "endatsim diagram: --from/--to: " << e.what() << "\n";
    return kBadInput;
  }
  if (d.window && d.window->second <= d.window->first) {
    std::cerr << "endatsim diagram: --to must be later than --from\n";
    return kBadInput;
  }
  if (const auto text = string_option(vm, "seed")) {
    d.seed = parse_uint(*text);
    if (!d.seed) {
      std::cerr << "endatsim diagram: --seed expects an integer 0 .. 18446744073709551615, got '" << *text << "'\n";
      return kBadInput;
    }
  }
  if (!parse_limits(vm, "diagram", d.limits)) return kBadInput;
  const std::vector<scenarios::OutputPath> outputs{{"--svg", *svg}};
  scenarios::check_output_paths(files, "the scenario file", outputs);
  scenarios::Scenario scenario;
  load_or_clear_outputs("diagram", outputs, [&] {
    scenario = scenarios::load_scenario_file(files.front());
    (void)scenarios::resolve_limits(scenario, d.limits);
  });
  StreamedFile out(*svg);
  scenarios::Diagram diagram;
  try {
    load_or_clear_outputs("diagram", outputs, [&] { diagram = scenarios::frame_diagram(scenario, d); });
  } catch (const scenarios::Interrupted& e) {
    std::cerr << "endatsim diagram: " << e.what() << "; no diagram written\n";
    return interrupted_status(e.signal());
  } catch (const scenarios::LimitReached& e) {
    std::cerr << "endatsim diagram: " << e.what() << "; no diagram written\n";
    return kIncomplete;
  }
  out.stream() << diagram.svg;
  out.commit();
  if (vm.count("quiet") == 0) SummaryStream(outputs).stream << diagram.caption << "\n";
  return kPass;
}

// The declared encoder of a check: a scenario's (its line's transceivers included in the delay
// at the connector) or a profile's with the model's transceivers.
// A scenario also gives its cable (to `cable`); a profile has none.
// What --encoder declares: a profile (its memory image: word 13's width, word 39's t_cal, word 25's
// highest clock), or a scenario or a bench whose encoder section adds the datasheet's times (t_m,
// t_R, t_ac, t_ST and t_LO maxima, possibly on top of a profile), its cable and its checker options.
struct EncoderFile {
  checker::EncoderDeclaration encoder;
  std::optional<double> cable;
  std::optional<sim::Time> cable_delay_per_m;
  std::optional<checker::CheckerParams> checker;
};

EncoderFile encoder_declaration_file(const std::string& path) {
  // A regular file of at most 4 MiB, as every JSON input (a FIFO or a device is refused).
  const std::string text = input::read_file(path, {"encoder profile or scenario", "an"});
  const auto j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw std::runtime_error(path + ": not a JSON object (a profile or a scenario)");
  if (j.contains("encoder") || j.contains("script") || j.contains("line")) {
    const bool bench = !j.contains("master") && !j.contains("script");
    const auto s = scenarios::load_scenario_file(path, bench ? scenarios::ScenarioKind::Bench : scenarios::ScenarioKind::Run);
    auto d = scenarios::declared_encoder(s.encoder);
    d.output_delay = s.line.encoder.receiver_delay + s.encoder.output_delay + s.line.encoder.driver_delay;
    return {d, s.line.cable_length_m, s.line.cable_delay_per_m, s.checker};
  }
  slave::EncoderParams p;
  slave::load_profile(path).apply(p);
  const line::LineParams lp;
  auto d = scenarios::declared_encoder(p);
  d.output_delay = lp.encoder.receiver_delay + p.output_delay + lp.encoder.driver_delay;
  return {d, std::nullopt, std::nullopt, std::nullopt};
}

// A duration option of `check` within 0 .. max; a message and false when it is not one.
bool check_duration(const po::variables_map& vm, const char* name, sim::Time max, std::optional<sim::Time>& out) {
  const auto text = string_option(vm, name);
  if (!text) return true;
  try {
    out = sim::parse_duration(*text);
  } catch (const std::invalid_argument& e) {
    std::cerr << "endatsim check: --" << name << ": " << e.what() << "\n";
    return false;
  }
  if (*out > max) {
    std::cerr << "endatsim check: --" << name << " must be 0 .. " << sim::format_time(max) << ", got " << *text << "\n";
    return false;
  }
  return true;
}

int check_command(const po::variables_map& vm) {
  const auto files = files_of(vm);
  scenarios::CaptureCheckOptions o;
  const auto clock = string_option(vm, "clock"), data_in = string_option(vm, "data-in");
  const auto data_out = string_option(vm, "data-out");
  const auto data = data_in ? data_in : string_option(vm, "data");
  if (vm.count("data") != 0 && (data_in || data_out)) {
    std::cerr << "endatsim check: --data is one DATA wire; --data-out and --data-in are an RTL master's split DATA: "
                 "give one or the other\n";
    return kBadInput;
  }
  if (data_in.has_value() != data_out.has_value()) {
    std::cerr << "endatsim check: --data-out and --data-in go together\n";
    return kBadInput;
  }
  if (files.empty() || !clock || !data) {
    std::cerr << "endatsim check: expected capture files, --clock NAME and --data NAME (or --data-out and --data-in)\n"
              << kCheckUsage;
    return kBadInput;
  }
  if (vm.count("verbose") != 0 && vm.count("quiet") != 0) {
    std::cerr << "endatsim check: --verbose and --quiet exclude each other\n";
    return kBadInput;
  }
  o.clock = *clock;
  o.data = *data;
  o.data_out = data_out;
  o.data_enable = string_option(vm, "data-enable");
  o.power = string_option(vm, "power");
  o.enable_active_low = vm.count("enable-active-low") != 0;
  o.master_data_enable = string_option(vm, "master-data-enable");
  if (o.master_data_enable && (!o.data_enable || o.data_out)) {
    std::cerr << "endatsim check: --master-data-enable goes with one DATA wire (--data) and the encoder's "
                 "--data-enable: both drivers' enables show a contention\n";
    return kBadInput;
  }
  if (const auto at = string_option(vm, "master-data-enable-at")) {
    if (*at != "encoder" && *at != "master") {
      std::cerr << "endatsim check: --master-data-enable-at must be 'encoder' or 'master', got '" << *at << "'\n";
      return kBadInput;
    }
    if (!o.master_data_enable) {
      std::cerr << "endatsim check: --master-data-enable-at says where --master-data-enable was recorded: give that too\n";
      return kBadInput;
    }
    o.master_enable_at_master = *at == "master";
  }
  if (o.enable_active_low && !o.data_enable) {
    std::cerr << "endatsim check: --enable-active-low needs --data-enable NAME\n";
    return kBadInput;
  }
  {
    const line::LineParams lp;
    const slave::EncoderParams model;
    o.encoder = scenarios::declared_encoder(model);
    o.encoder.output_delay = lp.encoder.receiver_delay + model.output_delay + lp.encoder.driver_delay;
  }
  std::optional<double> scenario_cable;
  if (const auto e = string_option(vm, "encoder")) {
    auto declared = encoder_declaration_file(*e);
    o.encoder = declared.encoder;
    scenario_cable = declared.cable;
    o.cable_delay_per_m = declared.cable_delay_per_m;
    if (declared.checker) o.checker = *declared.checker;
  }
  std::optional<sim::Time> clock_to_data;
  if (!check_duration(vm, "clock-to-data", sim::us(10), clock_to_data)) return kBadInput;
  if (clock_to_data) o.encoder.output_delay = *clock_to_data;
  if (vm.count("t-st-reduced-for-cable") != 0) o.checker.t_st_reduced_for_cable = true;
  if (o.data_out) o.at = scenarios::CaptureCheckOptions::At::Master;  // an RTL master's own signals
  if (const auto at = string_option(vm, "at")) {
    if (*at != "encoder" && *at != "master") {
      std::cerr << "endatsim check: --at must be 'encoder' or 'master', got '" << *at << "'\n";
      return kBadInput;
    }
    if (o.data_out && *at != "master") {
      std::cerr << "endatsim check: --data-out and --data-in are a master's signals: they are at the master\n";
      return kBadInput;
    }
    o.at = *at == "master" ? scenarios::CaptureCheckOptions::At::Master : scenarios::CaptureCheckOptions::At::Encoder;
  }
  if (const auto cable = string_option(vm, "cable")) {
    std::string text = *cable;
    if (text.size() > 1 && text.back() == 'm') text.pop_back();
    while (!text.empty() && text.back() == ' ') text.pop_back();
    double metres = -1;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), metres);
    if (error != std::errc() || end != text.data() + text.size() || !(metres >= 0 && metres <= 1000)) {
      std::cerr << "endatsim check: --cable must be a length of 0 .. 1000 m (\"25\" or \"25 m\"), got '" << *cable << "'\n";
      return kBadInput;
    }
    o.cable_m = metres;
  }
  if (!o.cable_m) o.cable_m = scenario_cable;  // --encoder SCENARIO.json: its line's cable
  if (!check_duration(vm, "t-d", sim::us(100), o.t_d)) return kBadInput;
  if (o.t_d && o.at != scenarios::CaptureCheckOptions::At::Master) {
    std::cerr << "endatsim check: --t-d is the round trip at the master's connector: it needs --at master\n";
    return kBadInput;
  }
  if (o.master_enable_at_master && !o.cable_m) {
    std::cerr << "endatsim check: --master-data-enable-at master needs --cable LENGTH (the enable reaches the encoder's "
                 "connector one cable delay later)\n";
    return kBadInput;
  }
  if (o.at == scenarios::CaptureCheckOptions::At::Master && !o.cable_m) {
    std::cerr << "endatsim check: --at master needs --cable LENGTH (t_D's bound and the round trip follow it)\n";
    return kBadInput;
  }
  if (o.at == scenarios::CaptureCheckOptions::At::Master && o.data_enable && !o.data_out) {
    std::cerr << "endatsim check: --data-enable is the encoder's driver enable, which a capture at the master's "
                 "connector does not hold\n";
    return kBadInput;
  }
  if (!check_duration(vm, "resolution", sim::ms(1), o.resolution)) return kBadInput;
  // A resolution says the capture was sampled (and may begin inside a frame); none is exact.
  if (o.resolution && *o.resolution == sim::Time::zero()) {
    std::cerr << "endatsim check: --resolution must be 1 ps .. 1 ms, got 0: a VCD's times are exact without it\n";
    return kBadInput;
  }
  const auto json = string_option(vm, "json"), log = string_option(vm, "log"), junit = string_option(vm, "junit");
  std::vector<scenarios::OutputPath> outputs;
  if (json) outputs.push_back({"--json", *json});
  if (junit) outputs.push_back({"--junit", *junit});
  if (log) outputs.push_back({"--log", *log});
  {
    std::vector<std::string> inputs = files;
    if (const auto e = string_option(vm, "encoder")) inputs.push_back(*e);
    scenarios::check_output_paths(inputs, "an input file", outputs);
  }
  const SummaryStream summary_out(outputs);
  std::optional<StreamedFile> json_file, junit_file;
  if (json) json_file.emplace(*json);
  if (junit) junit_file.emplace(*junit);
  // Each capture in turn; a bad one is reported and the others still checked. The outputs cover
  // the captures that could be read.
  // Progress on a terminal, at most twice a second, erased before the summary.
  const bool show_progress = vm.count("quiet") == 0 && isatty(STDERR_FILENO) != 0;
  auto last_shown = std::chrono::steady_clock::now();
  bool progress_shown = false;
  std::string current;
  if (show_progress)
    o.progress = [&](std::uint64_t read, std::uint64_t total) {
      const auto now = std::chrono::steady_clock::now();
      if (total == 0 || now - last_shown < std::chrono::milliseconds(500)) return;
      last_shown = now;
      progress_shown = true;
      std::cerr << "\r" << current << ": " << read * 100 / total << " %" << std::flush;
    };
  std::vector<scenarios::CaptureCheckResult> results;
  std::vector<scenarios::CaptureReadError> unreadable;
  bool conforms = true;
  // The log is streamed frame by frame while each capture is read (memory stays bounded on a
  // long capture), into a file that replaces the old one only when the whole check is done.
  std::optional<StreamedFile> log_file;
  if (log) log_file.emplace(*log);
  // The log's header names every option that relaxes a row, as each report does.
  for (const auto& r : checker::relaxations(o.checker))
    if (log_file) log_file->stream() << "# relaxed by option: " << r.check << " (" << r.by << ")\n";
  int interrupted = 0;
  for (const auto& file : files) {
    if (interrupted == 0) interrupted = scenarios::interrupt_signal();
    if (interrupted != 0) {
      const std::string why = file + ": interrupted by " + scenarios::signal_name(interrupted) + ": not judged";
      if (log_file) log_file->stream() << "# " << why << "\n";
      unreadable.push_back({file, why});
      continue;
    }
    o.file = file;
    current = file;
    if (log_file && files.size() > 1) log_file->stream() << "# " << file << "\n";
    if (log_file) o.on_frame = [&](const checker::WireFrame& f) { log_file->stream() << scenarios::frame_log_line(f); };
    try {
      results.push_back(scenarios::check_capture(o));
      if (progress_shown) std::cerr << "\r\033[K" << std::flush;
      progress_shown = false;
    } catch (const scenarios::Interrupted& e) {
      if (progress_shown) std::cerr << "\n";
      progress_shown = false;
      interrupted = e.signal();
      if (log_file) log_file->stream() << "# " << e.what() << "\n";
      unreadable.push_back({file, e.what()});
      continue;
    } catch (const capture::CaptureError& e) {
      if (progress_shown) std::cerr << "\n";
      progress_shown = false;
      std::cerr << "endatsim check: " << e.what() << "\n";
      if (log_file) log_file->stream() << "# " << file << ": not judged: " << e.what() << "\n";
      unreadable.push_back({file, e.what()});
      continue;
    }
    const auto& r = results.back();
    conforms = conforms && r.conforms();
    if (vm.count("quiet") == 0 || !r.conforms()) scenarios::write_capture_summary(summary_out.stream, r, vm.count("verbose") != 0);
  }
  if (json_file) {
    if (files.size() == 1 && results.size() == 1) {
      json_file->stream() << scenarios::json_file_text(scenarios::capture_json(results.front()));
    } else {
      // Every capture named, in order: a judged one, or one that could not be read.
      nlohmann::json all = nlohmann::json::array();
      auto judged = results.begin();
      auto bad = unreadable.begin();
      for (const auto& file : files) {
        if (bad != unreadable.end() && bad->file == file) {
          all.push_back({{"file", file}, {"error", bad->message}});
          ++bad;
        } else if (judged != results.end()) {
          all.push_back(scenarios::capture_json(*judged++));
        }
      }
      nlohmann::json j{{"captures", all}};
      if (interrupted != 0) {
        j["complete"] = false;
        j["incomplete"] = "interrupted by " + scenarios::signal_name(interrupted);
      }
      json_file->stream() << scenarios::json_file_text(j);
    }
    json_file->commit();
  }
  if (junit_file) {
    junit_file->stream() << scenarios::junit_xml(results, unreadable);
    junit_file->commit();
  }
  if (log_file) log_file->commit();
  if (interrupted != 0) {
    std::cerr << "endatsim check: interrupted by " << scenarios::signal_name(interrupted)
              << "; the outputs list the captures not judged\n";
    return interrupted_status(interrupted);
  }
  if (!unreadable.empty()) return kBadInput;
  return conforms ? kPass : kFail;
}

int checks_command(const po::variables_map& vm) {
  if (!files_of(vm).empty()) {
    std::cerr << "endatsim checks: takes no file\n" << kChecksUsage;
    return kBadInput;
  }
  if (vm.count("json") != 0 && vm.count("python") != 0) {
    std::cerr << "endatsim checks: --json and --python exclude each other\n" << kChecksUsage;
    return kBadInput;
  }
  if (vm.count("json") != 0) std::cout << scenarios::decoder_tables_json();
  else if (vm.count("python") != 0) std::cout << scenarios::decoder_tables_python();
  else std::cout << protocol::timing_table_markdown();
  return kPass;
}

int parameters_command(const po::variables_map& vm) {
  if (!files_of(vm).empty()) {
    std::cerr << "endatsim parameters: takes no file\n" << kParametersUsage;
    return kBadInput;
  }
  if (vm.count("schema") != 0) std::cout << scenarios::parameter_schema().dump(2) << "\n";
  else std::cout << scenarios::parameter_tables_markdown();
  return kPass;
}

const CommandInfo* find_command(const std::string& name) {
  for (const auto& c : kCommands)
    if (name == c.name) return &c;
  return nullptr;
}

// An option of another command is a usage error that says so.
std::optional<std::string> owner_of(const std::string& option, Command current) {
  for (const auto& c : kCommands) {
    if (c.command == current) continue;
    const auto o = options_of(c.command);
    if (o.find_nothrow(option, false) != nullptr) return c.name;
  }
  return std::nullopt;
}

void print_help_all() {
  std::cout << usage() << "\n";
  for (const auto& c : kCommands) std::cout << c.help << "\n";
  for (const auto& c : kCommands) std::cout << c.name << " " << options_of(c.command) << "\n";
}

}  // namespace

int dispatch(int argc, char** argv) {
  const std::string first = argc > 1 ? argv[1] : "";
  if (first == "--version") {
    std::cout << "endatsim " << ENDATSIM_VERSION << "\n";
    return kPass;
  }
  if (first == "--help" || first == "-h" || first == "help") {
    print_help_all();
    return kPass;
  }
  const CommandInfo* info = find_command(first);
  if (info == nullptr) {
    std::vector<std::string> names;
    for (const auto& c : kCommands) names.emplace_back(c.name);
    const auto near = input::closest_match(first, names);
    std::cerr << (first.empty() ? "endatsim: no command given\n"
                  : first[0] == '-' ? "endatsim: " + first + " before a command\n"
                                    : "endatsim: unknown command \"" + scenarios::trimmed(first) + "\"" +
                                          (near ? "; did you mean \"" + *near + "\"?" : "") + "\n")
              << usage();
    return kBadInput;
  }
  const auto visible = options_of(info->command);
  po::options_description all;
  all.add(visible).add_options()("files", po::value<std::vector<std::string>>());
  po::positional_options_description positional;
  positional.add("files", -1);
  po::variables_map vm;
  try {
    po::store(po::command_line_parser(argc - 1, argv + 1).options(all).positional(positional).run(), vm);
    po::notify(vm);
  } catch (const po::unknown_option& e) {
    std::string name = e.get_option_name();
    while (!name.empty() && name.front() == '-') name.erase(0, 1);
    if (const auto owner = owner_of(name, info->command))
      std::cerr << "endatsim " << info->name << ": --" << name << " is not an option of " << info->name
                << " (it is one of " << *owner << ")\n";
    else {
      std::vector<std::string> names;
      for (const auto& option : visible.options()) names.push_back(option->long_name());
      const auto near = input::closest_match(name, names);
      std::cerr << "endatsim " << info->name << ": " << e.what() << (near ? "; did you mean --" + *near + "?" : "") << "\n";
    }
    std::cerr << info->usage;
    return kBadInput;
  } catch (const po::error& e) {
    std::cerr << "endatsim " << info->name << ": " << e.what() << "\n" << info->usage;
    return kBadInput;
  }
  if (vm.count("help") != 0) {
    std::cout << info->usage << "\n" << info->help << "\n" << visible;
    return kPass;
  }
  if (vm.count("version") != 0) {
    std::cout << "endatsim " << ENDATSIM_VERSION << "\n";
    return kPass;
  }
  if (info->command != Command::Checks && info->command != Command::Parameters && info->command != Command::Validate)
    scenarios::install_interrupt_handlers();
  // A reader that goes away (`| head`) makes the next write fail with EPIPE instead of killing the
  // process: the outputs then end as on any write error, their part files removed, and it says so.
  std::signal(SIGPIPE, SIG_IGN);
  try {
    switch (info->command) {
      case Command::Run: return run_command(vm);
      case Command::Sweep: return sweep_command(vm);
      case Command::Merge: return merge_command(vm);
      case Command::Validate: return validate_command(vm);
      case Command::Diagram: return diagram_command(vm);
      case Command::Check: return check_command(vm);
      case Command::Checks: return checks_command(vm);
      case Command::Parameters: return parameters_command(vm);
    }
  } catch (...) {
    return report_failure(std::current_exception(), std::cerr);
  }
  return kBadInput;
}

int main(int argc, char** argv) {
  scenarios::CheckedStdout out("endatsim");
  return out.finish(dispatch(argc, argv));
}
