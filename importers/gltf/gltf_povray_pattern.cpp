#include "importers/gltf/gltf_povray_pattern.h"

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "core/texture/solid_defaults.h"
#include "core/texture/solid_pattern.h"
#include "core/util/error.h"

namespace fb::gltf {

namespace {

using tinygltf::Value;
using K = SolidPatternKind;

// POV-Ray's own keywords (the patterns' are core/scene/solid_texture.h's kSolidPatternNames).
constexpr std::pair<SolidWave, const char*> kWaves[] = {
    {SolidWave::kRamp, "ramp"},   {SolidWave::kTriangle, "triangle"},
    {SolidWave::kSine, "sine"},   {SolidWave::kScallop, "scallop"},
    {SolidWave::kCubic, "cubic"}, {SolidWave::kPoly, "poly"}};

// POV-Ray's colour maps hold at most 256 entries (MAX_BLEND_MAP_ENTRIES); a list pattern at most
// three (hexagon).
constexpr size_t kMaxMapEntries = 256, kMaxListEntries = 3;
// Any number a scene may give a modifier, far beyond what makes a visible pattern.
constexpr double kLargestPatternValue = 1e12;

template <typename E, size_t N>
const char* name_of(const std::pair<E, const char*> (&table)[N], E value) {
  for (const auto& [e, name] : table)
    if (e == value) return name;
  return table[0].second;
}

template <typename E, size_t N>
E value_of(const std::pair<E, const char*> (&table)[N], const Fields& f, const char* key,
           E fallback) {
  const std::optional<std::string> word = f.word(key);
  if (!word) return fallback;
  std::string names;
  for (const auto& [e, name] : table) {
    if (*word == name) return e;
    names += std::string(names.empty() ? "" : ", ") + name;
  }
  f.fail(key, "'" + *word + "' is not one of " + names);
}

Value::Object colour_json(const SolidColour& c) {
  Value::Object o{{"colour", number_array(c.rgb)}};
  if (c.filter != 0) o["filter"] = Value(double(c.filter));
  if (c.transmit != 0) o["transmit"] = Value(double(c.transmit));
  return o;
}

SolidColour read_colour(const Fields& f, bool required) {
  SolidColour c;
  const std::optional<Rgb> rgb = f.color("colour");
  if (!rgb && required) f.fail("colour", "expected a linear colour [r, g, b]");
  c.rgb = rgb.value_or(c.rgb);
  c.filter = float(f.number("filter", 0, 1).value_or(0));
  c.transmit = float(f.number("transmit", 0, 1).value_or(0));
  return c;
}

std::optional<Vec3d> read_vec3(const Fields& f, const char* key) {
  const auto v = f.numbers(key, 3, -kLargestPatternValue, kLargestPatternValue);
  if (!v) return std::nullopt;
  if (v->size() != 3) f.fail(key, "expected three numbers");
  return Vec3d{(*v)[0], (*v)[1], (*v)[2]};
}

bool same(Vec3d a, Vec3d b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

bool is_identity(const Transform& t) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      if (t(r, c) != (r == c ? 1.0 : 0.0)) return false;
  return true;
}

SolidPattern read(const Fields& f, int depth, size_t& count) {
  if (++count > kMaxPatterns)
    throw_input(f.file(), f.path(),
                "more than " + std::to_string(kMaxPatterns) + " patterns in one pigment");
  if (depth > kMaxPatternDepth)
    throw_input(f.file(), f.path(),
                "list patterns nested deeper than " + std::to_string(kMaxPatternDepth));
  SolidPattern p;
  if (!f.has("pattern")) f.fail("pattern", "expected the pattern's name");
  p.kind = value_of(kSolidPatternNames, f, "pattern", K::kSolid);
  p.colour = read_colour(f, p.kind == K::kSolid);
  for (const Fields& stop : f.objects("colour_map", kMaxMapEntries)) {
    const std::optional<double> value = stop.number("value", 0, 1);
    if (!value) stop.fail("value", "expected the entry's value in [0, 1]");
    p.colour_map.push_back({float(*value), read_colour(stop, true)});
  }
  for (const Fields& entry : f.objects("list", kMaxListEntries))
    p.list.push_back(read(entry, depth + 1, count));
  if (const auto m =
          f.numbers("pattern_from_world", 16, -kLargestPatternValue, kLargestPatternValue)) {
    if (m->size() != 16 || (*m)[3] != 0 || (*m)[7] != 0 || (*m)[11] != 0 || (*m)[15] != 1)
      f.fail("pattern_from_world",
             "expected an affine 4x4 matrix, 16 numbers column by column ending 0, 0, 0, 1");
    std::array<double, 16> columns;
    std::copy(m->begin(), m->end(), columns.begin());
    p.pattern_from_world = Transform::from_columns(columns);
  }
  p.turbulence = read_vec3(f, "turbulence").value_or(p.turbulence);
  p.octaves = int(f.whole("octaves", -1e9, 1e9).value_or(p.octaves));
  p.omega = f.number("omega", -kLargestPatternValue, kLargestPatternValue).value_or(p.omega);
  p.lambda = f.number("lambda", -kLargestPatternValue, kLargestPatternValue).value_or(p.lambda);
  p.frequency =
      f.number("frequency", -kLargestPatternValue, kLargestPatternValue).value_or(p.frequency);
  p.phase = f.number("phase", -kLargestPatternValue, kLargestPatternValue).value_or(p.phase);
  p.wave = value_of(kWaves, f, "wave", p.wave);
  p.wave_exponent = f.number("wave_exponent", -kLargestPatternValue, kLargestPatternValue)
                        .value_or(p.wave_exponent);
  p.gradient = read_vec3(f, "gradient").value_or(p.gradient);
  p.brick_size = read_vec3(f, "brick_size").value_or(p.brick_size);
  p.mortar = f.number("mortar", -kLargestPatternValue, kLargestPatternValue).value_or(p.mortar);
  p.spiral_arms = int(f.whole("spiral_arms", -1e9, 1e9).value_or(p.spiral_arms));
  p.agate_turbulence = f.number("agate_turbulence", -kLargestPatternValue, kLargestPatternValue)
                           .value_or(p.agate_turbulence);
  return p;
}

}  // namespace

tinygltf::Value pattern_json(const SolidPattern& p) {
  if (p.kind == K::kImageMap) {
    // The extension does not carry image files: the map's average colour stands in (docs/pov.md).
    SolidPattern plain;
    plain.colour = p.colour;
    return pattern_json(plain);
  }
  const SolidPattern d;  // what the reader assumes for what is not written
  Value::Object o = colour_json(p.colour);
  o["pattern"] = Value(std::string(name_of(kSolidPatternNames, p.kind)));
  if (!p.colour_map.empty()) {
    Value::Array map;
    for (const SolidColourStop& stop : p.colour_map) {
      Value::Object entry = colour_json(stop.colour);
      entry["value"] = Value(double(stop.value));
      map.emplace_back(std::move(entry));
    }
    o["colour_map"] = Value(std::move(map));
  }
  if (!p.list.empty()) {
    Value::Array list;
    for (const SolidPattern& entry : p.list)
      list.push_back(pattern_json(entry));
    o["list"] = Value(std::move(list));
  }
  if (!is_identity(p.pattern_from_world)) {
    Value::Array m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r)
        m.emplace_back(p.pattern_from_world(r, c));
    o["pattern_from_world"] = Value(std::move(m));
  }
  if (!same(p.turbulence, d.turbulence)) o["turbulence"] = number_array(p.turbulence);
  if (p.octaves != d.octaves) o["octaves"] = Value(p.octaves);
  if (p.omega != d.omega) o["omega"] = Value(p.omega);
  if (p.lambda != d.lambda) o["lambda"] = Value(p.lambda);
  if (p.frequency != d.frequency) o["frequency"] = Value(p.frequency);
  if (p.phase != d.phase) o["phase"] = Value(p.phase);
  if (p.wave != d.wave) o["wave"] = Value(std::string(name_of(kWaves, p.wave)));
  if (p.wave_exponent != d.wave_exponent) o["wave_exponent"] = Value(p.wave_exponent);
  if (!same(p.gradient, d.gradient)) o["gradient"] = number_array(p.gradient);
  if (!same(p.brick_size, d.brick_size)) o["brick_size"] = number_array(p.brick_size);
  if (p.mortar != d.mortar) o["mortar"] = Value(p.mortar);
  if (p.spiral_arms != d.spiral_arms) o["spiral_arms"] = Value(p.spiral_arms);
  if (p.agate_turbulence != d.agate_turbulence) o["agate_turbulence"] = Value(p.agate_turbulence);
  return Value(std::move(o));
}

SolidPattern read_pattern(const Fields& json) {
  size_t count = 0;
  return read(json, 0, count);
}

// The colours a pattern shows, as the renderer evaluates them (evaluate_solid): a list pattern's
// entries, POV-Ray's default colours for those it leaves out; a value pattern's map, POV-Ray's
// default map for its kind when it has none (a `radial` without one is cyan, yellow and magenta,
// not black).
SolidColour mean_colour(const SolidPattern& p) {
  SolidColour mean;
  const auto add = [&mean](const SolidColour& c) {
    mean.rgb += c.rgb, mean.filter += c.filter, mean.transmit += c.transmit;
  };
  if (p.kind == K::kSolid || p.kind == K::kImageMap) return p.colour;  // an image map's average
  if (solid::is_list(p.kind)) {
    const int n = solid::list_size(p.kind);
    for (int i = 0; i < n; ++i)
      add(size_t(i) < p.list.size() ? mean_colour(p.list[size_t(i)])
                                    : solid::default_list_colour(p.kind, i));
    return {mean.rgb * (1.f / float(n)), mean.filter / float(n), mean.transmit / float(n)};
  }
  // The map over evenly spread values.
  const std::vector<SolidColourStop>& map =
      p.colour_map.empty() ? solid::default_map(p.kind) : p.colour_map;
  constexpr int kSamples = 64;
  for (int i = 0; i < kSamples; ++i)
    add(solid::colour_at(map, (i + 0.5) / kSamples));
  return {mean.rgb * (1.f / kSamples), mean.filter / kSamples, mean.transmit / kSamples};
}

}  // namespace fb::gltf
