#include "core/cmd/frame_range.h"

#include <gtest/gtest.h>

#include "core/util/error.h"

namespace fb {
namespace {

// The message of the UsageError parse_frame_range throws for `text`; "" if it throws none.
std::string range_error(const std::string& text) {
  try {
    parse_frame_range(text);
  } catch (const UsageError& e) {
    return e.what();
  }
  return "";
}

TEST(FrameRange, RangesStepsAndSingleFrames) {
  const FrameRange r = parse_frame_range("1-10:3");
  EXPECT_EQ(r.frames(), (std::vector<int64_t>{1, 4, 7, 10}));
  EXPECT_EQ(r.text(), "1-10:3");
  // A step that does not land on B stops before it, as Blender's frame_step does.
  EXPECT_EQ(parse_frame_range("1-10:4").frames(), (std::vector<int64_t>{1, 5, 9}));
  EXPECT_EQ(parse_frame_range("7").frames(), (std::vector<int64_t>{7}));
  EXPECT_EQ(parse_frame_range("7-7").text(), "7");
  EXPECT_EQ(parse_frame_range("-5--1:2").frames(), (std::vector<int64_t>{-5, -3, -1}));
  EXPECT_EQ(parse_frame_range("-2-2").count(), 5u);
  // The largest range allowed, and the numbers' bounds.
  EXPECT_EQ(parse_frame_range("0-99999").count(), size_t(kMaxFramesInRange));
  EXPECT_EQ(parse_frame_range("-1000000000--1000000000").first, -kMaxFrameNumber);
  EXPECT_EQ(parse_frame_range("0-1000000000:1000000000").count(), 2u);
}

TEST(FrameRange, BadRangesAreUsageErrorsSayingWhy) {
  EXPECT_NE(range_error("5-3").find("--frames '5-3': expected A <= B"), std::string::npos);
  EXPECT_NE(range_error("1-10:0").find("expected a STEP of 1 or more, not 0"), std::string::npos);
  EXPECT_NE(range_error("1-10:-2").find("expected a STEP of 1 or more"), std::string::npos);
  EXPECT_NE(range_error("0-100000").find("100001 frames, expected at most 100000"),
            std::string::npos);
  for (const char* text : {"a-b", "", "-", "1-", "1-b", "1:2", "1-2:", "1-2:3x", "+1-2", "1.5-3",
                           " 1-2", "1-2 ", "1..3", "1000000001", "0-1000000001", "1-2:1-2"})
    EXPECT_NE(range_error(text).find("expected A-B[:STEP] or N"), std::string::npos) << text;
}

TEST(FramePattern, PaddedToTheRunOfHashes) {
  EXPECT_EQ(frame_path("shot.####.exr", 12), "shot.0012.exr");
  EXPECT_EQ(frame_path("shot.#.exr", 12), "shot.12.exr");  // longer numbers are written whole
  EXPECT_EQ(frame_path("shot.####.exr", 123456), "shot.123456.exr");
  EXPECT_EQ(frame_path("shot.####.exr", 0), "shot.0000.exr");
  EXPECT_EQ(frame_path("out/####", 7), "out/0007");
}

// printf's "%.4d": the sign comes before four digits, and is not one of them (C11 7.21.6.1).
TEST(FramePattern, NegativeFramesAsBlenderWritesThem) {
  EXPECT_EQ(frame_path("shot.####.exr", -12), "shot.-0012.exr");
  EXPECT_EQ(frame_path("shot.####.exr", -1), "shot.-0001.exr");
  EXPECT_EQ(frame_path("shot.##.exr", -123), "shot.-123.exr");
}

// Blender replaces the last run in the file name only; a '#' in a folder is a character.
TEST(FramePattern, OnlyTheLastRunOfTheFileName) {
  EXPECT_EQ(frame_path("a##b###c.exr", 5), "a##b005c.exr");
  EXPECT_EQ(frame_path("take#2/shot.###.png", 5), "take#2/shot.005.png");
  EXPECT_TRUE(is_frame_pattern("take#2/shot.###.png"));
  EXPECT_FALSE(is_frame_pattern("take#2/shot.png"));
  EXPECT_EQ(frame_path("take#2/shot.png", 5), "take#2/shot.png");
  EXPECT_FALSE(is_frame_pattern("shot.exr"));
  EXPECT_TRUE(is_frame_pattern("#.exr"));
}

TEST(FramePattern, MissingHashIsAUsageErrorNamingTheFile) {
  EXPECT_NO_THROW(require_frame_pattern("shot.####.exr", "output"));
  try {
    require_frame_pattern("take#2/shot.exr", "output");
    FAIL() << "no error";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("output 'take#2/shot.exr': expected a run of '#'"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace fb
