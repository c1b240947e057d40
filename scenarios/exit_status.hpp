#pragma once
// The exit statuses every endatsim front end ends with (the command line, the co-simulation
// benches, the VPI module); docs/command-line.md lists them for the scripts that read them.

namespace endatsim::scenarios::exit_status {

inline constexpr int kPass = 0;        // every expectation held
inline constexpr int kFail = 1;        // an expectation failed
inline constexpr int kBadInput = 2;    // input or usage the user can fix; nothing was judged
inline constexpr int kIncomplete = 3;  // a limit ended a run before its end
// sysexits.h's EX_SOFTWARE: an internal error, not the input's fault.
inline constexpr int kInternalError = 70;
// Interrupted by signal `signal` (130 SIGINT, 143 SIGTERM), the shell's convention.
constexpr int interrupted(int signal) { return 128 + signal; }

}  // namespace endatsim::scenarios::exit_status
