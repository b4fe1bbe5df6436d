#include "support/plugins.h"

#include "core/plugin/params.h"

namespace fb::test {

const PluginLoader& loader() {
  static const PluginLoader instance(PluginLoader::default_search_dirs());
  return instance;
}

std::unique_ptr<FilterInstance> make_filter(const std::string& text) {
  const PluginSpec spec = parse_plugin_spec(text, "--filter");
  auto library = loader().load(FB_KIND_FILTER, spec.name);
  return std::make_unique<FilterInstance>(library,
                                          BoundParams(library->descriptor(), spec.settings));
}

}  // namespace fb::test
