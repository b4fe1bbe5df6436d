#include "core/cmd/pre_pass_arguments.h"

#include "core/cmd/frame_range.h"

namespace fb {
namespace fs = std::filesystem;
namespace {

// Options of `render` the pre-pass replaces or must not inherit, and whether each takes a value.
struct Dropped {
  const char* name;
  bool takes_value;
};
constexpr Dropped kDropped[] = {
    {"--spp", true},        {"-o", true},
    {"--output", true},     {"--stats-json", true},
    {"-q", false},          {"--quiet", false},
    {"--checkpoint", true}, {"--checkpoint-every", true},
    {"--resume", false},    {"--tile", true},
    {"--crop", true},       {"--tile-plan", true},
    {"--frames", true},     {"--overwrite", false},
};

}  // namespace

std::vector<std::string> pre_pass_arguments(const fs::path& scene,
                                            const std::vector<std::string>& render_arguments,
                                            uint32_t spp, const fs::path& image,
                                            const fs::path& report) {
  std::vector<std::string> out = {"render", scene.string()};
  std::string frames;
  for (size_t i = 0; i < render_arguments.size(); ++i) {
    const std::string& arg = render_arguments[i];
    const Dropped* dropped = nullptr;
    std::string value;
    bool value_inline = false;
    for (const Dropped& d : kDropped) {
      const std::string name = d.name;
      const bool is_short = name.size() == 2;
      if (arg == name)
        dropped = &d;
      else if (d.takes_value && arg.rfind(name + "=", 0) == 0)
        dropped = &d, value = arg.substr(name.size() + 1), value_inline = true;
      else if (d.takes_value && is_short && arg.size() > 2 && arg.rfind(name, 0) == 0)
        dropped = &d, value = arg.substr(2), value_inline = true;
      if (dropped) break;
    }
    if (!dropped) {
      out.push_back(arg);
      continue;
    }
    if (dropped->takes_value && !value_inline && i + 1 < render_arguments.size())
      value = render_arguments[++i];
    if (std::string(dropped->name) == "--frames") frames = value;
  }
  // A frame range plans its first frame: the parts of every frame share the plan.
  if (!frames.empty())
    out.insert(out.end(), {"--frame", std::to_string(parse_frame_range(frames).first)});
  out.insert(out.end(), {"--spp", std::to_string(spp), "-q", "-o", image.string(), "--stats-json",
                         report.string()});
  return out;
}

}  // namespace fb
