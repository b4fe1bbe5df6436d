#include "tests/blender/blender_shot.h"

#include <sys/wait.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/image/image_io.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& path) {  // for /bin/sh: '...' with each ' written as '\''
  std::string out = "'";
  for (char c : path.string())
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string last_lines(const std::string& text, size_t count) {
  std::istringstream in(text);
  std::deque<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
    if (lines.size() > count) lines.pop_front();
  }
  std::string out;
  for (const std::string& line : lines)
    out += line + "\n";
  return out;
}

// Runs a shell command with its output in `log`; returns the wall time, or throws with the log's
// tail.
double run_logged(const std::string& command, const fs::path& log) {
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system((command + " > " + quoted(log) + " 2>&1").c_str());
  const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("command failed (status " + std::to_string(status) + "): " + command +
                             "\nlast lines of " + log.string() + ":\n" +
                             last_lines(read_text(log), 30));
  return seconds.count();
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

std::optional<fs::path> find_blender() {
  const char* path = std::getenv("PATH");
  std::string rest = path ? path : "";
  while (!rest.empty()) {
    const size_t colon = rest.find(':');
    const fs::path candidate = fs::path(rest.substr(0, colon)) / "blender";
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate;
    rest = colon == std::string::npos ? "" : rest.substr(colon + 1);
  }
  return std::nullopt;
}

ShotRenders render_shot(const fs::path& blender, const std::string& shot, const fs::path& work,
                        const fs::path& script) {
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
  r.filmback_s = run_logged(quoted(FILMBACK_EXE) + " render " + quoted(work / "shot.gltf") +
                                " -o " + quoted(work / "filmback.exr") + " --spp " +
                                r.shot.text("samples"),
                            work / "filmback.log");
  r.filmback_log = read_text(work / "filmback.log");
  r.cycles = read_image(work / "cycles.exr");
  r.filmback = read_image(work / "filmback.exr");
  return r;
}

}  // namespace fb::test
