// The loader against deliberately broken plugins (broken_filter.c, one defect each): every
// failure names the file and says what is wrong, the same way whether a render loads one plugin
// or `filmback plugins` scans them all. Also the plain-C plugin, called through the ABI.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/plugin/instances.h"
#include "core/plugin/loader.h"
#include "core/plugin/params.h"
#include "core/util/error.h"
#include "tests/plugin_abi/test_plugin_folders.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

using test::kDuplicates;
using test::kTestPlugins;

// The message of the InputError that load() throws; a test fails if it loads.
std::string load_error(const std::vector<fs::path>& dirs, uint32_t kind, const std::string& name) {
  try {
    PluginLoader(dirs).load(kind, name);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << kind_name(kind) << " '" << name << "' loaded, expected an error";
  return {};
}

struct BrokenCase {
  const char* name;  // also the test's name
  uint32_t kind;     // the kind the file name says
  std::string reason;
};

// The exact reasons, after "<file>: ". Sizes are the test's own build of the same SDK headers.
const std::vector<BrokenCase>& broken_cases() {
  static const std::vector<BrokenCase> cases = {
      {"noentry", FB_KIND_FILTER,
       "not a filmback plugin: it has no filmback_plugin_v1 entry point"},
      {"futureabi", FB_KIND_FILTER,
       "ABI version mismatch: the plugin was built for plugin ABI 2, this filmback speaks 1 "
       "(rebuild it against this SDK)"},
      {"bigdescriptor", FB_KIND_FILTER,
       "plugin newer than this filmback: its fb_plugin is " +
           std::to_string(sizeof(fb_plugin) + sizeof(void*)) + " bytes, this filmback's is " +
           std::to_string(sizeof(fb_plugin)) +
           " (update filmback, or rebuild the plugin against this SDK)"},
      {"bigtable", FB_KIND_FILTER,
       "plugin newer than this filmback: its filter function table is " +
           std::to_string(sizeof(fb_filter_api) + sizeof(void (*)())) +
           " bytes, this filmback's is " + std::to_string(sizeof(fb_filter_api)) +
           " (update filmback, or rebuild the plugin against this SDK)"},
      {"wrongkind", FB_KIND_CAMERA,
       "wrong kind: the file name says camera, the plugin declares itself a filter"},
      {"misnamed", FB_KIND_FILTER,
       "name mismatch: the file name says 'misnamed', the plugin declares the name 'othername'"},
      {"unresolved", FB_KIND_FILTER,
       "missing symbol: fb_test_absent_function (the plugin needs a symbol nothing "
       "provides)"},
      {"nolibrary", FB_KIND_FILTER,
       "missing library: libfb_test_absent.so (the plugin needs a shared library the dynamic "
       "loader cannot find)"},
      {"nosample", FB_KIND_FILTER, "incomplete plugin: its filter function table lacks 'sample'"},
      {"baddefault", FB_KIND_FILTER,
       "parameter 'radius' has default '-1', expected a number in [0.5, 0.5]"},
  };
  return cases;
}

void PrintTo(const BrokenCase& c, std::ostream* out) {
  *out << kind_name(c.kind) << " " << c.name;
}

fs::path file_of(uint32_t kind, const std::string& name) {
  return kTestPlugins / plugin_file_name(kind, name);
}

class BrokenPluginTest : public testing::TestWithParam<BrokenCase> {};

TEST_P(BrokenPluginTest, LoadNamesTheFileAndTheReason) {
  const BrokenCase& c = GetParam();
  EXPECT_EQ(load_error({kTestPlugins}, c.kind, c.name),
            file_of(c.kind, c.name).string() + ": " + c.reason);
}

INSTANTIATE_TEST_SUITE_P(Loader, BrokenPluginTest, testing::ValuesIn(broken_cases()),
                         [](const testing::TestParamInfo<BrokenCase>& info) {
                           return std::string(info.param.name);
                         });

// A text file named like a plugin: dlopen's own reason follows, without the path a second time.
TEST(Loader, NotASharedLibrary) {
  const std::string file = file_of(FB_KIND_FILTER, "junk").string();
  const std::string message = load_error({kTestPlugins}, FB_KIND_FILTER, "junk");
  const std::string head = file + ": not a filmback plugin: cannot load it as a shared library (";
  ASSERT_EQ(message.substr(0, head.size()), head);
  EXPECT_EQ(message.back(), ')');
  EXPECT_EQ(message.find(file, 1), std::string::npos) << message;
}

TEST(Loader, DuplicateNameNamesBothFiles) {
  const std::string file = plugin_file_name(FB_KIND_FILTER, "ctent");
  EXPECT_EQ(load_error({kTestPlugins, kDuplicates}, FB_KIND_FILTER, "ctent"),
            "duplicate plugin name: filter 'ctent' is provided by " +
                (kTestPlugins / file).string() + " and by " + (kDuplicates / file).string());
}

TEST(Loader, CreateFailureReachesTheUserNamingTheFile) {
  const auto library = PluginLoader({kTestPlugins}).load(FB_KIND_FILTER, "refuse");
  const BoundParams params(library->descriptor(), {});
  try {
    FilterInstance filter(library, params);
    FAIL() << "create() of 'refuse' succeeded";
  } catch (const InputError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        file_of(FB_KIND_FILTER, "refuse").string() +
            ": filter 'refuse' refused to start: this test filter always refuses (radius 0.5 px)");
  }
}

// `filmback plugins` scans a folder: each broken file gives exactly the message load() gives,
// and the broken files do not keep the good ones from loading.
TEST(Loader, ScanReportsEachBrokenFileOnceAndKeepsTheGoodOnes) {
  const PluginLoader::Scan scan = PluginLoader({kTestPlugins}).load_all();
  std::vector<std::string> names;
  for (const auto& library : scan.plugins)
    names.emplace_back(library->descriptor().name);
  EXPECT_EQ(names, (std::vector<std::string>{"ctent", "refuse"}));

  std::vector<std::string> expected;
  for (const BrokenCase& c : broken_cases())
    expected.push_back(file_of(c.kind, c.name).string() + ": " + c.reason);
  expected.push_back(load_error({kTestPlugins}, FB_KIND_FILTER, "junk"));
  std::vector<std::string> errors = scan.errors;
  std::sort(errors.begin(), errors.end());
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(errors, expected);
}

TEST(Loader, ScanReportsADuplicateAndKeepsTheFirst) {
  const PluginLoader::Scan scan = PluginLoader({kTestPlugins, kDuplicates}).load_all();
  const std::string duplicate = load_error({kTestPlugins, kDuplicates}, FB_KIND_FILTER, "ctent");
  EXPECT_EQ(std::count(scan.errors.begin(), scan.errors.end(), duplicate), 1);
  EXPECT_EQ(scan.errors.size(), broken_cases().size() + 2);  // + junk + the duplicate
  const auto ctent = std::find_if(
      scan.plugins.begin(), scan.plugins.end(),
      [](const auto& library) { return std::string(library->descriptor().name) == "ctent"; });
  ASSERT_NE(ctent, scan.plugins.end());
  EXPECT_EQ((*ctent)->file(), file_of(FB_KIND_FILTER, "ctent"));
}

// The plugin written in C99, called through the ABI: analytic values of the tent filter,
// t(x) = (1 - |x|/r) / r, with r = 2 px.
TEST(PlainCPlugin, LoadsAndComputesTheTent) {
  const auto library = PluginLoader({kTestPlugins}).load(FB_KIND_FILTER, "ctent");
  const BoundParams params(library->descriptor(), {{"radius", "2"}});
  const FilterInstance filter(library, params);
  float radius_px[2] = {0, 0};
  filter.radius(radius_px);
  EXPECT_EQ(radius_px[0], 2.f);
  EXPECT_EQ(radius_px[1], 2.f);
  EXPECT_FLOAT_EQ(filter.evaluate(0, 0), 0.25f);   // (1/2)^2
  EXPECT_FLOAT_EQ(filter.evaluate(1, 0), 0.125f);  // (1/4)(1/2)
  EXPECT_EQ(filter.evaluate(2.5f, 0), 0.f);
  EXPECT_EQ(filter.integral(), 1.0);
  // Inverse CDF: u = 1/8 -> x = r (sqrt(1/4) - 1) = -1; u = 7/8 -> x = r (1 - sqrt(1/4)) = 1.
  const float u[] = {0.125f, 0.875f, 0.5f, 0.5f};
  fb_filter_sample samples[2];
  filter.sample(u, samples);
  EXPECT_FLOAT_EQ(samples[0].x, -1.f);
  EXPECT_FLOAT_EQ(samples[0].y, 1.f);
  EXPECT_EQ(samples[1].x, 0.f);
  EXPECT_EQ(samples[1].y, 0.f);
  EXPECT_EQ(samples[0].weight, 1.f);
}

}  // namespace
}  // namespace fb
