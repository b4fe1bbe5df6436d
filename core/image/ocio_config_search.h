// Where filmback finds the OpenColorIO config for a view transform (docs/cli.md, "Colour"):
// --ocio-config FILE, else the file $OCIO names (as Blender and OpenColorIO read it), else the
// config of an installed Blender.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace fb {

struct OcioConfigChoice {
  std::filesystem::path file;
  // "--ocio-config", "$OCIO" or "Blender's": a config the user named must load (an error
  // otherwise); Blender's may fail with a warning.
  std::string origin;
  bool named_by_user = false;
};

// Blender's colormanagement/config.ocio in each place a Blender installs its datafiles, in the
// order they are tried: only $BLENDER_SYSTEM_DATAFILES/colormanagement when that is set (Blender's
// own variable for its datafiles folder); else Debian's /usr/share/blender/datafiles, versioned folders
// (/usr/share/blender/3.4/datafiles, highest version first), the same under /usr/local/share, and
// next to the `blender` found on PATH (Blender's own archives: blender-3.4.1-linux-x64/3.4/).
std::vector<std::filesystem::path> blender_config_candidates();

// The config to use, or none (then `searched` lists the files looked for).
std::optional<OcioConfigChoice> choose_ocio_config(const std::filesystem::path& option,
                                                   std::vector<std::filesystem::path>& searched);

}  // namespace fb
