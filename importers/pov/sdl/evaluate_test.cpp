#include "importers/pov/sdl/evaluate.h"

#include <gtest/gtest.h>

TEST(PovSdl, Placeholder) { SUCCEED(); }
