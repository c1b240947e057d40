// Reading VCD files back: a small parser for what waveform viewers accept (IEEE 1364 §18),
// used by the VCD lint (tools/vcdlint.cpp), by the frame diagrams and by the tests that check
// every waveform the simulator writes. Viewers do not fail on malformed input by themselves
// (GTKWave shows what it could read, sigrok silently reads nothing), so the lint names the
// line and what is wrong: time going backwards, undeclared identifiers, bad value syntax,
// unbalanced scopes; with the sigrok profile also vector variables and a $comment after
// $enddefinitions, which Debian's sigrok-cli 0.7 drops silently.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace endatsim::scenarios {

struct VcdChange {
  std::int64_t time = 0;  // in timescale units
  char value = '0';       // '0', '1', 'x', 'z' (scalars; vectors keep their last bit)
};

struct VcdVariable {
  std::string id;
  std::string type;       // "wire", "reg", ...
  unsigned width = 1;
  std::string name;       // "scope.sub.name"
  std::vector<VcdChange> changes;  // including the initial value from $dumpvars
  std::uint64_t rising = 0;   // 0 -> 1
  std::uint64_t falling = 0;  // 1 -> 0
};

struct VcdIssue {
  std::size_t line = 0;
  std::string message;
};

struct VcdLintOptions {
  bool sigrok = false;  // also reject what sigrok-cli 0.7 cannot read
};

struct VcdFile {
  std::string timescale;            // as written, e.g. "1ps"
  std::int64_t timescale_ps = 0;    // 0 when not a whole number of picoseconds
  std::int64_t end_time = 0;        // the last timestamp
  std::vector<VcdVariable> variables;  // in declaration order
  std::vector<VcdIssue> issues;     // empty: the file is clean
  // The variable with the full dotted name, or nullptr.
  const VcdVariable* find(const std::string& name) const;
};

// Parses and lints; never throws on malformed content (issues are collected, at most 100).
VcdFile parse_vcd(const std::string& text, const VcdLintOptions& options = {});
// Reads a file; throws std::runtime_error if it cannot be read.
VcdFile read_vcd_file(const std::string& path, const VcdLintOptions& options = {});

}  // namespace endatsim::scenarios
