// endatsim-vcdlint — checks VCD files the way a careful viewer would: monotonic time, declared
// identifiers, value syntax, balanced scopes; --sigrok also rejects what sigrok-cli 0.7 drops
// silently (vector variables, a $comment after $enddefinitions). --edges prints, per variable,
// how many rising and falling edges it has (name, rising, falling), for comparisons with what
// other tools read from the same file.
// Exit codes: 0 clean, 1 issues found, 2 usage error or unreadable file.
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "endatsim/scenarios/output_file.hpp"
#include "endatsim/scenarios/vcd_reader.hpp"

namespace {

const char* const kHelp =
    "usage: endatsim-vcdlint [--sigrok] [--edges] [--quiet] FILE...\n"
    "\n"
    "Checks VCD files: header keywords and their $end, $timescale, balanced $scope/$upscope,\n"
    "$var declarations, strictly increasing timestamps, value changes only for declared\n"
    "identifiers and with valid values. Prints FILE:LINE: message for each issue on stderr.\n"
    "\n"
    "  --sigrok   also reject vector variables and a $comment after $enddefinitions\n"
    "             (sigrok-cli 0.7 silently reads nothing or drops the variable)\n"
    "  --edges    print 'NAME RISING FALLING' for every variable on stdout\n"
    "  --quiet    print nothing for clean files\n"
    "  --help     this text\n"
    "  --version  the version\n"
    "\n"
    "Exit status: 0 every file is clean, 1 a file has issues, 2 usage error or unreadable file.\n";

}  // namespace

int run_lint(int argc, char** argv) {
  endatsim::scenarios::VcdLintOptions options;
  bool edges = false, quiet = false;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << kHelp;
      return 0;
    }
    if (a == "--version") {
      std::cout << "endatsim-vcdlint " << ENDATSIM_VERSION << "\n";
      return 0;
    }
    if (a == "--sigrok") options.sigrok = true;
    else if (a == "--edges") edges = true;
    else if (a == "--quiet" || a == "-q") quiet = true;
    else if (!a.empty() && a[0] == '-') {
      std::cerr << "endatsim-vcdlint: unknown option " << a << "\n" << kHelp;
      return 2;
    } else files.push_back(a);
  }
  if (files.empty()) {
    std::cerr << "endatsim-vcdlint: no file given\n" << kHelp;
    return 2;
  }
  int status = 0;
  for (const auto& path : files) {
    endatsim::scenarios::VcdFile f;
    try {
      f = endatsim::scenarios::read_vcd_file(path, options);
    } catch (const std::exception& e) {
      std::cerr << "endatsim-vcdlint: " << e.what() << "\n";
      return 2;
    }
    for (const auto& issue : f.issues) std::cerr << path << ":" << issue.line << ": " << issue.message << "\n";
    if (!f.issues.empty()) status = 1;
    else if (!quiet) std::cerr << path << ": clean, " << f.variables.size() << " variables, end time " << f.end_time
                               << " x " << f.timescale << "\n";
    if (edges)
      for (const auto& v : f.variables) std::cout << v.name << " " << v.rising << " " << v.falling << "\n";
  }
  return status;
}

int main(int argc, char** argv) {
  endatsim::scenarios::CheckedStdout out("endatsim-vcdlint");
  return out.finish(run_lint(argc, argv));
}
