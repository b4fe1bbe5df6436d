#include "tests/blender/blender_shot.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/image/image_io.h"
#include "tests/support/commands.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

// Cycles ends its log with " Time: MM:SS.ss (Saving: ...)"; 0 if absent.
double cycles_render_s(const std::string& log) {
  const size_t at = log.rfind("\n Time: ");
  int minutes = 0;
  double seconds = 0;
  if (at == std::string::npos ||
      std::sscanf(log.c_str() + at, "\n Time: %d:%lf", &minutes, &seconds) != 2)
    return 0;
  return 60 * minutes + seconds;
}

}  // namespace

const std::string& Record::text(const std::string& key) const {
  const auto it = fields.find(key);
  if (it == fields.end()) {
    const auto name = fields.find("name");
    throw std::runtime_error("manifest: " + kind + " '" +
                             (name == fields.end() ? "" : name->second) + "' has no " + key);
  }
  return it->second;
}

double Record::number(const std::string& key) const {
  return std::stod(text(key));
}

std::vector<Record> read_manifest(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("make_shot.py wrote no " + file.string());
  std::vector<Record> records;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    Record r;
    if (!(words >> r.kind)) continue;
    for (std::string word; words >> word;) {
      const size_t eq = word.find('=');
      if (eq == std::string::npos)
        throw std::runtime_error(file.string() + ": '" + word + "' is not key=value");
      r.fields[word.substr(0, eq)] = word.substr(eq + 1);
    }
    records.push_back(std::move(r));
  }
  return records;
}

std::optional<fs::path> find_blender() {
  return find_on_path("blender");
}

ShotRenders render_shot(const fs::path& blender, const std::string& shot, const fs::path& work,
                        const fs::path& script, const std::vector<std::string>& extra_outputs) {
  fs::remove_all(work);
  fs::create_directories(work);
  ShotRenders r;
  const fs::path bpy_script = script.empty() ? fs::path(FILMBACK_MAKE_SHOT_PY) : script;
  r.blender_s =
      run_logged(quoted(blender) + " -b --factory-startup --python-exit-code 1 --python " +
                     quoted(bpy_script) + " -- " + quoted(work) + " " + shot,
                 work / "blender.log");
  r.cycles_s = cycles_render_s(read_text(work / "blender.log"));
  for (Record& record : read_manifest(work / "manifest.txt")) {
    if (record.kind == "shot")
      r.shot = std::move(record);
    else if (record.kind == "marker")
      r.markers.push_back(std::move(record));
    else
      throw std::runtime_error("manifest: unknown record kind '" + record.kind + "'");
  }
  // No --res and no --filter: the shot's resolution and pixel filter (Cycles' 1 px box) come
  // from the file's FILMBACK_blender extension.
  std::string outputs = " -o " + quoted(work / "filmback.exr");
  for (const std::string& name : extra_outputs)
    outputs += " -o " + quoted(work / name);
  r.filmback_s = run_logged(quoted(FILMBACK_EXE) + " render " + quoted(work / "shot.gltf") +
                                outputs + " --spp " + r.shot.text("samples"),
                            work / "filmback.log");
  r.filmback_log = read_text(work / "filmback.log");
  r.cycles = read_image(work / "cycles.exr");
  r.filmback = read_image(work / "filmback.exr");
  return r;
}

}  // namespace fb::test
