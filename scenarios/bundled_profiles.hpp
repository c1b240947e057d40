#pragma once
// The encoder profiles that come with endatsim, found by name ("rotary_singleturn_25bit").
// They are looked up in $ENDATSIM_PROFILES when it is set, else in share/endatsim/profiles beside
// the program: in the program's folder or one of its parents, as installed (PREFIX/bin and
// PREFIX/share) and as the build tree lays them out (the build folder has share/endatsim/profiles),
// else in the folder set_package_profiles_dir() names, else where `make install` puts them (for a
// program that embeds the library). No path of the source or build tree is compiled in.

#include <filesystem>
#include <string>
#include <vector>

namespace endatsim::scenarios {

// Where the installed package a program was built against keeps its profiles: the package's
// CMake config defines ENDATSIM_PACKAGE_PROFILES_DIR for programs that link endatsim::scenarios
// (cosim/main.hpp passes it), since `cmake --install --prefix` may put the package elsewhere than
// the prefix its libraries were built for.
void set_package_profiles_dir(std::filesystem::path dir);

// The folder of the bundled profiles; throws std::runtime_error saying where it looked.
std::filesystem::path bundled_profiles_dir();

// The names of the bundled profiles, sorted.
std::vector<std::string> bundled_profile_names();

// The file of the bundled profile `name`; throws std::runtime_error for a name that is none of
// them, with a "did you mean" and the list of bundled profiles.
std::filesystem::path bundled_profile(const std::string& name);

// Whether a profile reference is a bundled profile's name (no folder, no ".json"), not a file.
bool is_bundled_profile_name(const std::string& reference);

}  // namespace endatsim::scenarios
