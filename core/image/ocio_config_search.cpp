#include "core/image/ocio_config_search.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <system_error>

#include "core/util/program_on_path.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

// Folders read in one place, at most: a bound on what a crowded /usr/share/blender costs.
constexpr size_t kMaxVersionFolders = 64;

const fs::path kRelativeConfig = fs::path("datafiles") / "colormanagement" / "config.ocio";

// root/datafiles/..., then root/<version>/datafiles/... for each version folder, highest first
// (compared as version numbers: 3.10 after 3.9).
void add_candidates(const fs::path& root, std::vector<fs::path>& out) {
  out.push_back(root / kRelativeConfig);
  std::vector<fs::path> versions;
  std::error_code ec;
  for (fs::directory_iterator it(root, ec), end;
       !ec && it != end && versions.size() < kMaxVersionFolders; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.empty() && std::isdigit(static_cast<unsigned char>(name[0])))
      versions.push_back(it->path());
  }
  const auto numbers = [](const fs::path& p) {
    std::vector<long> parts;
    std::istringstream in(p.filename().string());
    for (std::string part; std::getline(in, part, '.');)
      parts.push_back(std::atol(part.c_str()));
    return parts;
  };
  std::sort(versions.begin(), versions.end(),
            [&](const fs::path& a, const fs::path& b) { return numbers(a) > numbers(b); });
  for (const fs::path& v : versions)
    out.push_back(v / kRelativeConfig);
}

}  // namespace

std::vector<fs::path> blender_config_candidates() {
  std::vector<fs::path> out;
  // Blender's own variable for where its datafiles are; when set, the only place looked in.
  if (const char* datafiles = std::getenv("BLENDER_SYSTEM_DATAFILES"); datafiles && *datafiles)
    return {fs::path(datafiles) / "colormanagement" / "config.ocio"};
  add_candidates("/usr/share/blender", out);
  add_candidates("/usr/local/share/blender", out);
  // Resolved through links: Blender's archives are often linked into a folder on PATH.
  if (const auto blender = program_on_path("blender")) {
    std::error_code ec;
    const fs::path file = fs::canonical(*blender, ec);
    if (!ec && !file.empty()) add_candidates(file.parent_path(), out);
  }
  return out;
}

std::optional<OcioConfigChoice> choose_ocio_config(const fs::path& option,
                                                   std::vector<fs::path>& searched) {
  if (!option.empty()) return OcioConfigChoice{option, "--ocio-config", true};
  if (const char* env = std::getenv("OCIO"); env && *env)
    return OcioConfigChoice{env, "$OCIO", true};
  for (const fs::path& file : blender_config_candidates()) {
    searched.push_back(file);
    std::error_code ec;
    if (fs::is_regular_file(file, ec)) return OcioConfigChoice{file, "Blender's", false};
  }
  return std::nullopt;
}

}  // namespace fb
