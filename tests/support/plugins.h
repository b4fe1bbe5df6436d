// The built plugins, for tests: the loader the front end would use from this binary's folder.
#pragma once

#include <memory>
#include <string>

#include "core/plugin/instances.h"
#include "core/plugin/loader.h"

namespace fb::test {

const PluginLoader& loader();
std::unique_ptr<FilterInstance> make_filter(const std::string& spec);

}  // namespace fb::test
