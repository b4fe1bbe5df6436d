// fog { ... } at the top level of a scene (POV-Ray 3.7 reference, "Fog"): constant fog
// (fog_type 1) and ground fog (fog_type 2), as pov::Fog keeps them for the converter
// (docs/pov.md, "Fog").
#include <cmath>

#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// POV-Ray keeps every fog of a scene; each costs its closed form on every path segment, so a
// scene that makes thousands in a loop is bad input rather than a slow render.
constexpr size_t kMaxFogs = 64;

}  // namespace

// After `fog`: the block. Turbulence, which varies the fog's depth by a noise, is read and not
// rendered (reported).
void Parser::parse_fog(const Tok& keyword) {
  const SourceLocation where = location_of(keyword);
  expect("{");
  Fog fog;
  fog.where = where;
  for (;;) {
    Tok tok = next();  // directives run
    if (tok.symbol("}")) break;
    const std::string& w = tok.token.text;
    if (tok.word("fog_type")) {
      // POV-Ray truncates the number to an integer
      const double type = parse_float();
      if (!(type >= 1 && type < 3))
        fail_at(location_of(tok), "fog_type must be 1 (constant) or 2 (ground fog)");
      fog.ground = type >= 2;
    } else if (tok.word("distance")) {
      fog.distance = parse_float();
    } else if (tok.word("fog_offset")) {
      fog.offset = parse_float();
    } else if (tok.word("fog_alt")) {
      fog.altitude = parse_float();
    } else if (tok.word("up")) {
      fog.up = parse_vector();
    } else if (tok.word("turbulence")) {
      parse_vector();
      unsupported("fog turbulence", location_of(tok));
    } else if (tok.word("octaves") || tok.word("omega") || tok.word("lambda") ||
               tok.word("turb_depth")) {
      parse_float();
    } else if (starts_colour(tok) || (tok.identifier && tok.value.numeric())) {
      unget(std::move(tok));
      fog.colour = parse_colour();
    } else if (auto m = parse_transform_item(tok)) {
      fog.up = m->vector(fog.up);  // transforms turn the fog's up (and its turbulence)
    } else {
      fail_at(location_of(tok), "unexpected '" + w + "' in fog");
    }
  }
  // A non-finite height or distance would make every fogged pixel NaN.
  if (!std::isfinite(fog.distance) || !std::isfinite(fog.offset) || !std::isfinite(fog.altitude))
    fail_at(where, "fog distance, fog_offset and fog_alt must be finite");
  if (fog.ground && !(fog.altitude > 0))
    fail_at(where, "ground fog (fog_type 2) needs a fog_alt above 0");
  if (scene_.fogs.size() >= kMaxFogs)
    fail_at(where, "a scene has at most " + std::to_string(kMaxFogs) + " fogs");
  scene_.fogs.push_back(fog);
}

}  // namespace fb::pov::sdl
