// The SDL tests' fixture: a scene folder of its own per test (scene/ and lib/, the library path),
// and helpers that read SDL values back through the scene.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/util/error.h"
#include "importers/pov/sdl/evaluate.h"

namespace fb::pov {

// A scene folder of its own per test, with helper files.
class Sdl : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ =
        std::filesystem::temp_directory_path() / ("filmback_pov_sdl_" + std::string(info->name()));
    std::filesystem::remove_all(root_);
    std::filesystem::create_directories(root_ / "scene");
    std::filesystem::create_directories(root_ / "lib");
  }
  void TearDown() override { std::filesystem::remove_all(root_); }

  void write(const std::filesystem::path& relative, const std::string& text) {
    std::filesystem::create_directories((root_ / relative).parent_path());
    std::ofstream(root_ / relative) << text;
  }
  Scene run(const std::string& text, EvaluateOptions options = {}) {
    write("scene/scene.pov", text);
    options.scene_file = root_ / "scene" / "scene.pov";
    options.library_paths = {root_ / "lib"};
    return evaluate_pov(options);
  }
  std::string error_of(const std::string& text, EvaluateOptions options = {}) {
    try {
      run(text, options);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  // The sphere the scene's only object is: SDL values are read back through its centre/radius.
  Vec3d centre(const std::string& text) {
    Scene scene = run(text);
    EXPECT_EQ(scene.objects.size(), 1u);
    return scene.objects.empty() ? Vec3d{NAN, NAN, NAN} : scene.objects[0].a;
  }
  double number(const std::string& expression) {
    Scene scene = run("sphere { 0, " + expression + " }");
    return scene.objects.at(0).r0;
  }
  // Asserts an SDL condition inside the evaluator.
  void sdl_true(const std::string& condition) {
    EXPECT_NO_THROW(run("#if (!(" + condition + ")) #error \"false\" #end")) << condition;
  }

  std::filesystem::path root_;
};

}  // namespace fb::pov
