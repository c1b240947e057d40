#pragma once
// "Did you mean" for a misspelt name: a key, a check, an option, a command or a profile.

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace endatsim::input {

// The number of single-character insertions, deletions, substitutions and swaps of two neighbours
// that turn `a` into `b`, letters compared without case ("optimal string alignment" distance).
std::size_t edit_distance(std::string_view a, std::string_view b);

// The candidate `word` most likely meant: the nearest within a third of the word's length (at
// least one edit, at most three), the first listed of equally near ones; none when `word` is
// itself a candidate or nothing is near enough (a guess far off would mislead more than help).
std::optional<std::string> closest_match(std::string_view word, std::span<const std::string> candidates);

// "did you mean \"NAME\"? " (with its trailing space) for the closest match, or "" when there is none.
std::string did_you_mean(std::string_view word, std::span<const std::string> candidates);

}  // namespace endatsim::input
