#include "core/plugin/params.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/util/error.h"

namespace fb {
namespace {

TEST(PluginSpec, ParsesNameAndSettingsInOrder) {
  const PluginSpec spec = parse_plugin_spec("gaussian:radius=1.5,sigma=0.5", "--filter");
  EXPECT_EQ(spec.name, "gaussian");
  ASSERT_EQ(spec.settings.size(), 2u);
  EXPECT_EQ(spec.settings[0], (std::pair<std::string, std::string>{"radius", "1.5"}));
  EXPECT_EQ(spec.settings[1], (std::pair<std::string, std::string>{"sigma", "0.5"}));
  EXPECT_TRUE(parse_plugin_spec("box", "--filter").settings.empty());
}

TEST(PluginSpec, BracketsKeepListsTogether) {
  const PluginSpec spec =
      parse_plugin_spec("path:background=[0.1,0.2,0.3],max_depth=4", "--integrator");
  ASSERT_EQ(spec.settings.size(), 2u);
  EXPECT_EQ(spec.settings[0].second, "[0.1,0.2,0.3]");
}

TEST(PluginSpec, MalformedTextIsAUsageErrorNamingTheOption) {
  for (const char* bad : {"", "Gauss", "gaussian:radius", "gaussian:=1", ":x=1"}) {
    try {
      parse_plugin_spec(bad, "--filter");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const UsageError& e) {
      EXPECT_NE(std::string(e.what()).find("--filter"), std::string::npos) << e.what();
    }
  }
}

constexpr fb_param_desc kFloat{"sigma", FB_PARAM_FLOAT, "0.5", "px", nullptr, 0.001, 16, "d"};
constexpr fb_param_desc kInt{"depth", FB_PARAM_INT, "8", "", nullptr, 0, 1024, "d"};
constexpr fb_param_desc kChoice{"show", FB_PARAM_STRING, "albedo", "", "albedo|normal", 0, 0, "d"};
constexpr fb_param_desc kRgb{"colour", FB_PARAM_RGB, "0", "", nullptr, 0, HUGE_VAL, "d"};
constexpr fb_param_desc kBool{"on", FB_PARAM_BOOL, "false", "", nullptr, 0, 1, "d"};

TEST(ParamValue, NumbersAreCheckedAgainstTypeAndBounds) {
  fb_value v;
  EXPECT_EQ(parse_param_value(kFloat, "1.25", v), "");
  EXPECT_EQ(v.number[0], 1.25);
  EXPECT_NE(parse_param_value(kFloat, "-1", v), "");
  EXPECT_NE(parse_param_value(kFloat, "17", v), "");
  EXPECT_NE(parse_param_value(kFloat, "nan", v), "");
  EXPECT_NE(parse_param_value(kFloat, "1.5px", v), "");
  EXPECT_EQ(parse_param_value(kInt, "12", v), "");
  EXPECT_NE(parse_param_value(kInt, "1.5", v), "");
}

TEST(ParamValue, StringsColoursAndBools) {
  fb_value v;
  EXPECT_EQ(parse_param_value(kChoice, "normal", v), "");
  EXPECT_EQ(parse_param_value(kChoice, "depth", v), "one of albedo|normal");
  EXPECT_EQ(parse_param_value(kRgb, "[0.1,0.2,0.3]", v), "");
  EXPECT_DOUBLE_EQ(v.number[2], 0.3);
  EXPECT_EQ(parse_param_value(kRgb, "0.5", v), "");
  EXPECT_DOUBLE_EQ(v.number[1], 0.5);
  EXPECT_NE(parse_param_value(kRgb, "[1,2]", v), "");
  EXPECT_NE(parse_param_value(kRgb, "[1,-2,3]", v), "");
  EXPECT_EQ(parse_param_value(kBool, "yes", v), "");
  EXPECT_EQ(v.number[0], 1.0);
  EXPECT_NE(parse_param_value(kBool, "maybe", v), "");
}

TEST(BoundParams, FillsDefaultsAndRejectsUnknownOrRepeatedKeys) {
  const fb_param_desc params[] = {kFloat, kChoice};
  fb_plugin plugin{FB_ABI_VERSION, sizeof(fb_plugin), FB_KIND_FILTER, "test", "1", "s", params, 2,
                   nullptr};
  const BoundParams bound(plugin, {{"show", "normal"}});
  EXPECT_EQ(bound.values()[0].number[0], 0.5);
  EXPECT_STREQ(bound.values()[1].text, "normal");
  try {
    BoundParams(plugin, {{"sigmaa", "1"}});
    ADD_FAILURE() << "accepted an unknown key";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("expected one of: sigma, show"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(BoundParams(plugin, {{"sigma", "1"}, {"sigma", "2"}}), UsageError);
  EXPECT_THROW(BoundParams(plugin, {{"sigma", "0"}}), UsageError);
}

// A scene's value reaches the plugin exactly: 1/3 stays 1/3, where "%g" text would give 0.333333.
TEST(BoundParams, SetNumberBindsTypedValuesExactlyWithinTheSchemasBounds) {
  const fb_param_desc params[] = {kFloat, kChoice};
  fb_plugin plugin{FB_ABI_VERSION, sizeof(fb_plugin), FB_KIND_FILTER, "test", "1", "s", params, 2,
                   nullptr};
  BoundParams bound(plugin, {});
  EXPECT_EQ(bound.set_number(plugin, "sigma", 1.0 / 3), "");
  EXPECT_EQ(bound.values()[0].number[0], 1.0 / 3);
  EXPECT_NE(bound.set_number(plugin, "sigma", 0), "");  // below the schema's minimum
  EXPECT_NE(bound.set_number(plugin, "sigma", NAN), "");
  EXPECT_NE(bound.set_number(plugin, "show", 1), "");    // a string parameter
  EXPECT_NE(bound.set_number(plugin, "radius", 1), "");  // not in the schema
  EXPECT_EQ(bound.values()[0].number[0], 1.0 / 3);       // a refused value changes nothing
}

}  // namespace
}  // namespace fb
