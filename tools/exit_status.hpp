#pragma once
// How the command line ends on an exception: bad input (the user can fix it) or a bug in endatsim.

#include <exception>
#include <ostream>
#include <stdexcept>

#include "endatsim/scenarios/exit_status.hpp"

namespace endatsim::tools {

using scenarios::exit_status::kBadInput;
using scenarios::exit_status::kInternalError;

// Says what went wrong on `err` and returns the exit status. Every error the input can cause is a
// std::runtime_error (ScenarioError, CaptureError, ProfileError, a file that cannot be written...)
// or a std::invalid_argument (an option's value); anything else is a bug, and says so.
inline int report_failure(const std::exception_ptr& failure, std::ostream& err) {
  try {
    std::rethrow_exception(failure);
  } catch (const std::runtime_error& e) {
    err << "endatsim: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::invalid_argument& e) {
    err << "endatsim: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::exception& e) {
    err << "endatsim: internal error: " << e.what() << "\n";
  } catch (...) {
    err << "endatsim: internal error: an exception of an unknown type\n";
  }
  err << "endatsim: this is a bug in endatsim " ENDATSIM_VERSION
         "; please report it with the command line and its input files\n";
  return kInternalError;
}

}  // namespace endatsim::tools
