#pragma once
// Text from untrusted files, fit for a message.

#include <cstddef>
#include <string>

namespace endatsim::input {

// Text no longer than `max` characters: longer text is cut with "... (N bytes)" so that a hostile
// name or value cannot flood a message.
std::string trimmed(const std::string& text, std::size_t max = 80);

}  // namespace endatsim::input
