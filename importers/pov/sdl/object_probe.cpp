#include "importers/pov/sdl/object_probe.h"

#include <algorithm>
#include <cmath>

#include "core/util/diagnostics.h"
#include "importers/pov/pov_geometry.h"
#include "importers/pov/pov_space.h"

namespace fb::pov::sdl {

namespace {

const Bounds3d kPovUnboundedReach{
    {-kPovUnboundedExtent, -kPovUnboundedExtent, -kPovUnboundedExtent},
    {kPovUnboundedExtent, kPovUnboundedExtent, kPovUnboundedExtent}};

// The mirror is its own inverse: render space here is POV-Ray's space.
Transform pov_from_world() {
  return world_from_pov_space();
}

Vec3d to_vec3d(const float (&v)[3]) {
  return {v[0], v[1], v[2]};
}

}  // namespace

ObjectProbe::ObjectProbe(const Object& object) {
  pov::Scene pov;
  pov.objects.push_back(object);
  // An object the scene hides (no_image) is still there to be traced, as in POV-Ray.
  pov.objects.back().no_image = false;
  // Conversion warnings are the render's to give, where the object is placed.
  Diagnostics ignored;
  convert_objects(
      pov, [](const Texture&, const std::optional<Interior>&) { return 0u; }, scene_, ignored);
  scene_.materials.push_back({});

  const Transform render_from_world = pov_from_world();
  for (const Solid& solid : scene_.solids) {
    solids_.emplace_back(solid, render_from_world, kPovUnboundedReach);
    const Bounds3d b = solid_bounds(solid, render_from_world);
    bounds_.extend({max(b.lo, kPovUnboundedReach.lo), min(b.hi, kPovUnboundedReach.hi)});
  }
  for (const MeshInstance& instance : scene_.instances) {
    const Transform pov_from_object = render_from_world * instance.world_from_object;
    for (const Vec3f& p : scene_.meshes[instance.mesh].positions)
      bounds_.extend(pov_from_object.point({p.x, p.y, p.z}));
  }
  if (!scene_.instances.empty())
    triangles_ =
        std::make_unique<RenderGeometry>(scene_, render_from_world, ShotTimes{}, MotionTolerance{});
}

ObjectProbe::~ObjectProbe() = default;

std::optional<ProbeHit> ObjectProbe::trace(Vec3d origin, Vec3d direction) const {
  const double len = length(direction);
  if (!(len > 0) || !std::isfinite(len) || !is_finite(origin)) return std::nullopt;
  const Vec3d d = direction / len;  // POV-Ray normalises it; t is then a distance for all parts
  std::optional<ProbeHit> nearest;
  double nearest_t = HUGE_VAL;
  for (const RenderSolid& solid : solids_)
    if (std::optional<SolidHit> hit = solid.first_hit(origin, d, 0, nearest_t)) {
      nearest_t = hit->t;
      nearest = ProbeHit{hit->position, hit->normal};
    }
  if (triangles_) {
    const fb_ray ray{{float(origin.x), float(origin.y), float(origin.z)},
                     {float(d.x), float(d.y), float(d.z)},
                     0.f,
                     float(std::min(nearest_t, double(HUGE_VALF))),
                     0.f};
    fb_hit hit{};
    if (triangles_->intersect(ray, hit) && hit.t < nearest_t) {
      // A triangle's winding gives its side; without an inside here it faces the ray, which
      // is what POV-Ray's height fields give to a ray from above.
      Vec3d n = normalize(to_vec3d(hit.shading_normal));
      if (dot(to_vec3d(hit.geometric_normal), d) > 0) n = -n;
      nearest = ProbeHit{origin + d * double(hit.t), n};
    }
  }
  return nearest;
}

bool ObjectProbe::inside(Vec3d point) const {
  return std::any_of(solids_.begin(), solids_.end(),
                     [&](const RenderSolid& solid) { return solid.contains(point); });
}

}  // namespace fb::pov::sdl
