#include <cmath>
#include <iostream>

#include "core/cmd/commands.h"
#include "core/plugin/loader.h"
#include "core/plugin/params.h"

namespace fb {
namespace {

void print_plugin(const PluginLibrary& library) {
  const fb_plugin& d = library.descriptor();
  std::cout << kind_name(d.kind) << ' ' << d.name << ' ' << d.version << " - " << d.summary << '\n';
  std::cout << "  file " << library.file().string() << '\n';
  if (d.param_count == 0) std::cout << "  no parameters\n";
  for (uint32_t i = 0; i < d.param_count; ++i) {
    const fb_param_desc& p = d.params[i];
    std::cout << "  " << p.name << " (" << param_type_name(p.type) << ") = " << p.default_value;
    if (*p.unit) std::cout << ' ' << p.unit;
    if (p.choices) std::cout << "  one of " << p.choices;
    if (std::isfinite(p.min_value) || std::isfinite(p.max_value))
      if (p.type != FB_PARAM_STRING && p.type != FB_PARAM_BOOL)
        std::cout << "  range [" << p.min_value << ", " << p.max_value << "]";
    std::cout << "  " << p.doc << '\n';
  }
}

}  // namespace

int run_plugins() {
  const PluginLoader loader(PluginLoader::default_search_dirs());
  std::cout << "searched:";
  for (const auto& dir : loader.search_dirs())
    std::cout << ' ' << dir.string();
  std::cout << '\n';
  const PluginLoader::Scan scan = loader.load_all();
  for (const auto& library : scan.plugins)
    print_plugin(*library);
  for (const std::string& error : scan.errors)
    std::cerr << "filmback: error: " << error << '\n';
  return scan.errors.empty() ? 0 : 1;
}

}  // namespace fb
