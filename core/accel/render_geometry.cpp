#include "core/accel/render_geometry.h"

#include <embree3/rtcore.h>

#include <unistd.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/util/error.h"

namespace fb {

struct RenderGeometry::Mesh {
  std::vector<Vec3f> positions;  // one extra element: Embree reads 16 bytes past the last vertex
  std::vector<Vec3f> normals;
  std::vector<uint32_t> indices;
  uint32_t material = 0;
  uint32_t first_emitter = FB_NONE;
};

struct RenderGeometry::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::string error;
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

void record_embree_error(void* user, RTCError, const char* message) {
  static_cast<std::string*>(user)->assign(message ? message : "unknown Embree error");
}

// gamma(n) = n u / (1 - n u), the bound on n rounded float operations (pbrt 4e §6.8.1).
constexpr float gamma(int n) {
  constexpr float u = std::numeric_limits<float>::epsilon() * 0.5f;
  return (n * u) / (1 - n * u);
}

// Embree (Debian builds keep its assertions) aborts the process on a ray with a NaN or a component
// beyond FLT_LARGE (1.8e18); plugins must not be able to do that, so such rays are misses.
constexpr double kLargestCoordinate = 1e18;

bool traceable(const fb_ray& ray) {
  for (int i = 0; i < 3; ++i)
    if (!(std::abs(ray.origin[i]) <= kLargestCoordinate) ||
        !(std::abs(ray.direction[i]) <= kLargestCoordinate))
      return false;
  return !std::isnan(ray.t_min) && !std::isnan(ray.t_max);
}

// Flattening copies every instance's triangles; refuse before allocating when that would take
// more than half of this machine's memory (vertices, indices, normals and Embree's BVH: about
// 120 bytes per triangle measured on Embree 3.13 MEDIUM builds, notes/deps.md).
void check_memory_budget(const Scene& scene) {
  constexpr double kBytesPerTriangle = 120;
  const double triangles = double(scene.triangle_count());
  const double budget = 0.5 * double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (triangles * kBytesPerTriangle > budget)
    throw InputError(scene.file.string() + ": the scene flattens to " + number_text(triangles) +
                     " triangles (every instance copied), about " +
                     number_text(triangles * kBytesPerTriangle / 1e9) +
                     " GB, more than half of this "
                     "machine's " +
                     number_text(2 * budget / 1e9) + " GB");
}

RTCRay to_embree(const fb_ray& ray) {
  RTCRay r;
  r.org_x = ray.origin[0], r.org_y = ray.origin[1], r.org_z = ray.origin[2];
  r.dir_x = ray.direction[0], r.dir_y = ray.direction[1], r.dir_z = ray.direction[2];
  r.tnear = ray.t_min;
  r.tfar = ray.t_max;
  r.time = 0.f;  // static geometry: Embree's motion time is unused
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
  return r;
}

RTCRayHit to_embree_hit(const fb_ray& ray) {
  RTCRayHit rh;
  rh.ray = to_embree(ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace

RenderGeometry::RenderGeometry(const Scene& scene, const Transform& render_from_world)
    : embree_(std::make_unique<Embree>()) {
  embree_->device = rtcNewDevice(nullptr);
  if (!embree_->device) throw InputError("cannot create an Embree device");
  rtcSetDeviceErrorFunction(embree_->device, record_embree_error, &embree_->error);
  embree_->scene = rtcNewScene(embree_->device);
  // Watertight triangle tests: no ray slips between two triangles of a closed mesh (light leaks
  // into closed rooms), and single rays and packets agree on every hit.
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);

  check_memory_budget(scene);
  Vec3d lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi = -lo;
  for (const MeshInstance& instance : scene.instances) {
    const TriangleMesh& source = scene.meshes[instance.mesh];
    if (source.indices.empty()) continue;
    const Transform render_from_object = render_from_world * instance.world_from_object;
    const Transform normal_transform = render_from_object.normal_transform();
    // A mirroring transform turns counter-clockwise into clockwise: swap two corners so the
    // winding (and with it the front face) survives, as glTF requires.
    const bool mirrored = render_from_object.determinant3x3() < 0;

    Mesh mesh;
    mesh.material = source.material;
    mesh.positions.reserve(source.positions.size() + 1);
    for (const Vec3f& p : source.positions) {
      const Vec3d q = render_from_object.point(Vec3d(p));
      if (!(max_component(abs(q)) <= kLargestCoordinate))
        throw InputError("instance '" + instance.node + "' of mesh '" + source.name +
                         "': a vertex lies beyond 1e18 m of the camera (scales multiply too far)");
      lo = min(lo, q), hi = max(hi, q);
      mesh.positions.emplace_back(q);
    }
    mesh.positions.emplace_back();
    for (const Vec3f& n : source.normals) {
      const Vec3d m = normal_transform.vector(Vec3d(n));
      const double len = length(m);
      mesh.normals.emplace_back(len > 0 ? m / len : Vec3d{});
    }
    mesh.indices = source.indices;
    if (mirrored)
      for (size_t i = 0; i < mesh.indices.size(); i += 3)
        std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);

    const Material& material = scene.materials[mesh.material];
    if (max_component(material.emission) > 0.f) {
      mesh.first_emitter = static_cast<uint32_t>(emitters_.size());
      for (size_t i = 0; i < mesh.indices.size(); i += 3) {
        EmissiveTriangle e{mesh.positions[mesh.indices[i]],
                           mesh.positions[mesh.indices[i + 1]],
                           mesh.positions[mesh.indices[i + 2]],
                           {},
                           0.f,
                           mesh.material};
        const Vec3f c = cross(e.p1 - e.p0, e.p2 - e.p0);
        e.area = 0.5f * length(c);
        e.normal = e.area > 0.f ? c / (2.f * e.area) : Vec3f{0, 0, 1};
        emitters_.push_back(e);  // zero-area ones stay, so indices match primitive IDs
      }
    }

    RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               mesh.positions.data(), 0, sizeof(Vec3f), mesh.positions.size() - 1);
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               mesh.indices.data(), 0, 3 * sizeof(uint32_t),
                               mesh.indices.size() / 3);
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(embree_->scene, geometry, static_cast<unsigned>(meshes_.size()));
    rtcReleaseGeometry(geometry);
    triangle_count_ += mesh.indices.size() / 3;
    meshes_.push_back(
        std::move(mesh));  // vector storage moves with it: the shared pointers stay valid
  }
  rtcCommitScene(embree_->scene);
  if (!embree_->error.empty())
    throw InputError("Embree could not build the scene: " + embree_->error);
  if (lo.x <= hi.x) {
    centre_ = Vec3f((lo + hi) * 0.5);
    radius_ = static_cast<float>(length(hi - lo) * 0.5);
  }
}

RenderGeometry::~RenderGeometry() = default;

bool RenderGeometry::intersect(const fb_ray& ray, fb_hit& hit) const {
  if (!traceable(ray)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = to_embree_hit(ray);
  rtcIntersect1(embree_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  fill_hit(meshes_[rh.hit.geomID], rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, hit);
  return true;
}

void RenderGeometry::intersect_coherent(const fb_ray* rays, size_t count, fb_hit* hits) const {
  thread_local std::vector<RTCRayHit> stream;
  stream.resize(count);
  for (size_t i = 0; i < count; ++i)
    stream[i] = to_embree_hit(rays[i]);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // Embree packs the stream into packets
  rtcIntersect1M(embree_->scene, &context, stream.data(), unsigned(count), sizeof(RTCRayHit));
  for (size_t i = 0; i < count; ++i) {
    const RTCRayHit& rh = stream[i];
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      hits[i].t = HUGE_VALF;
    else
      fill_hit(meshes_[rh.hit.geomID], rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, hits[i]);
  }
}

void RenderGeometry::fill_hit(const Mesh& mesh, uint32_t primitive, float u, float v, float t,
                              fb_hit& hit) {
  const uint32_t* tri = &mesh.indices[3 * size_t(primitive)];
  const Vec3f p0 = mesh.positions[tri[0]], p1 = mesh.positions[tri[1]], p2 = mesh.positions[tri[2]];
  const float b1 = u, b2 = v, b0 = 1.f - b1 - b2;
  // Re-interpolating from the vertices puts the point on the triangle's plane up to rounding,
  // bounded by gamma(7) times the magnitudes summed (pbrt 4e §6.8.4).
  const Vec3f p = p0 * b0 + p1 * b1 + p2 * b2;
  const Vec3f error = (abs(p0 * b0) + abs(p1 * b1) + abs(p2 * b2)) * gamma(7);
  const Vec3f ng = normalize(cross(p1 - p0, p2 - p0));
  Vec3f ns = ng;
  if (!mesh.normals.empty()) {
    const Vec3f n =
        mesh.normals[tri[0]] * b0 + mesh.normals[tri[1]] * b1 + mesh.normals[tri[2]] * b2;
    const float len = length(n);
    if (len > 0.f) ns = n / len;
    if (dot(ns, ng) < 0.f) ns = -ns;
  }
  hit.t = t;
  p.store(hit.position);
  error.store(hit.position_error);
  ng.store(hit.geometric_normal);
  ns.store(hit.shading_normal);
  hit.material = mesh.material;
  hit.emitter = mesh.first_emitter == FB_NONE ? FB_NONE : mesh.first_emitter + primitive;
}

bool RenderGeometry::occluded(const fb_ray& ray) const {
  if (!traceable(ray)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = to_embree(ray);
  rtcOccluded1(embree_->scene, &context, &r);
  return r.tfar < 0.f;  // Embree sets tfar to -inf on a hit
}

}  // namespace fb
