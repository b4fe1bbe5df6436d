// The one entry the front end uses: picks the importer by file extension.
#pragma once

#include <filesystem>

#include "core/scene/scene.h"
#include "core/util/diagnostics.h"

namespace fb {

// Throws UsageError for an unknown extension, InputError for a file that cannot be read.
Scene import_scene(const std::filesystem::path& file, Diagnostics& diagnostics);

}  // namespace fb
