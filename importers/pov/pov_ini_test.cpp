#include "importers/pov/pov_ini.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/util/error.h"
#include "importers/pov/sdl/evaluate.h"

namespace fb::pov {
namespace {

namespace fs = std::filesystem;

// A folder of its own per test, holding the .ini files it writes.
class PovIni : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::temp_directory_path() / ("filmback_pov_ini_" + std::string(info->name()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "scene");
  }
  void TearDown() override { fs::remove_all(root_); }

  fs::path write(const fs::path& relative, const std::string& text) {
    fs::create_directories((root_ / relative).parent_path());
    std::ofstream(root_ / relative) << text;
    return root_ / relative;
  }
  IniOptions read(const std::string& text, const std::string& section = {}) {
    return read_ini(write("scene/scene.ini", text), section);
  }
  std::string error_of(const std::string& text) {
    try {
      read(text);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  }
  fs::path root_;
};

TEST_F(PovIni, ReadsKeysAndSwitchesCaseInsensitively) {
  const IniOptions ini = read(
      "; comment\n"
      "INPUT_FILE_NAME = \"shot.pov\" ; the scene\n"
      "+W200 +h100 -D\n"
      "Antialias_Threshold=0.1\n"
      "+R4\n"
      "Library_Path=inc\n"
      "Declare=Speed=2.5\n"
      "Output_File_Name=render/shot\n"
      "Output_File_Type=E\n");
  ASSERT_TRUE(ini.input_file);
  EXPECT_EQ(*ini.input_file, (root_ / "scene" / "shot.pov").lexically_normal());
  EXPECT_EQ(ini.width, 200u);
  EXPECT_EQ(ini.height, 100u);
  EXPECT_EQ(ini.antialias_threshold, 0.1);
  EXPECT_EQ(ini.antialias_depth, 4u);
  ASSERT_EQ(ini.library_paths.size(), 1u);
  EXPECT_EQ(ini.library_paths[0], (root_ / "scene" / "inc").lexically_normal());
  ASSERT_EQ(ini.declarations.size(), 1u);
  EXPECT_EQ(ini.declarations[0].first, "Speed");
  EXPECT_EQ(ini.declarations[0].second, 2.5);
  EXPECT_EQ(ini.output_file_type, 'E');
  EXPECT_FALSE(ini.clock);
  EXPECT_EQ(read("+K0.25").clock, 0.25);  // a still's clock
  EXPECT_EQ(read("Clock=-2").clock, -2);
  EXPECT_TRUE(ini.warnings.empty()) << ini.warnings.front();
}

TEST_F(PovIni, BooleansInEveryFormPovRayTakes) {
  for (const char* yes : {"on", "True", "yes", "1"})
    EXPECT_EQ(read(std::string("Antialias=") + yes).antialias, true) << yes;
  for (const char* no : {"Off", "false", "NO", "0"})
    EXPECT_EQ(read(std::string("Antialias=") + no).antialias, false) << no;
  // Key=Value among switches, as animations/splinefollow/splinefollow.ini writes it.
  const IniOptions mixed = read("+kf0.5 +kff20 +kc declare=fp=0");
  ASSERT_EQ(mixed.declarations.size(), 1u);
  EXPECT_EQ(mixed.declarations[0].first, "fp");
  ASSERT_TRUE(mixed.animation);
  EXPECT_EQ(mixed.animation->final_clock, 0.5);
  EXPECT_TRUE(mixed.animation->cyclic);
  EXPECT_EQ(read("+A0.2").antialias, true);
  EXPECT_EQ(read("+A0.2").antialias_threshold, 0.2);
  EXPECT_EQ(read("Antialias=on\n-A").antialias, false);  // the last one wins
  EXPECT_NE(error_of("Antialias=maybe").find("expected on/off"), std::string::npos);
}

TEST_F(PovIni, SectionsAreReadOnlyWhenSelected) {
  const std::string text = "+W120 +H100\n[Low]\n+W80 +H60\n[Really High]\n+W800 +H600\n";
  EXPECT_EQ(read(text).width, 120u);
  EXPECT_EQ(read(text, "low").width, 80u);
  EXPECT_EQ(read(text, "REALLY HIGH").height, 600u);
  EXPECT_THROW(read(text, "Medium"), InputError);
  EXPECT_EQ(split_ini_section("res.ini[Really High]"),
            (std::pair<fs::path, std::string>{"res.ini", "Really High"}));
  EXPECT_EQ(split_ini_section("res.ini").second, "");
  EXPECT_TRUE(is_ini_argument("RES.INI[Really High]"));
  EXPECT_TRUE(is_ini_argument("dir/res.ini"));
  EXPECT_FALSE(is_ini_argument("scene.pov"));
  EXPECT_FALSE(is_ini_argument("ini"));
}

TEST_F(PovIni, AnimationClockAsPovRayComputesIt) {
  // povray 3.7.0.10 with these options prints clock 2.4 at frame 4 and clock_delta 0.4.
  const IniOptions ini = read(
      "Initial_Frame=3\nFinal_Frame=7\nInitial_Clock=2\nFinal_Clock=4\nCyclic_Animation=on\n"
      "Subset_Start_Frame=4\nSubset_End_Frame=5\n");
  ASSERT_TRUE(ini.animation);
  EXPECT_DOUBLE_EQ(ini.animation->clock_delta(), 0.4);
  EXPECT_DOUBLE_EQ(ini.animation->clock_at(4), 2.4);
  const std::optional<IniFrames> frames = ini_frames(ini, "scene.ini");
  ASSERT_TRUE(frames);
  EXPECT_EQ(frames->first, 4);
  EXPECT_EQ(frames->last, 5);
  Animation open = *ini.animation;
  open.cyclic = false;  // the last frame reaches Final_Clock
  EXPECT_DOUBLE_EQ(open.clock_at(7), 4);
  EXPECT_FALSE(ini_frames(read("+W10"), "scene.ini"));
  // A subset as a fraction of the sequence: the second half of 1 to 11.
  const std::optional<IniFrames> half =
      ini_frames(read("+KFI1 +KFF11\nSubset_Start_Frame=0.5"), "scene.ini");
  ASSERT_TRUE(half);
  EXPECT_EQ(half->first, 6);
  EXPECT_THROW(ini_frames(read("+KFI1 +KFF3 +SF5"), "scene.ini"), InputError);
}

TEST_F(PovIni, OutputPatternAsPovRayNamesFrames) {
  EXPECT_EQ(ini_output_pattern(read("Output_File_Name=allnormals\n+KFI1 +KFF33"), "a.pov"),
            fs::path("allnormals##.png"));
  EXPECT_EQ(ini_output_pattern(read("Output_File_Name=out/\n+KFF7\n+FE"), "shot.pov"),
            fs::path("out/shot#.exr"));
  EXPECT_EQ(ini_output_pattern(read("Output_File_Name=still.png"), "a.pov"), fs::path("still.png"));
  EXPECT_FALSE(ini_output_pattern(read("+W10"), "a.pov"));
  EXPECT_FALSE(ini_output_pattern(read("Output_File_Name="), "a.pov"));  // benchmark.ini's
  EXPECT_NE(error_of("Output_File_Name=../../home/x").find("without '..'"), std::string::npos);
}

TEST_F(PovIni, DeclarationsReachTheScene) {
  write("scene/scene.pov", "#declare Doubled = Speed * 2;\n");
  EvaluateOptions options;
  options.scene_file = root_ / "scene" / "scene.pov";
  options.declarations = read("Declare=Speed=1.25").declarations;
  options.animation = Animation{1, 9, 0, 2, false};
  EXPECT_NO_THROW(evaluate_pov(options));
  write("scene/scene.pov",
        "#if (Speed != 1.25 | clock_delta != 0.25 | final_frame != 9) #error \"wrong\" #end\n");
  EXPECT_NO_THROW(evaluate_pov(options));
  EXPECT_NE(error_of("Declare=9lives=1").find("expected IDENTIFIER=FLOAT"), std::string::npos);
}

TEST_F(PovIni, UnknownOptionsAreWarningsNamingTheLine) {
  const IniOptions ini = read("+W10\nPause_when_Done=off\nJitter=on\n+Q9\n");
  ASSERT_EQ(ini.warnings.size(), 2u);
  const std::string file = (root_ / "scene" / "scene.ini").string();
  EXPECT_EQ(ini.warnings[0].rfind(file + ":3: 'Jitter'", 0), 0u) << ini.warnings[0];
  EXPECT_EQ(ini.warnings[1].rfind(file + ":4: '+Q9'", 0), 0u) << ini.warnings[1];
}

TEST_F(PovIni, ErrorsNameFileLineAndColumn) {
  const std::string file = (root_ / "scene" / "scene.ini").string();
  EXPECT_EQ(error_of("+W10\nWidth = 12x"),
            file + ":2:9: error: Width '12x': expected a number from 1 to 32768");
  EXPECT_EQ(error_of("; huge\n+W10 +H1e300"),
            file + ":2:8: error: +H '1e300': expected a number from 1 to 32768");
  EXPECT_NE(error_of("Final_Frame=1e12").find(":1:13: error: Final_Frame"), std::string::npos);
  EXPECT_NE(error_of("Width=2.5").find("expected a whole number"), std::string::npos);
  EXPECT_NE(error_of("[Open").find(":1:1: error:"), std::string::npos);
  // An empty value is located where it would be (portfolio/__empty.ini's "Final_Frame=").
  EXPECT_EQ(error_of("Final_Frame= "),
            file + ":1:13: error: Final_Frame '': expected a number from -1e+09 to 1e+09");
}

TEST_F(PovIni, PathsStayInsideTheIniFolder) {
  write("secret.pov", "");
  EXPECT_NE(error_of("Input_File_Name=../secret.pov").find("expected a path inside"),
            std::string::npos);
  EXPECT_NE(error_of("Input_File_Name=/etc/passwd").find("expected a path inside"),
            std::string::npos);
  fs::create_symlink(root_ / "secret.pov", root_ / "scene" / "link.pov");
  EXPECT_NE(error_of("Input_File_Name=link.pov").find("expected a path inside"), std::string::npos);
  const IniOptions ini = read("Library_Path=/usr/share/povray-3.7/include");
  EXPECT_TRUE(ini.library_paths.empty());
  ASSERT_EQ(ini.warnings.size(), 1u);
  EXPECT_NE(ini.warnings[0].find("give it with -L"), std::string::npos);
}

TEST_F(PovIni, NestedFilesAreReadAndCyclesRefused) {
  write("scene/sub/size.ini", "+W64\nmore\n");
  write("scene/sub/more.ini", "+H32\n");
  const IniOptions ini = read("Include_Ini=sub/size.ini\n");
  EXPECT_EQ(ini.width, 64u);
  EXPECT_EQ(ini.height, 32u);  // "more" names sub/more.ini, next to the file that names it
  write("scene/a.ini", "b.ini\n");
  write("scene/b.ini", "+W1\nInclude_Ini=a.ini\n");
  const std::string cycle = error_of("a\n");
  EXPECT_NE(cycle.find("b.ini:2:13: error: 'a.ini': includes itself"), std::string::npos) << cycle;
  EXPECT_NE(cycle.find("included from"), std::string::npos) << cycle;
  // A chain deeper than the bound, each file a new one.
  for (int i = 0; i < kMaxIniIncludeDepth + 2; ++i)
    write("scene/deep" + std::to_string(i) + ".ini", "deep" + std::to_string(i + 1) + "\n");
  EXPECT_NE(error_of("deep0\n").find("nested more than"), std::string::npos);
}

TEST_F(PovIni, OversizedFileRefused) {
  const std::string huge(kMaxIniFileBytes + 1, ';');
  EXPECT_NE(error_of(huge).find("expected an .ini of at most"), std::string::npos);
}

}  // namespace
}  // namespace fb::pov
