#include "importers/pov/pov_appearance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/math/constants.h"
#include "core/texture/solid_image_map.h"
#include "core/texture/solid_pattern.h"
#include "importers/pov/pov_space.h"
#include "importers/pov/sdl/solid_pigment.h"

namespace fb::pov {
namespace {

// A normal as the scene model's: its pattern converted as a pigment's would be (default waves,
// unit gradient), its colours unused; `pov_from_input` as for to_solid. A normal_map entry that
// is not rendered stays flat.
SolidNormal to_solid_normal(const Normal& n, const Transform& pov_from_input) {
  Pigment shape;
  static_cast<SolidPatternModifiers&>(shape) = n;
  shape.pattern = n.pattern;
  shape.pattern_from_world = n.pattern_from_world;
  SolidNormal s;
  s.pattern = to_solid(shape, 1.0, pov_from_input);
  for (const NormalMapEntry& e : n.normal_map) {
    SolidNormalStop stop;
    stop.value = float(std::clamp(e.value, 0.0, 1.0));
    if (e.normal.rendered)
      stop.normal = to_solid_normal(e.normal, Transform());  // in this normal's pattern space
    else
      stop.normal.amount = 0;
    s.normal_map.push_back(std::move(stop));
  }
  s.amount = n.amount;
  s.accuracy = n.accuracy;
  s.scale_bumps = n.scale_bumps;
  for (const SlopeMapEntry& e : n.slope_map)
    s.slope_map.push_back({float(std::clamp(e.value, 0.0, 1.0)), float(e.height), float(e.slope)});
  return s;
}

bool any_transmit(const SolidPattern& s) {
  // an image map may be clear off a `once` image or where its alpha is below 1
  if (s.colour.transmit > 0 || s.kind == SolidPatternKind::kImageMap) return true;
  for (const SolidColourStop& stop : s.colour_map)
    if (stop.colour.transmit > 0) return true;
  for (const SolidPattern& entry : s.list)
    if (any_transmit(entry)) return true;
  return false;
}

// GGX alpha for a Blinn-Phong exponent n, by matching the lobes' widths (Walter et al. 2007,
// §5.2: alpha_p = 2 / alpha_b^2 - 2); as perceptual roughness sqrt(alpha).
double roughness_for_blinn_exponent(double n) {
  return std::sqrt(std::sqrt(2 / (std::max(n, 0.0) + 2)));
}

// The highlight a finish asks for: its strength and GGX roughness. `specular` is Blinn's
// exponent 1/roughness on the half vector; `phong` is an exponent on the mirror direction, about
// a quarter of the equivalent Blinn exponent.
struct Highlight {
  double amount = 0, roughness = 1;
};
Highlight highlight(const Finish& f) {
  Highlight h;
  if (f.specular > 0)
    h = {f.specular, roughness_for_blinn_exponent(1 / std::max(f.roughness, 1e-4))};
  if (f.phong > h.amount) h = {f.phong, roughness_for_blinn_exponent(4 * f.phong_size)};
  return h;
}

double max_channel(const Colour& c) {
  return std::max({c.r, c.g, c.b});
}

// The content of a material, for finding identical ones: every field but the name.
void append_pattern(std::string& key, const SolidPattern& s);
void append(std::string& key, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g,", v);
  key += buf;
}
void append(std::string& key, Vec3d v) {
  append(key, v.x), append(key, v.y), append(key, v.z);
}
void append(std::string& key, Rgb v) {
  append(key, Vec3d(v));
}
void append(std::string& key, const SolidColour& c) {
  append(key, c.rgb), append(key, c.filter), append(key, c.transmit);
}
void append_pattern(std::string& key, const SolidPattern& s) {
  key += '{';
  append(key, int(s.kind));
  append(key, s.colour);
  for (const SolidColourStop& stop : s.colour_map)
    append(key, stop.value), append(key, stop.colour);
  key += "|";
  for (const SolidPattern& entry : s.list)
    append_pattern(key, entry);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c)
      append(key, s.pattern_from_world(r, c));
  append(key, s.turbulence);
  append(key, s.octaves), append(key, s.omega), append(key, s.lambda), append(key, s.frequency);
  append(key, s.phase), append(key, int(s.wave)), append(key, s.wave_exponent);
  append(key, s.gradient), append(key, s.brick_size), append(key, s.mortar);
  append(key, s.spiral_arms), append(key, s.agate_turbulence);
  const SolidImageMap& image = s.image_map;
  append(key, image.image), append(key, int(image.projection)), append(key, image.once);
  append(key, int(image.interpolation)), append(key, image.srgb), append(key, image.decode_gamma);
  append(key, image.filter_all), append(key, image.transmit_all), append(key, image.major_radius);
  key += "}";
}
void append_normal(std::string& key, const SolidNormal& n) {
  key += "normal{";
  append_pattern(key, n.pattern);
  append(key, n.amount), append(key, n.accuracy), append(key, n.scale_bumps);
  for (const SolidSlopeStop& stop : n.slope_map)
    append(key, stop.value), append(key, stop.height), append(key, stop.slope);
  for (const SolidNormalStop& stop : n.normal_map)
    append(key, stop.value), append_normal(key, stop.normal);
  key += "}";
}
void append_finish(std::string& key, const PovFinish& f) {
  key += "pov{";
  append(key, f.pigment), append(key, f.pigment_scale), append(key, f.filter);
  append(key, f.transmit), append(key, f.coverage), append(key, f.ambient);
  append(key, f.emission);
  append(key, f.diffuse), append(key, f.brilliance), append(key, f.phong);
  append(key, f.phong_size), append(key, f.specular), append(key, f.roughness);
  append(key, f.metallic), append(key, f.reflection_min), append(key, f.reflection_max);
  append(key, f.reflection_falloff), append(key, f.reflection_exponent);
  append(key, f.reflection_fresnel), append(key, f.reflection_metallic), append(key, f.ior);
  key += "}";
}
void append_medium(std::string& key, const InteriorMedium& m) {
  key += "medium{";
  append(key, m.absorption), append(key, m.scattering), append(key, m.emission);
  append(key, m.povray_extinction);
  key += "}";
}
std::string material_key(const Material& m) {
  std::string key;
  if (m.pov_finish) append_finish(key, *m.pov_finish);
  if (m.medium) append_medium(key, *m.medium);
  append(key, m.base_color), append(key, m.emission), append(key, m.double_sided);
  append(key, m.metallic), append(key, m.roughness), append(key, m.transmission);
  append(key, m.ior), append(key, m.specular), append(key, int(m.alpha_mode)), append(key, m.alpha);
  if (m.base_color_pattern) append_pattern(key, *m.base_color_pattern);
  if (m.normal_pattern) append_normal(key, *m.normal_pattern);
  for (const Material& layer : m.layers)
    key += "layer[" + material_key(layer) + "]";
  return key;
}

// A light's placement: at `position`, shining down its -Z towards `target` (world space).
Transform aimed(Vec3d position, Vec3d target) {
  Vec3d d = target - position;
  if (!(dot(d, d) > 0)) d = {0, 0, -1};
  const Vec3d n = d / std::sqrt(dot(d, d));
  const Vec3d up = std::abs(n.y) > 0.999 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  return Transform::look_at(position, position + n, up);
}

// POV-Ray's fogs as global media (docs/pov.md "Fog"): a fog of zero distance is none, as in
// POV-Ray; the up vector mirrored into the world like any direction (heights keep their values).
void convert_fogs(const std::vector<Fog>& fogs, double gamma, fb::Scene& out) {
  for (const Fog& fog : fogs) {
    if (std::abs(fog.distance) < 1e-10) continue;
    GlobalMedium m;
    m.profile = fog.ground ? MediumProfile::kGround : MediumProfile::kConstant;
    m.distance_m = std::abs(fog.distance);
    m.colour = decode(fog.colour, gamma);
    m.filter = float(std::clamp(fog.colour.filter, 0.0, 1.0));
    m.transmit = float(std::clamp(fog.colour.transmit, 0.0, 1.0));
    const Vec3d up = world_from_pov(fog.up);
    const double length = std::sqrt(dot(up, up));
    m.up = length > 0 ? up / length : Vec3d{0, 1, 0};
    m.offset_m = fog.offset, m.altitude_m = fog.altitude;
    out.media.push_back(m);
  }
}

}  // namespace

double colour_gamma(const Scene& scene) {
  if (scene.assumed_gamma && *scene.assumed_gamma > 0) return *scene.assumed_gamma;
  return scene.version >= 3.7 ? 1.0 : 2.2;
}

namespace {

// The finish as written, for the `povray` integrator (PovFinish says what each field is).
PovFinish pov_finish(const Finish& f, Rgb pigment, float pigment_scale, float filter,
                     float transmit, float coverage, double ior, Rgb ambient_light) {
  const auto colour = [](const Colour& c) { return Rgb(float(c.r), float(c.g), float(c.b)); };
  PovFinish p;
  p.pigment = pigment;
  p.pigment_scale = pigment_scale;
  p.filter = filter, p.transmit = transmit, p.coverage = coverage;
  p.ambient = colour(f.ambient) * ambient_light;
  p.emission = colour(f.emission);
  p.diffuse = float(f.diffuse), p.brilliance = float(f.brilliance);
  p.phong = float(f.phong), p.phong_size = float(f.phong_size);
  p.specular = float(f.specular), p.roughness = float(f.roughness);
  p.metallic = float(f.metallic);
  p.reflection_min = colour(f.reflection_min), p.reflection_max = colour(f.reflection_max);
  p.reflection_falloff = float(f.reflection_falloff);
  p.reflection_exponent = float(f.reflection_exponent);
  p.reflection_fresnel = f.reflection_fresnel;
  p.reflection_metallic = float(f.reflection_metallic);
  // The interior shows only through a transparent pigment or in Fresnel's reflection: an opaque
  // surface keeps sharing its material whatever its interior.
  p.ior = filter + transmit > 0 || f.reflection_fresnel ? float(ior) : 1.f;
  return p;
}

// A layer's reflection and highlights added to the base's finish, which is the one the `povray`
// integrator lights a hit with: POV-Ray adds every layer's reflected ray and highlights whatever
// shows of the layer (ComputeLightedTexture), so their amounts add; the first layer that has one
// gives its shape (falloff, fresnel, metallic, exponent; phong_size; roughness). The layers'
// diffuse is in the blended base colour already (SurfaceShader).
void add_layer_finish(PovFinish& base, const PovFinish& layer) {
  if (max_component(layer.reflection_max) > 0 || max_component(layer.reflection_min) > 0) {
    if (!(max_component(base.reflection_max) > 0 || max_component(base.reflection_min) > 0)) {
      base.reflection_falloff = layer.reflection_falloff;
      base.reflection_exponent = layer.reflection_exponent;
      base.reflection_fresnel = layer.reflection_fresnel;
      base.reflection_metallic = layer.reflection_metallic;
    }
    base.reflection_min += layer.reflection_min;
    base.reflection_max += layer.reflection_max;
  }
  if (layer.phong > 0) {
    if (!(base.phong > 0)) base.phong_size = layer.phong_size;
    base.phong += layer.phong;
  }
  if (layer.specular > 0) {
    if (!(base.specular > 0)) base.roughness = layer.roughness;
    base.specular += layer.specular;
  }
}

// One texture's material. A layer over others (`over_layers`) keeps its pigment as a pattern even
// when plain, whose filter and transmit at the hit then say how much of the layers below shows
// (SurfaceShader::shade), instead of making the surface transparent.
Material make_layer_material(const Texture& texture, const std::optional<Interior>& interior,
                             double gamma, const Colour& ambient_light, bool over_layers) {
  const Finish& f = texture.finish;
  Material m;
  m.name = texture.where.text();
  m.double_sided = true;  // POV-Ray's surfaces look the same from both sides
  const SolidPattern pigment = to_solid(texture.pigment, gamma, world_from_pov_space());
  const bool patterned = pigment.kind != SolidPatternKind::kSolid;
  // The pigment's colour: the pattern's average where one colour must stand for it (emission).
  const Rgb rho = decode(texture.pigment.colour, gamma);
  const bool colour_at_hit = patterned || over_layers;
  const float filter = colour_at_hit ? 0.f : pigment.colour.filter;
  const float transmit = colour_at_hit ? 0.f : pigment.colour.transmit;
  const double ior = interior ? interior->ior : 1.0;
  const bool refracts = ior != 1.0;
  // A ray must meet the surface of a medium to know it enters it: not a coverage that skips hits.
  const bool holds_medium = interior && !interior->media.empty();

  // Transparency: filter is coloured transmission; transmit is plain see-through coverage, unless
  // the interior refracts or holds a medium, when it is transmission too (tinted, unlike
  // POV-Ray's).
  const bool transmit_transmits = refracts || holds_medium;
  m.transmission = std::clamp(filter + (transmit_transmits ? transmit : 0.f), 0.f, 1.f);
  if (!transmit_transmits && !over_layers &&
      (transmit > 0 || (patterned && any_transmit(pigment)))) {
    m.alpha_mode = AlphaMode::kBlend;
    m.alpha = 1.f - transmit;
  }

  const double reflection = max_channel(f.reflection_max);
  const bool metal = reflection > 0 && (f.metallic > 0 || f.reflection_metallic > 0);
  // Diffuse: albedo rho d, so that a light of colour c (intensity pi c) gives rho d c cos(theta)
  // as POV-Ray's diffuse does. Transmissive and metallic surfaces tint by rho itself.
  const float d = float(std::max(f.diffuse, 0.0));
  const float scale = m.transmission > 0 || metal ? 1.f : d;
  m.base_color = Rgb{scale, scale, scale};
  if (colour_at_hit)
    m.base_color_pattern = pigment;
  else
    m.base_color = m.base_color * pigment.colour.rgb;

  // POV-Ray's ambient stands in for indirect light, which the path tracer computes: dropped,
  // except on a finish without diffuse, which is self-lit (test markers, skies). Both are times
  // the pigment: a pattern's colour at the hit (SurfaceShader::emission), or the plain colour.
  m.emission = Rgb(float(f.emission.r), float(f.emission.g), float(f.emission.b));
  if (d == 0.f)
    m.emission += Rgb(float(f.ambient.r), float(f.ambient.g), float(f.ambient.b)) *
                  decode(ambient_light, gamma);
  if (!colour_at_hit) m.emission = m.emission * rho;

  const Highlight h = highlight(f);
  if (reflection > 0 || m.transmission > 0) {
    // A mirror or glass: sharp, unless a highlight asks for some blur (kept small, since POV-Ray's
    // highlights imitate the reflection of its point lights, which a mirror cannot show).
    m.roughness = float(h.amount > 0 ? std::min(h.roughness, 0.15) : 0.0);
    m.specular = 1.f;
    if (refracts || f.reflection_fresnel) {
      m.ior = float(ior);
    } else if (reflection > 0) {
      // The reflectance at normal incidence as Fresnel's F0 = ((n - 1) / (n + 1))^2; POV-Ray's
      // reflection_max at grazing angles is left to Schlick's rise.
      const double f0 =
          std::clamp(std::max(max_channel(f.reflection_min), 0.25 * reflection), 0.01, 0.9);
      m.ior = float((1 + std::sqrt(f0)) / (1 - std::sqrt(f0)));
    } else {
      m.ior = 1.f;
    }
    if (metal) m.metallic = float(std::clamp(reflection, 0.0, 1.0));
  } else if (h.amount > 0) {
    m.roughness = float(h.roughness);
    m.specular = float(std::clamp(h.amount, 0.0, 1.0));
  } else {
    m.specular = 0.f;  // POV-Ray's default finish: Lambertian
    m.roughness = 1.f;
  }
  if (texture.normal && texture.normal->rendered)
    m.normal_pattern = to_solid_normal(*texture.normal, world_from_pov_space());
  m.pov_finish =
      pov_finish(f, rho, scale, filter, transmit, m.alpha_mode == AlphaMode::kBlend ? m.alpha : 1.f,
                 ior, decode(ambient_light, gamma));
  return m;
}

// The most points along a segment the `povray` integrator sums a medium's light at.
constexpr uint32_t kMostPovRayMediaPoints = 1024;

// An interior's media as one medium (docs/pov.md "Media"): POV-Ray adds their coefficients.
// Absorption and scattering are rates, taken as written; emission is light, decoded as colours.
// POV-Ray samples with the settings of the media with the most intervals (the first of them).
InteriorMedium interior_medium(const std::vector<Media>& media, double gamma) {
  const auto rate = [](const Colour& c) { return Rgb(float(c.r), float(c.g), float(c.b)); };
  const Media* sampled = &media.front();
  for (const Media& one : media)
    if (one.intervals > sampled->intervals) sampled = &one;
  InteriorMedium sum;
  sum.povray_points = std::min(uint32_t(std::max(2, sampled->samples / 2 + 1) * sampled->intervals),
                               kMostPovRayMediaPoints);
  for (const Media& one : media) {
    sum.absorption += rate(one.absorption);
    sum.scattering += rate(one.scattering);
    sum.emission += decode(one.emission, gamma);
    sum.povray_extinction += rate(one.absorption) + rate(one.scattering) * float(one.extinction);
  }
  return sum;
}

}  // namespace

Material make_material(const Texture& texture, const std::optional<Interior>& interior,
                       double gamma, const Colour& ambient_light) {
  Material m = make_layer_material(texture, interior, gamma, ambient_light, false);
  if (interior && !interior->media.empty()) m.medium = interior_medium(interior->media, gamma);
  for (const Texture& layer : texture.layers) {
    m.layers.push_back(make_layer_material(layer, interior, gamma, ambient_light, true));
    add_layer_finish(*m.pov_finish, *m.layers.back().pov_finish);
  }
  return m;
}

MaterialTable::MaterialTable(const Scene& scene, fb::Scene& out, Diagnostics& diagnostics)
    : out_(out),
      diagnostics_(diagnostics),
      gamma_(colour_gamma(scene)),
      ambient_light_(scene.ambient_light) {}

void MaterialTable::report(const Texture& texture) {
  const auto once = [&](const std::string& what, const SourceLocation& where) {
    if (reported_.insert(what).second)
      diagnostics_.warn(where.text() + ": " + what + " (first met here)");
  };
  // The importer does not know the integrator: the message says which one leaves it out.
  if (texture.finish.brilliance != 1)
    once(
        "finish brilliance is not rendered by the path integrator (--integrator povray renders it)",
        texture.where);
  const auto walk = [&](const auto& self, const Pigment& p) -> void {
    if (p.averaged)
      once("pattern " + (p.name.empty() ? std::string("image_map") : p.name) +
               " is not rendered (its average colour is used)",
           p.where);
    for (const Pigment& entry : p.list)
      self(self, entry);
  };
  walk(walk, texture.pigment);
  for (const Texture& layer : texture.layers)
    report(layer);
}

uint32_t MaterialTable::material(const Texture& texture, const std::optional<Interior>& interior) {
  report(texture);
  Material m = make_material(texture, interior, gamma_, ambient_light_);
  const auto [it, added] = index_.try_emplace(material_key(m), uint32_t(out_.materials.size()));
  if (added) out_.materials.push_back(std::move(m));
  return it->second;
}

void convert_lights(const Scene& scene, fb::Scene& out, Diagnostics& diagnostics) {
  const double gamma = colour_gamma(scene);
  bool looks_like_reported = false;
  for (const LightSource& l : scene.lights) {
    Light light;
    light.name = l.where.text();
    // A Lambertian albedo rho d lit by intensity pi c at any distance (no fading) reflects
    // rho d c cos(theta): POV-Ray's diffuse term for a light of colour c.
    light.intensity = decode(l.colour, gamma) * float(kPi);
    light.decay = LightDecay::kPovRay;
    light.fade_distance_m = l.fade_distance, light.fade_power = l.fade_power;
    light.casts_shadows = !l.shadowless;
    const Vec3d position = world_from_pov(l.location), target = world_from_pov(l.point_at);
    switch (l.kind) {
      case LightKind::kPoint:
        light.world_from_light = Transform::translate(position);
        break;
      case LightKind::kSpot:
        light.type = LightType::kSpot;
        light.spot_falloff = SpotFalloff::kPov;
        light.spot_inner_angle_rad = l.radius_deg * kPi / 180;
        light.spot_outer_angle_rad = l.falloff_deg * kPi / 180;
        light.spot_tightness = l.tightness;
        light.world_from_light = aimed(position, target);
        break;
      case LightKind::kCylinder:
        diagnostics.warn(l.where.text() +
                         ": cylinder light rendered as a parallel light (no beam radius)");
        [[fallthrough]];
      case LightKind::kParallel:
        light.type = LightType::kDirectional;  // irradiance pi c
        light.world_from_light = aimed(position, target);
        break;
    }
    if (l.area && l.size1 * l.size2 > 1) {
      const Transform light_from_world = light.world_from_light.inverse();
      light.area_axis1 = light_from_world.vector(world_from_pov(l.axis1));
      light.area_axis2 = light_from_world.vector(world_from_pov(l.axis2));
      light.area_size1 = uint32_t(std::clamp(l.size1, 1, 4096));
      light.area_size2 = uint32_t(std::clamp(l.size2, 1, 4096));
      light.area_circular = l.circular, light.area_orient = l.orient;
    }
    if (l.has_looks_like && !looks_like_reported) {
      diagnostics.warn(l.where.text() + ": light_source looks_like is not rendered");
      looks_like_reported = true;
    }
    out.lights.push_back(std::move(light));
  }
}

void convert_environment(const Scene& scene, fb::Scene& out, Diagnostics& diagnostics) {
  const double gamma = colour_gamma(scene);
  const Rgb background = scene.background ? decode(*scene.background, gamma) : Rgb{};
  out.background = background;
  convert_fogs(scene.fogs, gamma, out);
  if (!scene.sky_sphere || scene.sky_sphere->pigments.empty()) return;
  const SkySphere& sky = *scene.sky_sphere;
  std::vector<SolidPattern> layers;
  std::vector<uint8_t> image_uses(out.images.size(), 0);
  for (const Pigment& p : sky.pigments) {
    if (p.averaged)
      diagnostics.warn(p.where.text() + ": sky_sphere pattern " + p.name +
                       " is not rendered (its average colour is used)");
    layers.push_back(to_solid(p, gamma, Transform()));  // evaluated in the sky's own space
    mark_image_map_uses(layers.back(), image_uses);
  }
  // the sky's image maps, read as a render reads them (an unreadable image: an InputError)
  const TextureImages images(out, image_uses);
  const Transform sky_from_pov = sky.transform.inverse();
  EnvironmentMap map;
  map.name = "sky_sphere (" + sky.pigments.front().where.text() + ")";
  map.width = kSkyWidth, map.height = kSkyHeight;
  map.texels.resize(size_t(kSkyWidth) * kSkyHeight);
  for (uint32_t y = 0; y < kSkyHeight; ++y)
    for (uint32_t x = 0; x < kSkyWidth; ++x) {
      // The texel's direction in Blender's Z-up axes (scene.h, EnvironmentMap), then POV-Ray's:
      // world (x, y, z) = Blender (x, z, -y), POV-Ray (x, y, -z) of the world.
      const double phi = (0.5 - (x + 0.5) / kSkyWidth) * 2 * kPi,
                   theta = (y + 0.5) / kSkyHeight * kPi;
      const Vec3d blender{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                          std::cos(theta)};
      const Vec3d pov_direction{blender.x, blender.z, blender.y};
      // POV-Ray's ComputeSky: the ray direction, through the sky's inverse transform, as a point;
      // the last pigment on top, each letting through its filter and transmit.
      const Vec3d p = sky_from_pov.point(pov_direction);
      Rgb colour{};
      double through = 1, filter = 1, transmit = 1;
      for (size_t i = layers.size(); i-- > 0;) {
        const SolidColour c = evaluate_solid(layers[i], p, &images);
        colour += c.rgb * float(through * std::max(0.0, 1.0 - c.filter - c.transmit));
        filter *= c.filter, transmit *= c.transmit;
        through = std::abs(filter) + std::abs(transmit);
      }
      map.texels[size_t(y) * kSkyWidth + x] = colour + background * float(through);
    }
  out.environment = std::move(map);
}

}  // namespace fb::pov
