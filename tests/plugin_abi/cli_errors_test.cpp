// The broken plugins seen from the command line: `filmback plugins` lists the good plugins and
// prints one error per broken file, and `filmback render` with a broken plugin selected stops
// with exit status 1, names the file and writes nothing.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/plugin/loader.h"
#include "tests/plugin_abi/test_plugin_folders.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

using test::kDuplicates;
using test::kTestPlugins;
const fs::path kCrashPlugins = FB_TEST_CRASH_DIR;

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

// A fresh folder for the running test: CTest may run the tests in parallel.
fs::path scratch_dir() {
  const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(FB_SCRATCH_DIR) / test->test_suite_name() / test->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

struct Outcome {
  int status;
  std::string out, err;
};

// `filmback <args>` with FILMBACK_PLUGIN_PATH set; arguments are build-tree paths and plugin
// specs, which hold no quote.
Outcome run_filmback(const std::string& args, const std::string& plugin_path,
                     const fs::path& scratch) {
  const fs::path out = scratch / "stdout.txt", err = scratch / "stderr.txt";
  const std::string command = "FILMBACK_PLUGIN_PATH='" + plugin_path + "' '" FB_FILMBACK_EXE "' " +
                              args + " >'" + out.string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(command.c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read_text(out), read_text(err)};
}

TEST(PluginsCommand, ListsTheGoodPluginsAndOneErrorPerBrokenFile) {
  const std::string path = kTestPlugins.string() + ":" + kDuplicates.string();
  const Outcome run = run_filmback("plugins", path, scratch_dir());
  EXPECT_EQ(run.status, 1) << run.err;

  // Listed: every product plugin, and the two test plugins the loader accepts.
  std::vector<fs::path> good = {kTestPlugins / "libfilmback_filter_ctent.so",
                                kTestPlugins / "libfilmback_filter_refuse.so"};
  for (const auto& entry : fs::directory_iterator(FB_PRODUCT_PLUGIN_DIR))
    good.push_back(entry.path());
  ASSERT_GE(good.size(), 2u + 6u);  // perspective, orthographic, box, gaussian, path, aov
  for (const fs::path& file : good)
    EXPECT_NE(run.out.find("  file " + file.string() + "\n"), std::string::npos) << file;

  // One error line per broken file, naming it: every other file in test_plugins/, and the copy.
  std::vector<fs::path> broken = {kDuplicates / "libfilmback_filter_ctent.so"};
  for (const auto& entry : fs::directory_iterator(kTestPlugins))
    if (std::find(good.begin(), good.end(), entry.path()) == good.end())
      broken.push_back(entry.path());
  const std::vector<std::string> errors = lines_of(run.err);
  EXPECT_EQ(errors.size(), broken.size()) << run.err;
  for (const fs::path& file : broken)
    EXPECT_EQ(std::count_if(errors.begin(), errors.end(),
                            [&](const std::string& line) {
                              return line.find(file.string()) != std::string::npos;
                            }),
              1)
        << file << " in\n"
        << run.err;

  // And each line is the loader's own message (loader_errors_test.cpp checks their wording).
  std::vector<std::string> expected;
  for (const std::string& error : PluginLoader({kTestPlugins, kDuplicates}).load_all().errors)
    expected.push_back("filmback: error: " + error);
  EXPECT_EQ(errors, expected);
}

struct RenderCase {
  const char* test_name;
  const char* option;           // "--filter ctent:radius=1"
  std::vector<fs::path> files;  // the files the message must name
  const char* reason;           // a piece of the reason
};

void PrintTo(const RenderCase& c, std::ostream* out) {
  *out << c.option;
}

class RenderWithPluginTest : public testing::TestWithParam<RenderCase> {};

const char* kRender = "render '" FB_DEFAULT_SCENE "' --res 32x18 --spp 1 -q -o ";

// The control: the same command line with a good plugin renders, so a failure below is the
// plugin's and not the command's.
TEST(RenderWithPlugin, PlainCPluginRenders) {
  const fs::path scratch = scratch_dir();
  const fs::path image = scratch / "out.exr";
  const Outcome run = run_filmback(kRender + image.string() + " --filter ctent:radius=1.5",
                                   kTestPlugins.string(), scratch);
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(fs::is_regular_file(image));
}

TEST_P(RenderWithPluginTest, FailsNamingTheFileAndWritesNothing) {
  const RenderCase& c = GetParam();
  const fs::path scratch = scratch_dir();
  const fs::path image = scratch / "out.exr";
  const std::string path = kTestPlugins.string() + ":" + kDuplicates.string();
  const Outcome run = run_filmback(kRender + image.string() + " " + c.option, path, scratch);
  EXPECT_EQ(run.status, 1) << run.err;
  // The scene's own warnings come first; then exactly one error.
  std::vector<std::string> errors = lines_of(run.err);
  std::erase_if(errors, [](const std::string& line) { return line.starts_with("warning: "); });
  ASSERT_EQ(errors.size(), 1u) << run.err;
  EXPECT_TRUE(errors[0].starts_with("filmback: error: ")) << errors[0];
  for (const fs::path& file : c.files)
    EXPECT_NE(errors[0].find(file.string()), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find(c.reason), std::string::npos) << errors[0];
  EXPECT_FALSE(fs::exists(image));
}

// A plugin that faults in create(), in radius() (asked once, before the render) or while its
// descriptor is read takes the process down with it; filmback reports it naming the file and
// what was running, exits with status 1 and writes nothing (core/plugin/crash_guard.h). The
// signal's name ends the message.
TEST(RenderWithPlugin, CrashingPluginIsReportedNamingTheFile) {
  const struct {
    const char* option;
    fs::path file;
    const char* doing;
  } cases[] = {
      {"--filter crashcreate", kCrashPlugins / "libfilmback_filter_crashcreate.so", "create()"},
      {"--filter crashradius", kCrashPlugins / "libfilmback_filter_crashradius.so", "radius()"},
      {"--filter crashdescriptor", kCrashPlugins / "libfilmback_filter_crashdescriptor.so",
       "filmback_plugin_v1() or the descriptor it returned"}};
  for (const auto& c : cases) {
    const fs::path scratch = scratch_dir();
    const fs::path image = scratch / "out.exr";
    const Outcome run =
        run_filmback(kRender + image.string() + " " + c.option, kCrashPlugins.string(), scratch);
    EXPECT_EQ(run.status, 1) << run.err;
    std::vector<std::string> errors = lines_of(run.err);
    std::erase_if(errors, [](const std::string& line) { return line.starts_with("warning: "); });
    ASSERT_EQ(errors.size(), 1u) << run.err;
    EXPECT_EQ(errors[0], "filmback: error: " + c.file.string() + ": the plugin crashed in " +
                             c.doing + " (SIGSEGV); no render was started");
    EXPECT_FALSE(fs::exists(image));
  }
}

const fs::path kCtent = "libfilmback_filter_ctent.so";

INSTANTIATE_TEST_SUITE_P(
    RenderWithPlugin, RenderWithPluginTest,
    testing::Values(
        RenderCase{"no_entry_point",
                   "--filter noentry",
                   {kTestPlugins / "libfilmback_filter_noentry.so"},
                   ": not a filmback plugin: it has no filmback_plugin_v1 entry point"},
        RenderCase{"missing_symbol",
                   "--filter unresolved",
                   {kTestPlugins / "libfilmback_filter_unresolved.so"},
                   ": missing symbol: fb_test_absent_function"},
        RenderCase{"wrong_kind",
                   "--camera-model wrongkind",
                   {kTestPlugins / "libfilmback_camera_wrongkind.so"},
                   ": wrong kind: the file name says camera, the plugin declares itself a filter"},
        RenderCase{"duplicate",
                   "--filter ctent",
                   {kTestPlugins / kCtent, kDuplicates / kCtent},
                   "duplicate plugin name: filter 'ctent'"},
        RenderCase{"create_fails",
                   "--filter refuse",
                   {kTestPlugins / "libfilmback_filter_refuse.so"},
                   ": filter 'refuse' refused to start: this test filter always refuses"}),
    [](const testing::TestParamInfo<RenderCase>& info) {
      return std::string(info.param.test_name);
    });

}  // namespace
}  // namespace fb
