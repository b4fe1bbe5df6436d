// Scene-level statements: camera, light_source, background, sky_sphere, global_settings, the
// atmospheric effects (reported), and the top-level loop.
#include "importers/pov/sdl/parser.h"

#include <cmath>

namespace fb::pov::sdl {

CameraStatement Parser::parse_camera(const Tok& keyword) {
  CameraStatement c;
  c.where = location_of(keyword);
  expect("{");
  bool declared = false;
  bool first = true;
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    const std::string& w = tok.token.text;
    if (first && tok.identifier && tok.value.get<CameraStatement>()) {
      SourceLocation where = c.where;
      c = *tok.value.get<CameraStatement>();
      c.where = where;
      declared = true;
    } else if (auto m = parse_transform_item(tok)) {
      c.transform = *m * c.transform;
    } else if (declared) {
      // after a camera identifier only transforms are allowed (POV-Ray manual 3.4.2)
      fail("only transforms may follow a camera identifier, found '" + w + "'");
    } else if (w == "perspective") {
      c.type = CameraType::kPerspective;
    } else if (w == "orthographic") {
      c.type = CameraType::kOrthographic;
    } else if (w == "fisheye") {
      c.type = CameraType::kFisheye;
    } else if (w == "ultra_wide_angle") {
      c.type = CameraType::kUltraWideAngle;
    } else if (w == "omnimax") {
      c.type = CameraType::kOmnimax;
    } else if (w == "panoramic") {
      c.type = CameraType::kPanoramic;
    } else if (w == "spherical") {
      c.type = CameraType::kSpherical;
    } else if (w == "cylinder") {
      c.type = CameraType::kCylinder;
      c.cylinder_type = static_cast<int>(parse_float());
    } else if (w == "mesh_camera") {
      c.type = CameraType::kMeshCamera;
      unsupported("mesh_camera", location_of(tok));
      skip_block();
    } else if (w == "location") {
      c.location = parse_vector();
    } else if (w == "look_at") {
      c.look_at = parse_vector();
    } else if (w == "direction") {
      c.direction = parse_vector();
    } else if (w == "right") {
      c.right = parse_vector();
      c.right_given = true;
    } else if (w == "up") {
      c.up = parse_vector();
      c.up_given = true;
    } else if (w == "sky") {
      c.sky = parse_vector();
    } else if (w == "angle") {
      c.angle_where = location_of(tok);
      c.angle_deg = parse_float();
      c.angle_v_deg.reset();  // a later `angle H` alone gives V = H / 2 again
      if (accept(",")) c.angle_v_deg = parse_float();
    } else if (w == "focal_point") {
      c.focal_point = parse_vector();
    } else if (w == "aperture") {
      c.aperture = parse_float();
    } else if (w == "blur_samples") {
      c.blur_samples = static_cast<int>(parse_float());
      if (accept(",")) c.blur_samples = static_cast<int>(parse_float());  // MIN, MAX: the maximum
    } else if (w == "confidence" || w == "variance") {
      parse_float();
    } else if (w == "bokeh") {
      skip_block();
    } else if (w == "normal") {
      c.has_normal = true;
      unsupported("camera normal", location_of(tok));
      skip_block();
    } else {
      fail("unexpected '" + w + "' in camera");
    }
    first = false;
  }
  return c;
}

LightSource Parser::parse_light(const Tok& keyword) {
  LightSource l;
  l.where = location_of(keyword);
  expect("{");
  Tok start = next();
  if (start.identifier && start.value.get<Node>() && !start.value.get<Node>()->lights.empty()) {
    l = start.value.get<Node>()->lights.front();
  } else {
    unget(std::move(start));
    l.location = parse_vector();
    accept(",");
    l.colour = parse_colour();
  }
  for (;;) {
    Tok tok = next();
    if (tok.symbol("}")) break;
    const std::string& w = tok.token.text;
    if (auto m = parse_transform_item(tok)) {
      l.location = m->point(l.location);
      l.point_at = m->point(l.point_at);
      l.axis1 = m->vector(l.axis1);
      l.axis2 = m->vector(l.axis2);
    } else if (w == "spotlight") {
      l.kind = LightKind::kSpot;
    } else if (w == "cylinder") {
      l.kind = LightKind::kCylinder;
    } else if (w == "parallel") {
      l.kind = LightKind::kParallel;
    } else if (w == "point_at") {
      l.point_at = parse_vector();
    } else if (w == "radius") {
      l.radius_deg = parse_float();
    } else if (w == "falloff") {
      l.falloff_deg = parse_float();
    } else if (w == "tightness") {
      l.tightness = parse_float();
    } else if (w == "area_light") {
      l.area = true;
      l.axis1 = parse_vector();
      accept(",");
      l.axis2 = parse_vector();
      accept(",");
      l.size1 = static_cast<int>(parse_float());
      accept(",");
      l.size2 = static_cast<int>(parse_float());
    } else if (w == "circular") {
      l.circular = parse_bool_option();
    } else if (w == "orient") {
      l.orient = parse_bool_option();
    } else if (w == "adaptive" || w == "jitter" || w == "area_illumination" ||
               w == "media_interaction" || w == "media_attenuation") {
      parse_bool_option();
    } else if (w == "fade_distance") {
      l.fade_distance = parse_float();
    } else if (w == "fade_power") {
      l.fade_power = parse_float();
    } else if (w == "shadowless") {
      l.shadowless = true;
    } else if (w == "looks_like") {
      l.has_looks_like = true;
      unsupported("looks_like", location_of(tok));
      skip_block();
    } else if (w == "projected_through" || w == "photons") {
      unsupported(w, location_of(tok));
      skip_block();
    } else if (w == "color" || w == "colour" || starts_colour(tok)) {
      unget(std::move(tok));
      l.colour = parse_colour();
    } else {
      fail("unexpected '" + w + "' in light_source");
    }
  }
  return l;
}

void Parser::parse_statement(const Tok& tok) {
  const std::string& w = tok.token.text;
  if (tok.symbol(";")) return;  // stray semicolons after statements, as POV-Ray accepts
  if (tok.word("default")) {
    // the pre-3.0 spelling of #default, still accepted by POV-Ray 3.7
    Token directive_token = tok.token;
    return directive(directive_token);
  }
  if (is_object_keyword(tok)) return emit(parse_object(tok), location_of(tok));
  if (w == "camera" && tok.keyword()) {
    if (scene_.camera) warn("more than one camera: the last one wins");
    scene_.camera = parse_camera(tok);
    return;
  }
  if (w == "background" && tok.keyword()) {
    expect("{");
    scene_.background = parse_colour();
    expect("}");
    return;
  }
  if (w == "sky_sphere" && tok.keyword()) {
    unget(tok);
    Value sky = parse_rvalue();
    scene_.sky_sphere = *sky.get<SkySphere>();
    return;
  }
  if (tok.identifier && tok.value.get<SkySphere>()) {
    scene_.sky_sphere = *tok.value.get<SkySphere>();
    return;
  }
  if (w == "fog" && tok.keyword()) {
    parse_fog(tok);
    return;
  }
  if ((w == "rainbow" || w == "media") && tok.keyword()) {
    unsupported(w, location_of(tok));
    skip_block();
    return;
  }
  if (w == "global_settings" && tok.keyword()) {
    expect("{");
    for (;;) {
      Tok item = next();
      if (item.symbol("}")) break;
      const std::string& g = item.token.text;
      if (g == "assumed_gamma") {
        scene_.assumed_gamma = parse_float();
      } else if (g == "ambient_light") {
        scene_.ambient_light = parse_colour(false);
      } else if (g == "radiosity" || g == "photons") {
        unsupported(g, location_of(item));
        skip_block();
      } else if (g == "subsurface") {
        skip_block();
      } else if (g == "irid_wavelength") {
        parse_colour(false);
      } else if (g == "charset") {
        next();
      } else if (g == "hf_gray_16") {
        parse_bool_option();
      } else if (g == "max_trace_level") {
        // POV-Ray's own limit (MAX_TRACE_LEVEL_LIMIT): a ray tree's depth, so its cost, is bounded
        const double level = parse_float();
        if (!(level >= 1 && level <= 256))
          fail("max_trace_level " + number_string(level) + " is outside [1, 256]");
        scene_.max_trace_level = std::floor(level);
      } else if (g == "adc_bailout") {
        const double bailout = parse_float();
        if (!(bailout >= 0 && bailout <= 1))
          fail("adc_bailout " + number_string(bailout) + " is outside [0, 1]");
        scene_.adc_bailout = bailout;
      } else if (g == "number_of_waves" || g == "noise_generator" || g == "max_intersections" ||
                 g == "mm_per_unit") {
        parse_float();
      } else {
        fail("unexpected '" + g + "' in global_settings");
      }
    }
    return;
  }
  if (tok.token.kind == TokenKind::kWord && !tok.identifier) {
    fail("unknown keyword or undeclared identifier '" + w + "'");
  }
  fail("unexpected " + std::string(tok.identifier ? "identifier '" + w + "'" : "'" + w + "'") +
       " at the top level of the scene");
}

Scene Parser::run() {
  for (;;) {
    Tok tok = next();
    if (tok.token.kind == TokenKind::kEnd) break;
    parse_statement(tok);
  }
  return std::move(scene_);
}

}  // namespace fb::pov::sdl
