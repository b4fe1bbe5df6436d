// Running one shot of make_shot.py through both renderers: Debian's Blender builds the shot,
// exports it through filmback's add-on and renders it with Cycles; the built `filmback` renders
// the export at the shot's own resolution and pixel filter (Cycles' 1 px box, both from the
// file's FILMBACK_blender extension) and the same sample count. Shared by the tests against
// Blender.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/image/image.h"

namespace fb::test {

// One line of make_shot.py's manifest.txt: "KIND key=value ...".
struct Record {
  std::string kind;
  std::map<std::string, std::string> fields;
  // The field's value; throws std::runtime_error naming the record when it is missing.
  const std::string& text(const std::string& key) const;
  double number(const std::string& key) const;  // "nan" reads as NaN
};

struct ShotRenders {
  Record shot;                  // name, samples, width_px, height_px, camera_model, ...
  std::vector<Record> markers;  // name, blender_x_px, image_x_px, diameter_x_px, ...
  Image cycles, filmback;
  double blender_s = 0, filmback_s = 0;  // wall times: Blender (build, export, Cycles), filmback
  double cycles_s = 0;                   // Cycles' own render time, from Blender's log
  std::string filmback_log;              // its plan line says which camera model it chose
};

// The records of a manifest.txt; throws std::runtime_error naming the file when it is missing or
// a word is not key=value.
std::vector<Record> read_manifest(const std::filesystem::path& file);

// The `blender` executable on PATH, if any.
std::optional<std::filesystem::path> find_blender();

// A test against Blender (Base: testing::Test or testing::TestWithParam<T>): skipped, naming the
// Debian package to install, where `blender` is not on PATH; else `blender` is its executable.
template <class Base = testing::Test>
class WithBlender : public Base {
 protected:
  void SetUp() override {
    const std::optional<std::filesystem::path> found = find_blender();
    if (!found)
      GTEST_SKIP() << "Blender is not installed: no `blender` on PATH. Install Debian's package "
                      "`blender` (apt-get install blender) to run the tests against Blender.";
    blender = *found;
  }
  std::filesystem::path blender;
};

// Renders `shot` of the bpy script `script` (default: make_shot.py) into `work_dir` (emptied
// first) with both renderers. The script runs as `blender -b --factory-startup --python SCRIPT
// -- WORK_DIR SHOT` and writes shot.gltf, cycles.exr and manifest.txt there. filmback writes
// filmback.exr, and each of `extra_outputs` (file names in `work_dir`) from the same render.
// Throws std::runtime_error with the tail of the failing program's log when a step fails.
ShotRenders render_shot(const std::filesystem::path& blender, const std::string& shot,
                        const std::filesystem::path& work_dir,
                        const std::filesystem::path& script = {},
                        const std::vector<std::string>& extra_outputs = {});

}  // namespace fb::test
