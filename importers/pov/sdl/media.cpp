// media { ... } inside an interior (POV-Ray 3.7 reference, "Media"): a homogeneous medium's
// absorption, emission and scattering, as pov::Media keeps them for the converter (docs/pov.md,
// "Media"). A density is read exactly when it is a constant colour, which scales the
// coefficients; one with a pattern counts as 1 and is reported, as are scattering types other
// than isotropic, which are taken as isotropic.
#include <cmath>
#include <string>

#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// Each sample is a point of the sum along every ray in the medium: bounded for untrusted scenes.
constexpr int kMostMediaSamples = 1000;

Colour times(const Colour& a, const Colour& b) {
  return {a.r * b.r, a.g * b.g, a.b * b.b, 0, 0};
}

// A coefficient must be a finite amount at or above 0: a negative one would make light grow
// without bound through the medium.
void check_coefficient(Parser& p, const Colour& c, const SourceLocation& where,
                       const std::string& name) {
  for (double v : {c.r, c.g, c.b})
    if (!(v >= 0 && std::isfinite(v)))
      p.fail_at(where,
                "media " + name + " must be finite and at least 0, not " + std::to_string(v));
}

}  // namespace

// After `density`: the block. A constant colour (`density { rgb 0.5 }`) multiplies the medium's
// coefficients; anything else (a pattern, a density_file, a declared density) is taken as 1.
Colour Parser::parse_media_density(const SourceLocation& where) {
  expect("{");
  Colour density{1, 1, 1, 0, 0};
  Tok first = next();
  if (first.symbol("}")) return density;
  if (starts_colour(first) || (first.identifier && first.value.numeric())) {
    unget(std::move(first));
    density = parse_colour(false);
  } else {
    unsupported("media density pattern", where);
    unget(std::move(first));
  }
  skip_rest_of_block();  // the density's transforms and maps: nothing to do for a constant
  return density;
}

// After `scattering`: { type, colour [eccentricity e] [extinction e] }.
void Parser::parse_media_scattering(Media& media) {
  expect("{");
  const SourceLocation where = here();
  const double type = parse_float();
  if (!(type >= 1 && type < 6))
    fail_at(where, "media scattering type must be 1 to 5, not " + std::to_string(type));
  if (int(type) != 1) unsupported("media scattering type", where);
  accept(",");
  const SourceLocation colour_at = location_of(peek());
  media.scattering = parse_colour(false);
  check_coefficient(*this, media.scattering, colour_at, "scattering");
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    if (tok.word("eccentricity")) {
      parse_float();  // Henyey-Greenstein's g: not rendered (isotropic)
    } else if (tok.word("extinction")) {
      media.extinction = parse_float();
      if (!(media.extinction >= 0 && std::isfinite(media.extinction)))
        fail_at(location_of(tok), "media scattering extinction must be finite and at least 0");
    } else {
      fail_at(location_of(tok), "unexpected '" + tok.token.text + "' in media scattering");
    }
  }
}

// After `media`: the block, or a declared media with modifiers.
Media Parser::parse_media(const Tok& keyword) {
  Nesting guard(*this);
  expect("{");
  Media media;
  media.where = location_of(keyword);
  Colour density{1, 1, 1, 0, 0};
  bool first = true;
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    if (tok.token.kind == TokenKind::kEnd) fail("missing '}' in media");
    const std::string& w = tok.token.text;
    if (first && tok.identifier && tok.value.get<Media>()) {
      media = *tok.value.get<Media>();
    } else if (w == "absorption" || w == "emission") {
      const SourceLocation at = location_of(peek());
      const Colour c = parse_colour(false);
      check_coefficient(*this, c, at, w);
      (w == "absorption" ? media.absorption : media.emission) = c;
    } else if (w == "scattering") {
      parse_media_scattering(media);
    } else if (w == "density") {
      density = times(density, parse_media_density(location_of(tok)));
      check_coefficient(*this, density, location_of(tok), "density");
    } else if (w == "method" || w == "confidence" || w == "variance" || w == "ratio" ||
               w == "jitter" || w == "aa_level" || w == "aa_threshold") {
      parse_float();  // the rest of POV-Ray's sampling: not needed for a homogeneous medium
    } else if (w == "samples" || w == "intervals") {
      // the least samples (a maximum may follow) and the intervals set where POV-Ray sums the
      // medium's light along a ray (the `povray` integrator)
      const double count = parse_float();
      if (!(count >= 1 && count <= kMostMediaSamples))
        fail_at(location_of(tok),
                "media " + w + " must be 1 to " + std::to_string(kMostMediaSamples));
      (w == "samples" ? media.samples : media.intervals) = int(count);
      if (w == "samples" && accept(",")) parse_float();
    } else if (w == "collect" || w == "ignore_photons") {
      parse_bool_option();
    } else if (parse_transform_item(tok)) {
      // moves the density, which is constant here
    } else {
      fail_at(location_of(tok), "unexpected '" + w + "' in media");
    }
    first = false;
  }
  media.absorption = times(media.absorption, density);
  media.emission = times(media.emission, density);
  media.scattering = times(media.scattering, density);
  return media;
}

}  // namespace fb::pov::sdl
