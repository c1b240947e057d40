#include "endatsim/scenarios/bundled_profiles.hpp"

#include "endatsim/input/suggest.hpp"
#include "endatsim/input/text.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <system_error>

namespace endatsim::scenarios {
namespace {

namespace fs = std::filesystem;

const fs::path kBeside = fs::path("share") / "endatsim" / "profiles";
// PREFIX/bin/endatsim and PREFIX/lib/endatsim/endatsim.vpi are one and two levels below PREFIX;
// build/tests/interop/x is two below the build folder.
constexpr int kLevels = 4;

// Where the code runs from: the module that holds this function (a VPI module loaded by a
// simulator, or the program itself) and the program.
std::vector<fs::path> own_files() {
  std::vector<fs::path> files;
  std::error_code ec;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&bundled_profiles_dir), &info) != 0 && info.dli_fname != nullptr &&
      *info.dli_fname != '\0') {
    const auto module = fs::weakly_canonical(fs::path(info.dli_fname), ec);
    if (!ec) files.push_back(module);
  }
  const auto program = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) files.push_back(program);
  return files;
}

fs::path& package_profiles_dir() {
  static fs::path dir;
  return dir;
}

}  // namespace

void set_package_profiles_dir(std::filesystem::path dir) { package_profiles_dir() = std::move(dir); }

fs::path bundled_profiles_dir() {
  std::error_code ec;
  if (const char* dir = std::getenv("ENDATSIM_PROFILES"); dir != nullptr && *dir != '\0') {
    if (!fs::is_directory(dir, ec))
      throw std::runtime_error("ENDATSIM_PROFILES=" + input::trimmed(dir) + " is not a folder of profiles");
    return dir;
  }
  std::string looked;
  for (const auto& file : own_files()) {
    fs::path dir = file.parent_path();
    for (int level = 0; level <= kLevels && !dir.empty(); ++level, dir = dir.parent_path()) {
      if (fs::is_directory(dir / kBeside, ec)) return dir / kBeside;
      if (dir == dir.root_path()) break;
    }
    looked += (looked.empty() ? "" : ", ") + file.parent_path().string();
  }
  const fs::path& package = package_profiles_dir();
  if (!package.empty() && fs::is_directory(package, ec)) return package;
  if (fs::is_directory(ENDATSIM_INSTALLED_PROFILES_DIR, ec)) return ENDATSIM_INSTALLED_PROFILES_DIR;
  throw std::runtime_error("the bundled profiles are not found: no " + kBeside.string() + " in or above " +
                           (looked.empty() ? std::string("the program's folder") : looked) + ", nor in " +
                           (package.empty() ? std::string() : package.string() + " or ") + ENDATSIM_INSTALLED_PROFILES_DIR +
                           "; set ENDATSIM_PROFILES to the folder that holds them");
}

std::vector<std::string> bundled_profile_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(bundled_profiles_dir(), ec))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

fs::path bundled_profile(const std::string& name) {
  const auto names = bundled_profile_names();
  if (std::find(names.begin(), names.end(), name) != names.end()) return bundled_profiles_dir() / (name + ".json");
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  throw std::runtime_error("no bundled profile \"" + input::trimmed(name) + "\" (" + input::did_you_mean(name, names) +
                           "the bundled profiles are " + list + ")");
}

bool is_bundled_profile_name(const std::string& reference) {
  return reference.find('/') == std::string::npos && !reference.ends_with(".json");
}

}  // namespace endatsim::scenarios
