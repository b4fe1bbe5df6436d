#include "core/accel/embree_solids.h"

#include <embree3/rtcore.h>

#include <cmath>

namespace fb {

namespace {

float down(double v) {
  return std::nextafter(float(v), -INFINITY);
}
float up(double v) {
  return std::nextafter(float(v), INFINITY);
}

void solid_bounds(const RTCBoundsFunctionArguments* args) {
  const Bounds3d& b = static_cast<const RenderSolid*>(args->geometryUserPtr)->bounds();
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
// rest (RenderSolid::first_hit is deterministic), which costs one solve per ray that ends here.
void solid_intersect(const RTCIntersectFunctionNArguments* args) {
  const RenderSolid& solid = *static_cast<const RenderSolid*>(args->geometryUserPtr);
  const unsigned n = args->N;
  RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, n);
  RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, n);
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const auto hit =
        solid.first_hit(origin(rays, n, i), direction(rays, n, i), RTCRayN_tnear(rays, n, i));
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
  const RenderSolid& solid = *static_cast<const RenderSolid*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const auto hit = solid.first_hit(origin(args->ray, n, i), direction(args->ray, n, i),
                                     RTCRayN_tnear(args->ray, n, i));
    if (hit && float(hit->t) < RTCRayN_tfar(args->ray, n, i))
      RTCRayN_tfar(args->ray, n, i) = -INFINITY;
  }
}

}  // namespace

void attach_solid(RTCDevice device, RTCScene scene, const RenderSolid& solid, unsigned id) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, 1);
  rtcSetGeometryUserData(geometry, const_cast<RenderSolid*>(&solid));
  rtcSetGeometryBoundsFunction(geometry, solid_bounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, solid_intersect);
  rtcSetGeometryOccludedFunction(geometry, solid_occluded);
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(scene, geometry, id);
  rtcReleaseGeometry(geometry);
}

}  // namespace fb
