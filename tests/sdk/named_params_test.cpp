// Plugins read parameters by name (plugin_sdk.h, "parameters, by name"): a handle found in the
// schema reads the same value wherever the schema puts the parameter. The values come from the
// host's own binder (core/plugin/params.h), as create() receives them, for a schema and its
// reversal.
#include <gtest/gtest.h>

#include <filmback/plugin_sdk.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/plugin/params.h"

namespace fb {
namespace {

constexpr fb_param_desc kSchema[] = {
    {"radius", FB_PARAM_FLOAT, "1.5", "px", nullptr, 1e-3, 16, "d"},
    {"max_depth", FB_PARAM_INT, "8", "", nullptr, 0, 1024, "d"},
    {"show", FB_PARAM_STRING, "albedo", "", "albedo|normal|depth", 0, 0, "d"},
    {"tint", FB_PARAM_RGB, "[0.1,0.2,0.3]", "", nullptr, 0, 1, "d"},
    {"mirror", FB_PARAM_BOOL, "false", "", nullptr, 0, 1, "d"},
    {"sigma", FB_PARAM_FLOAT, "0.5", "px", nullptr, 1e-3, 16, "d"},
};
// Found at compile time: a misspelt name or a wrong type here would not compile.
constexpr auto kSigma = param<double>(kSchema, "sigma");
static_assert(kSigma.index() == 5);

struct Read {
  double radius, sigma;
  int max_depth;
  std::string show;
  Rgb tint;
  bool mirror;
};

// A filter descriptor with `schema`, for the host's binder.
fb_plugin plugin_with(const std::vector<fb_param_desc>& schema) {
  fb_plugin plugin{};
  plugin.abi_version = FB_ABI_VERSION;
  plugin.struct_size = sizeof(fb_plugin);
  plugin.kind = FB_KIND_FILTER;
  plugin.params = schema.data();
  plugin.param_count = uint32_t(schema.size());
  return plugin;
}

// What a plugin with `schema` reads through handles from create()'s values for `settings`.
Read read_through_handles(const std::vector<fb_param_desc>& schema,
                          const std::vector<std::pair<std::string, std::string>>& settings) {
  const BoundParams bound(plugin_with(schema), settings);
  const fb_value* values = bound.data();
  const size_t n = schema.size();
  return {param<double>(schema.data(), n, "radius")(values),
          param<double>(schema.data(), n, "sigma")(values),
          param<int>(schema.data(), n, "max_depth")(values),
          param<const char*>(schema.data(), n, "show")(values),
          param<Rgb>(schema.data(), n, "tint")(values),
          param<bool>(schema.data(), n, "mirror")(values)};
}

TEST(NamedParams, ReorderedSchemaReadsTheSameValues) {
  const std::vector<fb_param_desc> schema(std::begin(kSchema), std::end(kSchema));
  std::vector<fb_param_desc> reversed = schema;
  std::reverse(reversed.begin(), reversed.end());
  const std::vector<std::pair<std::string, std::string>> settings = {
      {"sigma", "0.75"}, {"show", "normal"}, {"mirror", "true"}, {"max_depth", "3"}};
  for (const auto& s : {schema, reversed}) {
    const Read r = read_through_handles(s, settings);
    EXPECT_EQ(r.radius, 1.5);  // the default
    EXPECT_EQ(r.sigma, 0.75);
    EXPECT_EQ(r.max_depth, 3);
    EXPECT_EQ(r.show, "normal");
    EXPECT_EQ(r.tint.x, 0.1f);
    EXPECT_EQ(r.tint.y, 0.2f);
    EXPECT_EQ(r.tint.z, 0.3f);
    EXPECT_TRUE(r.mirror);
  }
  // The control: by position, the reversed schema's first value is another parameter.
  const BoundParams bound(plugin_with(reversed), settings);
  EXPECT_EQ(bound.data()[0].number[0], 0.75);  // sigma, where radius was
}

TEST(NamedParams, AMissingNameOrAWrongTypeIsAnErrorCreateReports) {
  EXPECT_THROW(param<double>(kSchema, std::size(kSchema), "radius_px"), std::invalid_argument);
  EXPECT_THROW(param<int>(kSchema, std::size(kSchema), "radius"), std::invalid_argument);
  EXPECT_THROW(param<double>(kSchema, std::size(kSchema), "show"), std::invalid_argument);
  // Through the SDK's create(): the message reaches the error buffer.
  struct Misread {
    explicit Misread(const fb_value* values) {
      param<float>(kSchema, std::size(kSchema), "rad")(values);
    }
  };
  char text[256] = "";
  void* instance = nullptr;
  const fb_value values[std::size(kSchema)] = {};
  EXPECT_NE(create_instance<Misread>(&instance, {text, sizeof text}, values), 0);
  EXPECT_STREQ(text, "the plugin reads a parameter 'rad' its schema lacks");
}

}  // namespace
}  // namespace fb
