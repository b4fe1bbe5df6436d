// The one table of sensor-fit words: every fit named and read back, any letter case, and a word
// that is no fit refused.
#include "core/scene/sensor_fit.h"

#include <gtest/gtest.h>

#include <filmback/plugin_abi.h>

namespace fb {
namespace {

TEST(SensorFit, EveryFitIsReadBackFromItsName) {
  for (uint32_t fit : {FB_SENSOR_FIT_AUTO, FB_SENSOR_FIT_HORIZONTAL, FB_SENSOR_FIT_VERTICAL})
    EXPECT_EQ(sensor_fit_named(sensor_fit_name(fit)), fit) << sensor_fit_name(fit);
}

TEST(SensorFit, WordsAreReadInAnyLetterCaseAsBlenderWritesThem) {
  EXPECT_EQ(sensor_fit_named("VERTICAL"), FB_SENSOR_FIT_VERTICAL);
  EXPECT_EQ(sensor_fit_named("Horizontal"), FB_SENSOR_FIT_HORIZONTAL);
  EXPECT_EQ(sensor_fit_named("vertical "), std::nullopt);
  EXPECT_EQ(sensor_fit_named("diagonal"), std::nullopt);
  EXPECT_EQ(sensor_fit_named(""), std::nullopt);
}

TEST(SensorFit, AnUnknownValueIsNamedAutoAndTheChoicesListEveryWord) {
  EXPECT_STREQ(sensor_fit_name(7), "auto");
  EXPECT_EQ(sensor_fit_choices(), "auto, horizontal or vertical");
}

}  // namespace
}  // namespace fb
