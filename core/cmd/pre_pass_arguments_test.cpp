#include "core/cmd/pre_pass_arguments.h"

#include <gtest/gtest.h>

namespace fb {
namespace {

using Args = std::vector<std::string>;

Args tail(const Args& a) {
  return Args(a.begin() + 2, a.end());
}

TEST(PrePassArguments, KeepsTheRenderOptionsAndSetsItsOwn) {
  const Args out = pre_pass_arguments("shot.gltf", {"--res", "640x360", "--filter", "box"}, 2,
                                      "/t/p.exr", "/t/p.json");
  EXPECT_EQ(out, (Args{"render", "shot.gltf", "--res", "640x360", "--filter", "box", "--spp", "2",
                       "-q", "-o", "/t/p.exr", "--stats-json", "/t/p.json"}));
}

TEST(PrePassArguments, DropsWhatThePrePassSetsInEveryForm) {
  const Args in = {"--spp",
                   "256",
                   "--spp=64",
                   "-o",
                   "a.exr",
                   "-ob.png",
                   "--output",
                   "c.exr",
                   "--output=d",
                   "-q",
                   "--quiet",
                   "--stats-json",
                   "s.json",
                   "--checkpoint-every",
                   "5m",
                   "--checkpoint",
                   "c.exr",
                   "--resume",
                   "--tile",
                   "3/8",
                   "--crop=0,0,16,16",
                   "--tile-plan",
                   "p.json",
                   "--seed",
                   "7"};
  EXPECT_EQ(tail(pre_pass_arguments("s.pov", in, 1, "i.exr", "r.json")),
            (Args{"--seed", "7", "--spp", "1", "-q", "-o", "i.exr", "--stats-json", "r.json"}));
}

TEST(PrePassArguments, AFrameRangePlansItsFirstFrame) {
  EXPECT_EQ(tail(pre_pass_arguments("s", {"--frames", "12-40:2"}, 1, "i", "r")),
            (Args{"--frame", "12", "--spp", "1", "-q", "-o", "i", "--stats-json", "r"}));
  EXPECT_EQ(tail(pre_pass_arguments("s", {"--frames=-5-3"}, 1, "i", "r")),
            (Args{"--frame", "-5", "--spp", "1", "-q", "-o", "i", "--stats-json", "r"}));
}

}  // namespace
}  // namespace fb
