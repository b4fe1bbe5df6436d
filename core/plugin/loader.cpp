#include "core/plugin/loader.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <map>

#include "core/plugin/crash_guard.h"
#include "core/util/error.h"

#ifndef FILMBACK_INSTALL_PLUGIN_DIR
#define FILMBACK_INSTALL_PLUGIN_DIR "/usr/local/lib/filmback/plugins"
#endif

namespace fb {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> directories_with(const std::vector<fs::path>& dirs, const std::string& file) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (const fs::path& dir : dirs)
    if (fs::is_regular_file(dir / file, ec)) found.push_back(dir / file);
  return found;
}

// A render finds a plugin by its file name (`--filter gaussian` opens
// libfilmback_filter_gaussian.so), so the name must agree with what the descriptor declares.
std::string check_file_name(const fs::path& file, const fb_plugin& p) {
  const std::string expected = plugin_file_name(p.kind, p.name);
  const std::string actual = file.filename().string();
  if (actual == expected) return {};
  constexpr std::string_view prefix = "libfilmback_", suffix = ".so";
  if (actual.starts_with(prefix) && actual.ends_with(suffix)) {
    // libfilmback_<kind>_<name>.so; no kind name holds a '_'.
    const std::string stem =
        actual.substr(prefix.size(), actual.size() - prefix.size() - suffix.size());
    const size_t cut = stem.find('_');
    if (stem.substr(0, cut) != kind_name(p.kind))
      return "wrong kind: the file name says " + stem.substr(0, cut) +
             ", the plugin declares itself a " + kind_name(p.kind);
    if (cut != std::string::npos)
      return "name mismatch: the file name says '" + stem.substr(cut + 1) +
             "', the plugin declares the name '" + p.name + "'";
  }
  return "name mismatch: the plugin declares " + std::string(kind_name(p.kind)) + " '" + p.name +
         "', so its file must be named " + expected;
}

}  // namespace

const char* kind_name(uint32_t kind) {
  switch (kind) {
    case FB_KIND_CAMERA:
      return "camera";
    case FB_KIND_FILTER:
      return "filter";
    case FB_KIND_INTEGRATOR:
      return "integrator";
  }
  return "unknown";
}

std::string plugin_file_name(uint32_t kind, std::string_view name) {
  return "libfilmback_" + std::string(kind_name(kind)) + "_" + std::string(name) + ".so";
}

PluginLibrary::PluginLibrary(const fs::path& file) : file_(file), library_(file) {
  auto fail = [&](const std::string& reason) -> InputError {
    return InputError(located(file.string(), "", reason));
  };
  if (!library_.is_open()) {
    const std::string& why = library_.error();
    const size_t at = why.find("undefined symbol: ");
    if (at != std::string::npos)
      throw fail("missing symbol: " + why.substr(at + 18) +
                 " (the plugin needs a symbol nothing provides)");
    // glibc: "<dependency>: cannot open shared object file: ..." for a library the plugin needs.
    const size_t dependency = why.find(": cannot open shared object file");
    if (dependency != std::string::npos)
      throw fail("missing library: " + why.substr(0, dependency) +
                 " (the plugin needs a shared library the dynamic loader cannot find)");
    throw fail("not a filmback plugin: cannot load it as a shared library (" + why + ")");
  }
  auto entry = reinterpret_cast<fb_entry_point_fn>(library_.symbol(FB_ENTRY_POINT));
  std::string problem = "not a filmback plugin: it has no " FB_ENTRY_POINT " entry point";
  if (entry) {
    const PluginCrashGuard guard(file, FB_ENTRY_POINT "() or the descriptor it returned");
    problem = check_descriptor(entry(), read_);
  }
  if (!problem.empty()) throw fail(problem);  // library_ closes the file
}

// A folder named twice (say in FILMBACK_PLUGIN_PATH as well) is searched once: otherwise each of
// its plugins would be "provided twice".
PluginLoader::PluginLoader(std::vector<fs::path> search_dirs) {
  for (const fs::path& dir : search_dirs) {
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(dir, ec);
    const fs::path& key = ec ? dir : canonical;
    if (std::find(search_dirs_.begin(), search_dirs_.end(), key) == search_dirs_.end())
      search_dirs_.push_back(key);
  }
}

std::vector<fs::path> PluginLoader::default_search_dirs() {
  std::vector<fs::path> dirs;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  const fs::path beside =
      ec ? fs::path() : exe.parent_path().parent_path() / "lib/filmback/plugins";
  if (!beside.empty() && fs::is_directory(beside, ec))
    dirs.push_back(beside);
  else
    dirs.emplace_back(FILMBACK_INSTALL_PLUGIN_DIR);
  if (const char* env = std::getenv("FILMBACK_PLUGIN_PATH")) {
    std::string_view rest = env;
    while (!rest.empty()) {
      const size_t colon = rest.find(':');
      if (colon != 0) dirs.emplace_back(std::string(rest.substr(0, colon)));
      if (colon == std::string_view::npos) break;
      rest.remove_prefix(colon + 1);
    }
  }
  return dirs;
}

std::shared_ptr<const PluginLibrary> PluginLoader::load(uint32_t kind,
                                                        std::string_view name) const {
  const std::string file = plugin_file_name(kind, name);
  const std::vector<fs::path> found = directories_with(search_dirs_, file);
  if (found.empty()) {
    std::string where;
    for (const fs::path& dir : search_dirs_)
      where += (where.empty() ? "" : ", ") + dir.string();
    throw UsageError("unknown " + std::string(kind_name(kind)) + " plugin '" + std::string(name) +
                     "': no " + file + " in " + where + " (`filmback plugins` lists what exists)");
  }
  if (found.size() > 1)
    throw InputError("duplicate plugin name: " + std::string(kind_name(kind)) + " '" +
                     std::string(name) + "' is provided by " + found[0].string() + " and by " +
                     found[1].string());
  auto library = std::make_shared<const PluginLibrary>(found[0]);
  // The file is named for (kind, name), so a matching file name means the kind and name match.
  if (std::string problem = check_file_name(found[0], library->descriptor()); !problem.empty())
    throw InputError(located(found[0].string(), "", problem));
  return library;
}

PluginLoader::Scan PluginLoader::load_all() const {
  Scan scan;
  std::map<std::pair<uint32_t, std::string>, fs::path> seen;
  for (const fs::path& dir : search_dirs_) {
    std::error_code ec;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
      const std::string filename = entry.path().filename().string();
      if (filename.starts_with("libfilmback_") && filename.ends_with(".so"))
        files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      try {
        auto library = std::make_shared<const PluginLibrary>(file);
        const fb_plugin& d = library->descriptor();
        if (std::string problem = check_file_name(file, d); !problem.empty()) {
          scan.errors.push_back(located(file.string(), "", problem));
          continue;
        }
        const auto [it, fresh] = seen.emplace(std::pair{d.kind, std::string(d.name)}, file);
        if (!fresh) {
          scan.errors.push_back("duplicate plugin name: " + std::string(kind_name(d.kind)) + " '" +
                                d.name + "' is provided by " + it->second.string() + " and by " +
                                file.string());
          continue;
        }
        scan.plugins.push_back(std::move(library));
      } catch (const InputError& e) {
        scan.errors.push_back(e.what());
      }
    }
  }
  return scan;
}

}  // namespace fb
