// Finding, opening and checking plugin libraries. A render loads exactly the plugins it uses,
// by file name (libfilmback_<kind>_<name>.so); `filmback plugins` opens them all.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <filmback/plugin_abi.h>

#include "core/plugin/descriptor.h"
#include "core/util/shared_library.h"

namespace fb {

// One opened plugin file whose descriptor passed every check; closed when the last user goes.
class PluginLibrary {
 public:
  // Throws InputError "file: reason" for anything that is not a well-formed filmback plugin.
  explicit PluginLibrary(const std::filesystem::path& file);
  PluginLibrary(const PluginLibrary&) = delete;
  PluginLibrary& operator=(const PluginLibrary&) = delete;

  // The descriptor and the function table as this filmback reads them (plugin_abi.h, "Growth"):
  // an older plugin's, with the fields its layout lacks at their defaults.
  const fb_plugin& descriptor() const { return read_.plugin; }
  const std::filesystem::path& file() const { return file_; }
  template <typename Api>
  const Api& api() const {
    if constexpr (std::is_same_v<Api, fb_camera_api>)
      return read_.camera;
    else if constexpr (std::is_same_v<Api, fb_filter_api>)
      return read_.filter;
    else
      return read_.integrator;
  }

 private:
  std::filesystem::path file_;
  SharedLibrary library_;
  PluginDescriptor read_;
};

const char* kind_name(uint32_t kind);  // "camera", "filter", "integrator"
std::string plugin_file_name(uint32_t kind, std::string_view name);

class PluginLoader {
 public:
  explicit PluginLoader(std::vector<std::filesystem::path> search_dirs);
  // The plugin folder next to this executable (../lib/filmback/plugins: the build tree's or the
  // install tree's, whichever the binary is in), else the configured install folder; then each
  // folder of FILMBACK_PLUGIN_PATH (colon-separated).
  static std::vector<std::filesystem::path> default_search_dirs();
  const std::vector<std::filesystem::path>& search_dirs() const { return search_dirs_; }

  // Throws UsageError when no folder has the plugin, InputError when it is broken, of the wrong
  // kind, or provided by more than one folder.
  std::shared_ptr<const PluginLibrary> load(uint32_t kind, std::string_view name) const;

  struct Scan {
    std::vector<std::shared_ptr<const PluginLibrary>> plugins;
    std::vector<std::string> errors;  // one per broken file or duplicate name
  };
  Scan load_all() const;

 private:
  std::vector<std::filesystem::path> search_dirs_;
};

}  // namespace fb
