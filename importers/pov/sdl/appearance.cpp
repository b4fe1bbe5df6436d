// Appearance statements: pigment (colours, patterns, colour maps), finish, texture, interior,
// material, and the transforms (translate/rotate/scale/matrix/transform) they and objects share.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "importers/pov/sdl/keyword_table.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {
namespace {

// POV-Ray has no limit; a scene that piles up media in a loop is bad input, not a slow render.
constexpr size_t kMostMediaPerInterior = 64;

// POV-Ray's `rotate <a, b, c>`: about x by a, then y by b, then z by c, each the ordinary
// right-hand-rule matrix (column form Rz * Ry * Rx; ../shared/notes/povray-camera.md 1.1).
Matrix rotation(Vec3d degrees) {
  auto axis = [](int i, double deg) {
    double r = deg * std::numbers::pi / 180, c = std::cos(r), s = std::sin(r);
    if (i == 0) return Matrix::from_rows({1, 0, 0, 0, 0, c, -s, 0, 0, s, c, 0, 0, 0, 0, 1});
    if (i == 1) return Matrix::from_rows({c, 0, s, 0, 0, 1, 0, 0, -s, 0, c, 0, 0, 0, 0, 1});
    return Matrix::from_rows({c, -s, 0, 0, s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
  };
  return axis(2, degrees.z) * axis(1, degrees.y) * axis(0, degrees.x);
}

// POV-Ray's pattern keywords that filmback does not evaluate (beside those it does, named in
// core/scene/solid_texture.h): a pigment of one is parsed and rendered in its average colour.
const char* const kAveragedPatterns[] = {
    "boxed",   "cylindrical",   "spherical", "planar",          "mandel",       "julia",
    "magnet",  "object",        "function",  "pigment_pattern", "density_file", "facets",
    "quilted", "tiling",        "pavement",  "slope",           "aoi",          "cubic",
    "average", "image_pattern", "square",    "triangular",      "bump_map",
};

bool is_averaged_pattern(const std::string& w) {
  for (const char* p : kAveragedPatterns) {
    if (w == p) return true;
  }
  return false;
}

// "solid" names a plain colour in the scene model's table; it is no keyword of POV-Ray's.
std::optional<Pattern> evaluated_pattern(const std::string& w) {
  const std::optional<Pattern> kind = solid_pattern_named(w);
  return kind == Pattern::kSolid ? std::nullopt : kind;
}

bool is_pattern(const std::string& w) {
  return evaluated_pattern(w) || is_averaged_pattern(w);
}

Colour mix(const Colour& a, const Colour& b, double t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t,
          a.filter + (b.filter - a.filter) * t, a.transmit + (b.transmit - a.transmit) * t};
}

// The mean of a colour map over [0, 1]: piecewise linear between entries, constant outside.
Colour map_average(const ColourMap& map) {
  if (map.empty()) return {0.5, 0.5, 0.5, 0, 0};  // POV-Ray's default map runs black to white
  Colour sum{};
  auto add = [&](const Colour& c, double w) {
    sum.r += c.r * w;
    sum.g += c.g * w;
    sum.b += c.b * w;
    sum.filter += c.filter * w;
    sum.transmit += c.transmit * w;
  };
  add(map.front().colour, std::clamp(map.front().value, 0.0, 1.0));
  for (size_t i = 1; i < map.size(); ++i) {
    double a = std::clamp(map[i - 1].value, 0.0, 1.0), b = std::clamp(map[i].value, 0.0, 1.0);
    add(mix(map[i - 1].colour, map[i].colour, 0.5), std::max(0.0, b - a));
  }
  add(map.back().colour, 1 - std::clamp(map.back().value, 0.0, 1.0));
  return sum;
}

Colour list_average(const std::vector<Pigment>& list) {
  Colour sum{};
  for (const Pigment& p : list) {
    sum.r += p.colour.r / list.size();
    sum.g += p.colour.g / list.size();
    sum.b += p.colour.b / list.size();
    sum.filter += p.colour.filter / list.size();
    sum.transmit += p.colour.transmit / list.size();
  }
  return sum;
}

Pigment solid(const Colour& c) {
  Pigment p;
  p.colour = c;
  return p;
}

void move_pigment(Pigment& pigment, const Matrix& inverse) {
  pigment.pattern_from_world = pigment.pattern_from_world * inverse;
  for (Pigment& entry : pigment.list)
    move_pigment(entry, inverse);
}

// ---- pigment steps (POV-Ray 3.7 reference, "Patterns", "Pattern Modifiers") ----

// `function { body }` as a pattern, after the keyword: the compiled function in `m`; false (and
// reported) when it needs what filmback does not evaluate.
bool read_function_pattern(Parser& parser, SolidPatternModifiers& m) {
  const SourceLocation where = parser.location_of(parser.peek());
  FunctionValue f = parser.parse_function_body({"x", "y", "z"}, true);
  m.function = std::move(f.program);
  if (f.unsupported.empty()) return true;
  parser.unsupported("function " + f.unsupported, where);
  return false;
}

// The entries of a list pattern (checker A, B; hexagon A, B, C; brick A, B), at most `max`:
// pigments, colours or pigment identifiers.
void parse_list_entries(Parser& parser, Pigment& p, size_t max) {
  p.list.clear();
  for (;;) {
    const Tok& tok = parser.peek();
    if (p.list.size() >= max) break;
    if (tok.word("pigment")) {
      parser.next();
      p.list.push_back(parser.parse_pigment());
    } else if (parser.starts_colour(tok) || (tok.identifier && tok.value.numeric()) ||
               tok.symbol("<") || tok.token.kind == TokenKind::kNumber) {
      Pigment entry;
      entry.colour = parser.parse_colour();
      p.list.push_back(entry);
    } else if (tok.identifier && tok.value.get<Pigment>()) {
      p.list.push_back(*parser.next().value.get<Pigment>());
    } else {
      break;
    }
    parser.accept(",");
  }
}

// A pattern keyword and its arguments; list patterns get POV-Ray's default entries where the
// scene gives fewer.
void parse_pigment_pattern(Parser& parser, Pigment& p, const Tok& tok) {
  const std::string& w = tok.token.text;
  p.pattern = evaluated_pattern(w).value_or(Pattern::kSolid);
  p.averaged = !evaluated_pattern(w);
  p.name = w;
  p.colour_map.clear();
  p.list.clear();
  if (w == "checker" || w == "brick") {
    parse_list_entries(parser, p, 2);
    // defaults (POV-Ray manual 3.5.11): checker blue and green, brick white mortar and red
    Colour a = w == "checker" ? Colour{0, 0, 1} : Colour{1, 1, 1};
    Colour b = w == "checker" ? Colour{0, 1, 0} : Colour{1, 0, 0};
    if (p.list.size() < 1) p.list.push_back(solid(a));
    if (p.list.size() < 2) p.list.push_back(solid(b));
  } else if (w == "hexagon") {
    parse_list_entries(parser, p, 3);
    const Colour defaults[3] = {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}};  // blue, green, red
    while (p.list.size() < 3)
      p.list.push_back(solid(defaults[p.list.size()]));
  } else if (w == "gradient") {
    p.gradient = parser.parse_vector();
  } else if (w == "image_map") {
    parser.parse_image_map(p);  // image_map.cpp
    return;
  } else if (w == "function") {
    p.averaged = !read_function_pattern(parser, p);
    if (p.averaged) p.pattern = Pattern::kSolid;
  } else {
    parser.parse_pattern_arguments(w);
  }
  if (p.averaged && w != "function") parser.unsupported("pattern " + w, parser.location_of(tok));
}

// poly_wave [Exponent]
void parse_poly_wave(Parser& parser, SolidPatternModifiers& p) {
  p.wave = Wave::kPoly;
  const Tok& n = parser.peek();
  if (n.token.kind == TokenKind::kNumber || (n.identifier && n.value.kind == ValueKind::kFloat)) {
    p.wave_exponent = parser.parse_float();
  }
}

// A modifier whose optional value is dropped (image_map's once, crackle's metric ...).
void skip_optional_value(Parser& parser) {
  const Tok& n = parser.peek();
  if (n.token.kind == TokenKind::kNumber || n.symbol("<") || n.symbol("-") ||
      (n.identifier && n.value.numeric())) {
    parser.parse_expression();
  }
}

void skip_two_floats(Parser& parser) {
  parser.parse_float();
  parser.accept(",");
  parser.parse_float();
}

// The modifiers a pigment or a normal reads after its pattern, one line each: those with a field
// in SolidPatternModifiers are kept, the others read and dropped (uv_mapping and warp reported).
struct PigmentModifier {
  std::string_view name;
  void (*parse)(Parser&, SolidPatternModifiers&, const Tok&);
};

using P = Parser&;
using G = SolidPatternModifiers&;
using T = const Tok&;
constexpr PigmentModifier kPigmentModifiers[] = {
    {"turbulence", [](P parser, G p, T) { p.turbulence = parser.parse_vector(); }},
    {"octaves", [](P parser, G p, T) { p.octaves = static_cast<int>(parser.parse_float()); }},
    {"omega", [](P parser, G p, T) { p.omega = parser.parse_float(); }},
    {"lambda", [](P parser, G p, T) { p.lambda = parser.parse_float(); }},
    {"frequency", [](P parser, G p, T) { p.frequency = parser.parse_float(); }},
    {"phase", [](P parser, G p, T) { p.phase = parser.parse_float(); }},
    {"ramp_wave", [](P, G p, T) { p.wave = Wave::kRamp; }},
    {"triangle_wave", [](P, G p, T) { p.wave = Wave::kTriangle; }},
    {"sine_wave", [](P, G p, T) { p.wave = Wave::kSine; }},
    {"scallop_wave", [](P, G p, T) { p.wave = Wave::kScallop; }},
    {"cubic_wave", [](P, G p, T) { p.wave = Wave::kCubic; }},
    {"poly_wave", [](P parser, G p, T) { parse_poly_wave(parser, p); }},
    {"brick_size", [](P parser, G p, T) { p.brick_size = parser.parse_vector(); }},
    {"mortar", [](P parser, G p, T) { p.mortar = parser.parse_float(); }},
    {"quick_color", [](P parser, G, T) { parser.parse_colour(); }},
    {"quick_colour", [](P parser, G, T) { parser.parse_colour(); }},
    {"agate_turb", [](P parser, G, T) { parser.parse_float(); }},
    {"uv_mapping",
     [](P parser, G, T tok) { parser.unsupported("uv_mapping", parser.location_of(tok)); }},
    // mandel/julia: interior Type, Factor
    {"interior", [](P parser, G, T) { skip_two_floats(parser); }},
    {"exterior", [](P parser, G, T) { skip_two_floats(parser); }},
    {"noise_generator", [](P parser, G, T) { parser.parse_float(); }},
    {"metric", [](P parser, G, T) { parser.parse_float(); }},
    {"offset", [](P parser, G, T) { parser.parse_float(); }},
    {"control0", [](P parser, G, T) { parser.parse_float(); }},
    {"control1", [](P parser, G, T) { parser.parse_float(); }},
    {"interpolate", [](P parser, G, T) { parser.parse_float(); }},
    {"map_type", [](P parser, G, T) { parser.parse_float(); }},
    {"form", [](P parser, G, T) { parser.parse_vector(); }},
    {"solid", [](P parser, G, T) { skip_optional_value(parser); }},
    {"once", [](P parser, G, T) { skip_optional_value(parser); }},
    {"use_colour", [](P parser, G, T) { skip_optional_value(parser); }},
    {"use_color", [](P parser, G, T) { skip_optional_value(parser); }},
    {"use_index", [](P parser, G, T) { skip_optional_value(parser); }},
    {"use_alpha", [](P parser, G, T) { skip_optional_value(parser); }},
    {"orientation", [](P parser, G, T) { skip_optional_value(parser); }},
    {"dist_exp", [](P parser, G, T) { skip_optional_value(parser); }},
    {"major_radius", [](P parser, G, T) { skip_optional_value(parser); }},
    {"exponent", [](P parser, G, T) { skip_optional_value(parser); }},
    {"coords", [](P parser, G, T) { skip_optional_value(parser); }},
    {"accuracy", [](P parser, G, T) { skip_optional_value(parser); }},
    {"repeat", [](P parser, G, T) { skip_optional_value(parser); }},
    {"flip", [](P parser, G, T) { skip_optional_value(parser); }},
    {"precision", [](P parser, G, T) { skip_optional_value(parser); }},
    {"color_space", [](P parser, G, T) { skip_optional_value(parser); }},
    {"warp",
     [](P parser, G, T tok) {
       parser.unsupported("warp", parser.location_of(tok));
       parser.skip_block();
     }},
};

// ---- normal steps (POV-Ray 3.7 reference, "Normal", "Slope Maps") ----

// A value right after a normal's pattern: its amount (`bumps 0.5`, `gradient x, 0.5`).
bool starts_normal_amount(const Tok& tok) {
  return tok.token.kind == TokenKind::kNumber || tok.symbol("-") || tok.symbol("(") ||
         (tok.identifier && tok.value.kind == ValueKind::kFloat);
}

// The pattern keyword of a normal, its arguments and amount. A list pattern with normals of its
// own (`checker normal {..} normal {..}`) is read and not rendered.
void parse_normal_pattern(Parser& parser, Normal& n, const Tok& tok) {
  const std::string& w = tok.token.text;
  n.pattern = evaluated_pattern(w).value_or(Pattern::kSolid);
  n.rendered = evaluated_pattern(w).has_value();
  n.name = w;
  if (w == "gradient") {
    n.gradient = parser.parse_vector();
  } else if (w == "function") {
    n.rendered = read_function_pattern(parser, n);
  } else {
    parser.parse_pattern_arguments(w);
  }
  if (!n.rendered && w != "function")
    parser.unsupported("normal pattern " + w, parser.location_of(tok));
  if (w == "checker" || w == "brick" || w == "hexagon") {
    bool entries = false;
    while (parser.peek().word("normal") ||
           (parser.peek().identifier && parser.peek().value.get<Normal>())) {
      if (parser.next().word("normal")) parser.skip_block();
      parser.accept(",");
      entries = true;
    }
    if (entries) {
      n.rendered = false;
      parser.unsupported("normal list " + w, parser.location_of(tok));
    }
  }
  parser.accept(",");
  if (starts_normal_amount(parser.peek())) n.amount = parser.parse_float();
}

// slope_map { [value, <height, slope>] ... }
std::vector<SlopeMapEntry> parse_slope_map(Parser& parser) {
  std::vector<SlopeMapEntry> map;
  parser.expect("{");
  for (;;) {
    Tok tok = parser.next();
    if (tok.symbol("}")) break;
    if (!tok.symbol("[")) parser.fail("expected '[' in a slope_map");
    SlopeMapEntry e;
    e.value = parser.parse_count();  // no comparison: `[0.5 <1, 1>]` opens the vector
    parser.accept(",");
    const Vec3d height_slope = parser.parse_vector();
    e.height = height_slope.x, e.slope = height_slope.y;
    parser.expect("]");
    map.push_back(e);
    if (map.size() > 256) parser.fail("a slope_map has at most 256 entries");
  }
  return map;
}

// How deep normal_maps nest in `n` (0: none). A hit bends the normal through two entries per
// level, so the work grows as 2^depth: a scene nesting them deeper than any real one is bad
// input rather than a render that never ends.
int normal_map_depth(const Normal& n) {
  int deepest = 0;
  for (const NormalMapEntry& e : n.normal_map)
    deepest = std::max(deepest, normal_map_depth(e.normal));
  return n.normal_map.empty() ? 0 : 1 + deepest;
}
constexpr int kMaxNormalMapDepth = 6;

// normal_map { [value normal-body] ... }, at most 256 entries.
std::vector<NormalMapEntry> parse_normal_map(Parser& parser) {
  std::vector<NormalMapEntry> map;
  parser.expect("{");
  for (;;) {
    Tok tok = parser.next();
    if (tok.symbol("}")) break;
    if (!tok.symbol("[")) parser.fail("expected '[' in a normal_map");
    NormalMapEntry e;
    // `average` maps may leave the value out: [gradient x, -5.0]
    if (parser.starts_value(parser.peek())) e.value = parser.parse_count();
    parser.accept(",");
    e.normal = parser.parse_normal_items("]");
    if (normal_map_depth(e.normal) >= kMaxNormalMapDepth)
      parser.fail("normal_maps nest at most " + std::to_string(kMaxNormalMapDepth) + " deep");
    map.push_back(std::move(e));
    if (map.size() > 256) parser.fail("a normal_map has at most 256 entries");
  }
  return map;
}

// ---- texture steps (POV-Ray 3.7 reference, "Texture", "Patterned Textures") ----

// A texture pattern is not evaluated: the first texture of its list or map stands for the whole
// pattern, so only that one is kept.
void keep_first(std::optional<Texture>& first_sub, Texture sub) {
  if (!first_sub) first_sub = std::move(sub);
}

// tiles { texture {..} tile2 texture {..} }
void parse_tiles(Parser& parser, std::optional<Texture>& first_sub) {
  parser.expect("{");
  for (;;) {
    Tok item = parser.next();
    if (item.symbol("}")) break;
    if (item.word("texture")) {
      keep_first(first_sub, parser.parse_texture());
    } else if (!item.word("tile2")) {
      parser.fail("unexpected '" + item.token.text + "' in tiles");
    }
  }
}

// texture_map { [v texture {..}] ... } or material_map { "file" options texture {..} ... }
// (`map` names which).
void parse_texture_map(Parser& parser, const std::string& map, std::optional<Texture>& first_sub) {
  parser.expect("{");
  for (;;) {
    Tok entry = parser.next();
    if (entry.symbol("}")) break;
    if (entry.word("texture") && map == "material_map") {
      keep_first(first_sub, parser.parse_texture());
      continue;
    }
    if (!entry.symbol("[")) {
      if (map == "material_map") continue;  // image file and options
      parser.fail("expected '[' in texture_map");
    }
    if (parser.starts_value(parser.peek()) && !parser.starts_colour(parser.peek()))
      parser.parse_float();
    parser.accept(",");
    if (parser.peek().word("texture")) {
      parser.next();
      keep_first(first_sub, parser.parse_texture());
      parser.expect("]");
    } else {
      keep_first(first_sub, parser.parse_texture_items("]"));  // [v Ident], [v pigment {..} ..]
    }
  }
}

// pigment, finish or normal (keyword or identifier) of a plain texture: false if `tok` is none.
bool parse_texture_part(Parser& parser, const Tok& tok, Texture& t) {
  const std::string& w = tok.token.text;
  if (w == "pigment") {
    t.pigment = parser.parse_pigment();
  } else if (tok.identifier && tok.value.get<Pigment>()) {
    t.pigment = *tok.value.get<Pigment>();
  } else if (w == "finish") {
    t.finish = parser.parse_finish(t.finish);
  } else if (tok.identifier && tok.value.get<Finish>()) {
    t.finish = *tok.value.get<Finish>();
  } else if (w == "normal") {
    t.normal = parser.parse_normal();
  } else {
    return false;
  }
  return true;
}

}  // namespace

// The pattern follows later transforms: pattern_from_world gains inverse(M) on the right.
void transform_texture(Texture& texture, const Matrix& inverse) {
  move_pigment(texture.pigment, inverse);
  if (texture.normal)
    texture.normal->pattern_from_world = texture.normal->pattern_from_world * inverse;
  for (Texture& layer : texture.layers)
    transform_texture(layer, inverse);
}

// POV-Ray has no limit on layers; every layer costs a pattern evaluation per hit, so a scene
// that builds thousands in a loop is bad input rather than a slow render.
constexpr size_t kMaxTextureLayers = 64;

void Parser::add_texture_layer(Texture& texture, Texture layer) {
  std::vector<Texture> above = std::move(layer.layers);
  layer.layers.clear();
  texture.layers.push_back(std::move(layer));
  for (Texture& t : above)
    texture.layers.push_back(std::move(t));
  if (texture.layers.size() >= kMaxTextureLayers)
    fail("a layered texture has at most " + std::to_string(kMaxTextureLayers) + " layers");
}

// The arguments a pattern keyword takes right after it (POV-Ray manual 3.5.11).
void Parser::parse_pattern_arguments(const std::string& w) {
  if (w == "gradient") {
    parse_vector();
  } else if (w == "spiral1" || w == "spiral2" || w == "mandel" || w == "tiling" || w == "magnet" ||
             w == "agate_turb" || w == "pavement" || w == "facets") {
    if (starts_value(peek())) parse_float();
  } else if (w == "julia") {
    parse_numeric(2);
    accept(",");
    parse_float();
  } else if (w == "slope") {
    if (peek().symbol("{")) {
      skip_block();
    } else {
      parse_vector();
      if (accept(",")) {
        parse_float();
        accept(",");
        parse_float();
      }
    }
  } else if (w == "image_map" || w == "pigment_pattern" || w == "image_pattern" ||
             w == "function" || w == "object" || w == "bump_map") {
    skip_block();
  } else if (w == "density_file") {
    next();  // df3
    parse_expression();
  }
}

Matrix Parser::parse_transform_block() {
  Matrix m;
  if (!peek().symbol("{")) {
    // `transform Ident`
    Tok tok = next();
    if (!tok.identifier || !tok.value.get<Matrix>()) fail("expected a transform");
    return *tok.value.get<Matrix>();
  }
  expect("{");
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    if (tok.identifier && tok.value.get<Matrix>()) {
      m = *tok.value.get<Matrix>() * m;
    } else if (tok.word("inverse")) {
      m = m.inverse();
    } else if (auto t = parse_transform_item(tok)) {
      m = *t * m;
    } else {
      fail("unexpected '" + tok.token.text + "' in transform");
    }
  }
  return m;
}

std::optional<Matrix> Parser::parse_transform_item(const Tok& tok) {
  if (!tok.keyword()) return std::nullopt;
  const std::string& w = tok.token.text;
  if (w == "translate") {
    Vec3d t = parse_vector();
    return Matrix::translate(t);
  }
  if (w == "rotate") return rotation(parse_vector());
  if (w == "scale") {
    Vec3d s = parse_vector();
    // POV-Ray replaces a zero scale by 1 with a warning
    for (double* c : {&s.x, &s.y, &s.z}) {
      if (*c == 0) {
        warn("scale by 0 changed to 1");
        *c = 1;
      }
    }
    return Matrix::scale(s);
  }
  if (w == "matrix") {
    // `matrix <m00, m01, m02, m10, ..., m32>`: POV-Ray's row-vector layout (p' = p M, the last
    // triple the translation), transposed into column form
    expect("<");
    int saved = vector_level_;
    vector_level_ = nesting + 1;
    double e[12];
    for (int i = 0; i < 12; ++i) {
      if (i) expect(",");
      e[i] = parse_float();
    }
    vector_level_ = saved;
    expect(">");
    return Matrix::from_rows(
        {e[0], e[3], e[6], e[9], e[1], e[4], e[7], e[10], e[2], e[5], e[8], e[11], 0, 0, 0, 1});
  }
  if (w == "transform") return parse_transform_block();
  return std::nullopt;
}

ColourMap Parser::parse_colour_map(bool pigment_map) {
  ColourMap map;
  expect("{");
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    if (tok.identifier && tok.value.get<ColourMap>()) {
      map = *tok.value.get<ColourMap>();
      continue;
    }
    if (!tok.symbol("[")) fail("expected '[' in a colour map");
    // `average` maps may leave the value out: [pigment {..}]
    double value = starts_value(peek()) && !starts_colour(peek()) ? parse_float() : 0;
    accept(",");
    const Tok& after = peek();
    if (!pigment_map && (after.token.kind == TokenKind::kNumber ||
                         (after.identifier && after.value.kind == ValueKind::kFloat))) {
      // old form [v1, v2 colour c1 colour c2]
      double value2 = parse_float();
      Colour c1 = parse_colour(), c2 = parse_colour();
      map.push_back({value, c1});
      map.push_back({value2, c2});
    } else {
      const Tok& entry = peek();
      if (pigment_map && !entry.word("pigment")) {
        // pigment_map entries hold a pigment's body: [0.5 bozo colour_map {...}]
        map.push_back({value, parse_pigment_items("]").colour});
        continue;
      } else if (entry.word("pigment")) {
        next();
        map.push_back({value, parse_pigment().colour});
      } else if (entry.identifier && entry.value.get<Pigment>()) {
        map.push_back({value, next().value.get<Pigment>()->colour});
      } else {
        map.push_back({value, parse_colour()});
      }
    }
    expect("]");
    if (map.size() > 256) fail("a colour map has at most 256 entries");
  }
  return map;
}

Pigment Parser::parse_pigment() {
  expect("{");
  return parse_pigment_items("}");
}

Pigment Parser::parse_pigment_items(const char* closing) {
  Nesting guard(*this);
  Pigment p = default_texture_.pigment;
  p.where = here();
  bool first = true;
  for (;;) {
    Tok tok = next();
    if (tok.symbol(closing)) break;
    const std::string& w = tok.token.text;
    if (first && tok.identifier && tok.value.get<Pigment>()) {
      p = *tok.value.get<Pigment>();
    } else if (starts_colour(tok) || (tok.identifier && tok.value.numeric())) {
      unget(std::move(tok));
      p.pattern = Pattern::kSolid;
      p.averaged = false;
      p.name.clear();
      p.colour = parse_colour();
    } else if (tok.keyword() && is_pattern(w)) {
      parse_pigment_pattern(*this, p, tok);
    } else if (w == "color_map" || w == "colour_map" || w == "pigment_map") {
      p.colour_map = parse_colour_map(w == "pigment_map");
    } else if (tok.identifier && tok.value.get<ColourMap>()) {
      p.colour_map = *tok.value.get<ColourMap>();
    } else if (const PigmentModifier* modifier = find_keyword(kPigmentModifiers, w)) {
      modifier->parse(*this, p, tok);
    } else if (auto m = parse_transform_item(tok)) {
      move_pigment(p, m->inverse());
    } else {
      fail("unexpected '" + w + "' in pigment");
    }
    first = false;
  }
  // the parser's estimate of the pattern's mean, which converters use where they cannot
  // evaluate the pattern
  if (p.pattern != Pattern::kSolid || p.averaged) {
    p.colour = p.list.empty() ? map_average(p.colour_map) : list_average(p.list);
  }
  return p;
}

Finish Parser::parse_finish(Finish start) {
  Finish f = std::move(start);
  expect("{");
  auto optional_albedo = [&] {
    if (peek().word("albedo")) next();
  };
  bool first = true;
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    const std::string& w = tok.token.text;
    if (first && tok.identifier && tok.value.get<Finish>()) {
      f = *tok.value.get<Finish>();
    } else if (w == "ambient") {
      f.ambient = parse_colour(false);
    } else if (w == "emission") {
      f.emission = parse_colour(false);
    } else if (w == "diffuse") {
      optional_albedo();
      f.diffuse = parse_float();
      if (accept(",")) parse_float();  // back-side diffuse
    } else if (w == "brilliance") {
      f.brilliance = parse_float();
    } else if (w == "specular") {
      optional_albedo();
      f.specular = parse_float();
    } else if (w == "roughness") {
      f.roughness = parse_float();
    } else if (w == "phong") {
      optional_albedo();
      f.phong = parse_float();
    } else if (w == "phong_size") {
      f.phong_size = parse_float();
    } else if (w == "metallic") {
      f.metallic = starts_value(peek()) ? parse_float() : 1;
    } else if (w == "reflection") {
      if (peek().symbol("{")) {
        next();
        Colour first_colour = parse_colour(false);
        f.reflection_min = f.reflection_max = first_colour;
        if (accept(",") || starts_value(peek())) f.reflection_max = parse_colour(false);
        for (;;) {
          Tok item = next();
          if (item.symbol("}")) break;
          if (item.word("fresnel")) {
            f.reflection_fresnel = parse_bool_option();
          } else if (item.word("metallic")) {
            f.reflection_metallic = parse_bool_option() ? 1 : 0;
          } else if (item.word("falloff")) {
            f.reflection_falloff = parse_float();
          } else if (item.word("exponent")) {
            f.reflection_exponent = parse_float();
          } else {
            fail("unexpected '" + item.token.text + "' in reflection");
          }
        }
      } else {
        f.reflection_min = f.reflection_max = parse_colour(false);
      }
    } else if (w == "reflection_exponent") {
      f.reflection_exponent = parse_float();
    } else if (w == "crand" || w == "refraction" || w == "ior" || w == "caustics" ||
               w == "fade_distance" || w == "fade_power") {
      parse_float();
    } else if (w == "conserve_energy") {
      f.conserve_energy = parse_bool_option();
    } else if (w == "irid" || w == "subsurface") {
      unsupported(w, location_of(tok));
      skip_block();
    } else if (w == "fresnel") {
      parse_bool_option();
    } else {
      fail("unexpected '" + w + "' in finish");
    }
    first = false;
  }
  return f;
}

Texture Parser::parse_texture() {
  expect("{");
  return parse_texture_items("}");
}

// A texture's body. Texture patterns (`checker texture {..} texture {..}`, texture_map,
// material_map, tiles) are approximated by their first texture, and reported.
// A texture's body up to `closing`: a plain texture's parts, or a texture pattern (tiles,
// texture_map, material_map, a pattern keyword), of which the first texture is used.
Texture Parser::parse_texture_items(const char* closing) {
  Nesting guard(*this);
  Texture t = default_texture_;
  t.where = here();
  bool first = true;
  bool patterned = false;
  std::optional<Texture> first_sub;
  for (;;) {
    Tok tok = next();
    if (tok.symbol(closing)) break;
    if (tok.token.kind == TokenKind::kEnd)
      fail(std::string("missing '") + closing + "' in texture");
    const std::string& w = tok.token.text;
    if (first && tok.identifier && tok.value.get<Texture>()) {
      t = *tok.value.get<Texture>();
    } else if (patterned && tok.identifier && tok.value.get<Texture>()) {
      keep_first(first_sub, *tok.value.get<Texture>());
    } else if (parse_texture_part(*this, tok, t.top())) {
      // pigment, finish or normal, read
    } else if (w == "texture" && patterned) {
      keep_first(first_sub, parse_texture());
    } else if (w == "tiles") {
      patterned = true;
      unsupported("texture pattern tiles (first texture used)", location_of(tok));
      parse_tiles(*this, first_sub);
    } else if ((w == "texture_map" || w == "material_map") && patterned) {
      parse_texture_map(*this, w, first_sub);
    } else if (tok.keyword() && (is_pattern(w) || w == "material_map")) {
      patterned = true;
      unsupported("texture pattern " + w + " (first texture used)", location_of(tok));
      if (w == "material_map") {
        unget(std::move(tok));
      } else {
        parse_pattern_arguments(w);
      }
    } else if (auto m = parse_transform_item(tok)) {
      transform_texture(t, m->inverse());
      if (first_sub) transform_texture(*first_sub, m->inverse());
    } else if (w == "warp") {
      unsupported("warp", location_of(tok));
      skip_block();
    } else if (w == "uv_mapping") {
      unsupported("uv_mapping", location_of(tok));
    } else if (patterned && tok.keyword()) {
      // the pattern's own modifiers (turbulence, octaves ...): read and dropped
      if (starts_value(peek())) parse_expression();
    } else if (patterned && tok.symbol(",")) {
      // commas between the list's textures
    } else {
      fail("unexpected '" + w + "' in texture");
    }
    first = false;
  }
  if (first_sub) {
    SourceLocation where = t.where;
    t = *first_sub;
    t.where = where;
  }
  return t;
}

Normal Parser::parse_normal() {
  expect("{");
  return parse_normal_items("}");
}

Normal Parser::parse_normal_items(const char* closing) {
  Nesting guard(*this);
  Normal n = default_texture_.normal.value_or(Normal{});
  n.where = here();
  bool first = true;
  for (;;) {
    Tok tok = next();
    if (tok.symbol(closing)) break;
    if (tok.token.kind == TokenKind::kEnd) fail(std::string("missing '") + closing + "' in normal");
    const std::string& w = tok.token.text;
    if (first && tok.identifier && tok.value.get<Normal>()) {
      n = *tok.value.get<Normal>();
    } else if (tok.keyword() && is_pattern(w)) {
      parse_normal_pattern(*this, n, tok);
    } else if (w == "bump_size") {
      n.amount = parse_float();
    } else if (w == "accuracy") {
      n.accuracy = parse_float();
    } else if (w == "no_bump_scale") {
      n.scale_bumps = !parse_bool_option();
    } else if (w == "slope_map") {
      n.slope_map = parse_slope_map(*this);
    } else if (w == "normal_map") {
      n.normal_map = parse_normal_map(*this);
    } else if (const PigmentModifier* modifier = find_keyword(kPigmentModifiers, w)) {
      modifier->parse(*this, n, tok);
    } else if (auto m = parse_transform_item(tok)) {
      n.pattern_from_world = n.pattern_from_world * m->inverse();
    } else {
      fail("unexpected '" + w + "' in normal");
    }
    first = false;
  }
  return n;
}

Interior Parser::parse_interior() {
  Interior in;
  expect("{");
  bool first = true;
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    const std::string& w = tok.token.text;
    if (first && tok.identifier && tok.value.get<Interior>()) {
      in = *tok.value.get<Interior>();
    } else if (w == "ior") {
      in.ior = parse_float();
    } else if (w == "fade_distance") {
      in.fade_distance = parse_float();
    } else if (w == "fade_power") {
      in.fade_power = parse_float();
    } else if (w == "fade_colour" || w == "fade_color") {
      in.fade_colour = parse_colour(false);
    } else if (w == "caustics" || w == "dispersion" || w == "dispersion_samples") {
      parse_float();
    } else if (w == "media" || (tok.identifier && tok.value.get<Media>())) {
      // POV-Ray sums an interior's media; each costs every ray through the object a little
      if (in.media.size() >= kMostMediaPerInterior)
        fail_at(location_of(tok),
                "an interior has at most " + std::to_string(kMostMediaPerInterior) + " media");
      in.media.push_back(w == "media" ? parse_media(tok) : *tok.value.get<Media>());
    } else {
      fail("unexpected '" + w + "' in interior");
    }
    first = false;
  }
  return in;
}

MaterialValue Parser::parse_material() {
  MaterialValue m;
  expect("{");
  bool first = true;
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    if (first && tok.identifier && tok.value.get<MaterialValue>()) {
      m = *tok.value.get<MaterialValue>();
    } else if (tok.word("texture")) {
      if (m.texture)
        add_texture_layer(*m.texture, parse_texture());  // layered, as on an object
      else
        m.texture = parse_texture();
    } else if (tok.word("interior")) {
      m.interior = parse_interior();
    } else if (auto t = parse_transform_item(tok)) {
      if (m.texture) transform_texture(*m.texture, t->inverse());
    } else {
      fail("unexpected '" + tok.token.text + "' in material");
    }
    first = false;
  }
  return m;
}

}  // namespace fb::pov::sdl
