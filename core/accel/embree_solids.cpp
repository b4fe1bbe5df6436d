#include "core/accel/embree_solids.h"

#include <embree3/rtcore.h>

#include <bit>
#include <cmath>

#include "core/math/random.h"

namespace fb {

namespace {

float down(double v) {
  return std::nextafter(float(v), -INFINITY);
}
float up(double v) {
  return std::nextafter(float(v), INFINITY);
}

// A solid has at most this many partly transparent surfaces along a ray: past it, the next one
// counts as covered (a bound for hostile scenes; a CSG of a thousand glass panes is not a scene).
constexpr int kMaxSkippedSurfaces = 256;

const EmbreeSolid& user_solid(void* user_data) {
  return *static_cast<const EmbreeSolid*>(user_data);
}

void solid_bounds(const RTCBoundsFunctionArguments* args) {
  const Bounds3d& b = user_solid(args->geometryUserPtr).solid->bounds();
  RTCBounds* out = args->bounds_o;
  out->lower_x = down(b.lo.x), out->lower_y = down(b.lo.y), out->lower_z = down(b.lo.z);
  out->upper_x = up(b.hi.x), out->upper_y = up(b.hi.y), out->upper_z = up(b.hi.z);
}

Vec3d origin(RTCRayN* rays, unsigned n, unsigned i) {
  return {RTCRayN_org_x(rays, n, i), RTCRayN_org_y(rays, n, i), RTCRayN_org_z(rays, n, i)};
}

Vec3d direction(RTCRayN* rays, unsigned n, unsigned i) {
  return {RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i), RTCRayN_dir_z(rays, n, i)};
}

// The hit record keeps only t and the normal: the renderer intersects the solid again for the
// rest (first_covered_hit is deterministic), which costs one solve per ray that ends here. The
// search stops at the ray's tfar: a solid behind the nearest hit so far costs only the culling of
// its tree's boxes.
void solid_intersect(const RTCIntersectFunctionNArguments* args) {
  const EmbreeSolid& solid = user_solid(args->geometryUserPtr);
  const unsigned n = args->N;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const auto hit = first_covered_hit(solid, origin(rays, n, i), direction(rays, n, i),
                                       RTCRayN_tnear(rays, n, i), RTCRayN_tfar(rays, n, i));
    if (!hit) continue;
    const float t = float(hit->t);
    if (!(t < RTCRayN_tfar(rays, n, i))) continue;
    RTCRayN_tfar(rays, n, i) = t;
    RTCHitN_Ng_x(hits, n, i) = float(hit->normal.x);
    RTCHitN_Ng_y(hits, n, i) = float(hit->normal.y);
    RTCHitN_Ng_z(hits, n, i) = float(hit->normal.z);
    RTCHitN_u(hits, n, i) = 0.f;
    RTCHitN_v(hits, n, i) = 0.f;
    RTCHitN_primID(hits, n, i) = args->primID;
    RTCHitN_geomID(hits, n, i) = args->geomID;
    RTCHitN_instID(hits, n, i, 0) = args->context->instID[0];
  }
}

void solid_occluded(const RTCOccludedFunctionNArguments* args) {
  const EmbreeSolid& solid = user_solid(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const auto hit =
        first_covered_hit(solid, origin(args->ray, n, i), direction(args->ray, n, i),
                          RTCRayN_tnear(args->ray, n, i), RTCRayN_tfar(args->ray, n, i));
    if (hit && float(hit->t) < RTCRayN_tfar(args->ray, n, i))
      RTCRayN_tfar(args->ray, n, i) = -INFINITY;
  }
}

}  // namespace

std::optional<SolidHit> first_covered_hit(const EmbreeSolid& s, Vec3d origin, Vec3d direction,
                                          double t_min, double t_max) {
  const auto bits = [](double v) { return uint64_t(std::bit_cast<uint32_t>(float(v))); };
  std::optional<SolidHit> hit = s.solid->first_hit(origin, direction, t_min, t_max);
  for (int skipped = 0; hit && skipped < kMaxSkippedSurfaces; ++skipped) {
    if (!s.shader->has_alpha(hit->material)) return hit;
    SurfacePoint point;
    point.position = Vec3f(hit->position);
    const uint64_t hash = pcg_hash(bits(hit->position.x) << 32 | bits(hit->position.y),
                                   bits(hit->position.z) << 32 | bits(direction.x),
                                   bits(direction.y) << 32 | bits(direction.z));
    if (s.shader->covers(hit->material, point, hash)) return hit;
    hit = s.solid->first_hit(origin, direction, hit->t, t_max);
  }
  return hit;
}

void attach_solid(RTCDevice device, RTCScene scene, const EmbreeSolid& solid, unsigned id) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, 1);
  rtcSetGeometryUserData(geometry, const_cast<EmbreeSolid*>(&solid));
  rtcSetGeometryBoundsFunction(geometry, solid_bounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, solid_intersect);
  rtcSetGeometryOccludedFunction(geometry, solid_occluded);
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene, geometry, id);
  rtcReleaseGeometry(geometry);
}

}  // namespace fb
