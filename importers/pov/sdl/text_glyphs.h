// POV-Ray's text { ttf "font.ttf" "string" thickness, offset }: the string's glyphs as outlines
// (core/scene/outline.h) read with FreeType, placed as POV-Ray 3.7 places them (its
// TrueType::ProcessNewTTF; docs/pov.md "Prism and text").
#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <filmback/vec.h>

#include "core/scene/outline.h"

namespace fb::pov::sdl {

// One glyph that draws something: its outline in em units (the font's units per em are 1), at
// `position` in the text's object space (x along the string, y up, the baseline at y = 0).
struct PlacedGlyph {
  std::shared_ptr<const Outline> outline;
  Vec3d position;
};

// Characters past this many are refused: each becomes a solid.
constexpr size_t kMaxTextCharacters = 10'000;

// The glyphs of `text` (bytes, each a character code: ASCII and Latin-1) in the TrueType font
// file: the first glyph's left edge at x = 0, each next one after the advance of the one before
// and the fonts' kerning of the pair, and `offset` added after every character. Throws
// std::runtime_error naming the problem when the font cannot be read.
std::vector<PlacedGlyph> text_glyphs(const std::filesystem::path& font, const std::string& text,
                                     Vec3d offset);

}  // namespace fb::pov::sdl
