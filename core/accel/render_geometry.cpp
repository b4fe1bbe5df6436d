#include "core/accel/render_geometry.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

#include "core/accel/embree_solids.h"
#include "core/math/random.h"
#include "core/util/error.h"

namespace fb {

struct RenderGeometry::Mesh {
  // Each motion step's vertices in turn, then one extra element: Embree reads 16 bytes past the
  // last vertex.
  std::vector<Vec3f> positions;
  std::vector<Vec3f> normals;   // none, or each motion step's in turn
  VertexTextureData texturing;  // tangents in render space at the first motion step
  std::vector<uint32_t> indices;
  uint32_t material = 0;
  const SurfaceShader* shader = nullptr;  // set when the material has alpha: for the filter
  uint32_t first_emitter = FB_NONE;
  uint32_t step_count = 1;  // evenly spaced over the open shutter when more than one
  size_t vertex_count = 0;  // per step
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

// RenderGeometry::live_bytes(): Embree reports each allocation (bytes > 0) before it is made and
// each release (bytes < 0) after, from whichever thread builds.
std::atomic<int64_t> live_bytes_total{0};

bool count_embree_bytes(void*, ssize_t bytes, bool) {
  live_bytes_total.fetch_add(bytes, std::memory_order_relaxed);
  return true;
}

template <typename T>
size_t bytes_of(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
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

RTCRay to_embree(const fb_ray& ray, float time) {
  RTCRay r;
  r.org_x = ray.origin[0], r.org_y = ray.origin[1], r.org_z = ray.origin[2];
  r.dir_x = ray.direction[0], r.dir_y = ray.direction[1], r.dir_z = ray.direction[2];
  r.tnear = ray.t_min;
  r.tfar = ray.t_max;
  r.time = time;
  r.mask = 0xffffffffu;
  r.id = 0;
  r.flags = 0;
  return r;
}

RTCRayHit to_embree_hit(const fb_ray& ray, float time) {
  RTCRayHit rh;
  rh.ray = to_embree(ray, time);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// Embree's split of a normalised time into a motion segment and the fraction within it
// (getTimeSegment in Embree 3's common/math), repeated so hits are rebuilt where Embree found them.
uint32_t time_segment(float time, uint32_t segments, float& fraction) {
  const float scaled = time * float(segments);
  const float segment = std::clamp(std::floor(scaled), 0.f, float(segments) - 1.f);
  fraction = scaled - segment;
  return uint32_t(segment);
}

// Corners of the object-space bounding box: an affine map's error against linear interpolation is
// affine in the point, so its largest norm over the mesh is at one of them.
std::vector<Vec3d> box_corners(const std::vector<Vec3f>& positions) {
  Bounds3d box;
  for (const Vec3f& p : positions)
    box.extend(Vec3d(p));
  std::vector<Vec3d> corners;
  for (int i = 0; i < 8; ++i)
    corners.push_back(
        {i & 1 ? box.hi.x : box.lo.x, i & 2 ? box.hi.y : box.lo.y, i & 4 ? box.hi.z : box.lo.z});
  return corners;
}

// render_from_object at 2^n + 1 evenly spaced times over the open shutter, the fewest (n = 0, 1,
// ...) for which linear interpolation between consecutive steps follows the true motion within
// the tolerance at a quarter, half and three quarters of every step, up to Embree's 129 steps.
std::vector<Transform> motion_steps(const Scene& scene, const MeshInstance& instance,
                                    const Transform& render_from_world, const ShotTimes& times,
                                    const MotionTolerance& tolerance) {
  const auto at = [&](double s) {
    return render_from_world *
           scene.world_from_object(instance, times.open_s + s * (times.close_s - times.open_s));
  };
  const std::vector<Vec3d> corners = box_corners(scene.meshes[instance.mesh].positions);
  for (uint32_t segments = 1;; segments *= 2) {
    std::vector<Transform> steps;
    for (uint32_t k = 0; k <= segments; ++k)
      steps.push_back(at(double(k) / segments));
    bool follows = true;
    for (uint32_t k = 0; k < segments && follows; ++k)
      for (double f : {0.25, 0.5, 0.75}) {
        const Transform exact = at((k + f) / segments);
        for (const Vec3d& c : corners) {
          const Vec3d e = exact.point(c);
          const Vec3d lerp = steps[k].point(c) * (1 - f) + steps[k + 1].point(c) * f;
          follows &= length(e - lerp) <= tolerance.absolute_m + tolerance.per_metre * length(e);
        }
      }
    if (follows || segments + 1 >= RTC_MAX_TIME_STEP_COUNT) return steps;
  }
}

// What bounds the unbounded solids (half-spaces) for Embree, which needs finite boxes: a cube about
// the camera reaching twice as far as any bounded geometry, and at least 1000 km. Rays start
// within it, so Embree always offers them the half-space, which thus acts as unbounded; Embree's
// limit of 1e18 m stays far away.
Bounds3d solid_reach(const Bounds3d& bounded) {
  double reach = 1e6;
  if (!bounded.empty())
    reach = std::max(reach, 2 * max_component(max(abs(bounded.lo), abs(bounded.hi))));
  reach = std::min(reach, 1e17);
  return {{-reach, -reach, -reach}, {reach, reach, reach}};
}

}  // namespace

RenderGeometry::Mesh RenderGeometry::build_mesh(
    const Scene& scene, const MeshInstance& instance,
    const std::vector<Transform>& render_from_object_steps) {
  const TriangleMesh& source = scene.meshes[instance.mesh];
  Mesh mesh;
  mesh.material = source.material;
  mesh.step_count = uint32_t(render_from_object_steps.size());
  mesh.vertex_count = source.positions.size();
  mesh.positions.reserve(source.positions.size() * mesh.step_count + 1);
  for (const Transform& render_from_object : render_from_object_steps) {
    for (const Vec3f& p : source.positions) {
      const Vec3d q = render_from_object.point(Vec3d(p));
      if (!(max_component(abs(q)) <= kLargestCoordinate))
        throw InputError("instance '" + instance.node + "' of mesh '" + source.name +
                         "': a vertex lies beyond 1e18 m of the camera (scales multiply too far)");
      bounds_.extend(q);
      mesh.positions.emplace_back(q);
    }
    const Transform normal_transform = render_from_object.normal_transform();
    for (const Vec3f& n : source.normals) {
      const Vec3d m = normal_transform.vector(Vec3d(n));
      const double len = length(m);
      mesh.normals.emplace_back(len > 0 ? m / len : Vec3d{});
    }
  }
  mesh.positions.emplace_back();
  mesh.texturing.texcoords = source.texturing.texcoords;
  const Transform& first = render_from_object_steps.front();
  for (const auto& t : source.texturing.tangents) {
    const Vec3d m = first.vector(Vec3d{t[0], t[1], t[2]});
    const double len = length(m);
    const Vec3f u(len > 0 ? m / len : Vec3d{});
    mesh.texturing.tangents.push_back({u.x, u.y, u.z, t[3]});
  }
  const Transform normal_from_object = first.normal_transform();  // Cycles: a normal's transform
  for (const Vec3f& t : source.texturing.radial_tangents)
    mesh.texturing.radial_tangents.emplace_back(normal_from_object.vector(Vec3d(t)));
  mesh.indices = source.indices;
  // A mirroring transform turns counter-clockwise into clockwise: swap two corners so the
  // winding (and with it the front face) survives, as glTF requires.
  if (render_from_object_steps.front().determinant3x3() < 0)
    for (size_t i = 0; i < mesh.indices.size(); i += 3)
      std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
  return mesh;
}

RenderGeometry::RenderGeometry(const Scene& scene, const Transform& render_from_world,
                               const ShotTimes& times, const MotionTolerance& tolerance)
    : shader_(std::make_unique<SurfaceShader>(scene, render_from_world.inverse())),
      embree_(std::make_unique<Embree>()) {
  open_embree();
  meshes_.reserve(scene.instances.size());  // alpha filters keep pointers to their mesh
  if (times.shutter_open()) {
    open_s_ = float(times.open_s - times.frame_s);
    inverse_duration_ = float(1 / (times.close_s - times.open_s));
  }
  for (const MeshInstance& instance : scene.instances) {
    if (scene.meshes[instance.mesh].indices.empty()) continue;
    const bool moving =
        times.shutter_open() && scene.moves(instance.node_index, times.open_s, times.close_s);
    Mesh mesh = build_mesh(
        scene, instance,
        moving
            ? motion_steps(scene, instance, render_from_world, times, tolerance)
            : std::vector{render_from_world * scene.world_from_object(instance, times.still_s())});
    moving_instances_ += moving;
    most_motion_steps_ = std::max(most_motion_steps_, mesh.step_count);
    if (max_component(scene.materials[mesh.material].emission) > 0.f) add_emitters(mesh, moving);
    attach_mesh(std::move(mesh));
  }
  attach_solids(scene, render_from_world);
  rtcCommitScene(embree_->scene);
  if (!embree_->error.empty())
    throw InputError("Embree could not build the scene: " + embree_->error);
  if (!bounds_.empty()) {
    centre_ = Vec3f((bounds_.lo + bounds_.hi) * 0.5);
    radius_ = static_cast<float>(length(bounds_.hi - bounds_.lo) * 0.5);
  }
  own_bytes_ = count_own_bytes();
  live_bytes_total.fetch_add(int64_t(own_bytes_), std::memory_order_relaxed);
}

void RenderGeometry::open_embree() {
  embree_->device = rtcNewDevice(nullptr);
  if (!embree_->device) throw InputError("cannot create an Embree device");
  rtcSetDeviceErrorFunction(embree_->device, record_embree_error, &embree_->error);
  rtcSetDeviceMemoryMonitorFunction(embree_->device, count_embree_bytes, nullptr);
  embree_->scene = rtcNewScene(embree_->device);
  // Watertight triangle tests: no ray slips between two triangles of a closed mesh (light leaks
  // into closed rooms), and single rays and packets agree on every hit.
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
}

// Each triangle of an emissive mesh, at its first motion step, as the mesh meshes_.size() will be.
void RenderGeometry::add_emitters(Mesh& mesh, bool moving) {
  mesh.first_emitter = static_cast<uint32_t>(emitters_.size());
  for (size_t i = 0; i < mesh.indices.size(); i += 3) {
    EmissiveTriangle e{mesh.positions[mesh.indices[i]],
                       mesh.positions[mesh.indices[i + 1]],
                       mesh.positions[mesh.indices[i + 2]],
                       {},
                       0.f,
                       mesh.material,
                       uint32_t(meshes_.size()),
                       uint32_t(i / 3),
                       moving};
    const Vec3f c = cross(e.p1 - e.p0, e.p2 - e.p0);
    e.area = 0.5f * length(c);
    e.normal = e.area > 0.f ? c / (2.f * e.area) : Vec3f{0, 0, 1};
    emitters_.push_back(e);  // zero-area ones stay, so indices match primitive IDs
  }
}

// The mesh as Embree triangle geometry sharing its buffers (one vertex buffer per motion step),
// with the alpha filter when its material has alpha; its Embree ID is its index in meshes_.
void RenderGeometry::attach_mesh(Mesh mesh) {
  RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryTimeStepCount(geometry, mesh.step_count);
  for (uint32_t k = 0; k < mesh.step_count; ++k)
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, k, RTC_FORMAT_FLOAT3,
                               mesh.positions.data() + k * mesh.vertex_count, 0, sizeof(Vec3f),
                               mesh.vertex_count);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                             mesh.indices.data(), 0, 3 * sizeof(uint32_t), mesh.indices.size() / 3);
  if (shader_->has_alpha(mesh.material)) {
    mesh.shader = shader_.get();
    // The slot the mesh is moved into below; meshes_ never reallocates (reserved).
    rtcSetGeometryUserData(geometry, meshes_.data() + meshes_.size());
    rtcSetGeometryIntersectFilterFunction(geometry, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(geometry, alpha_filter);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(embree_->scene, geometry, static_cast<unsigned>(meshes_.size()));
  rtcReleaseGeometry(geometry);
  triangle_count_ += mesh.indices.size() / 3;
  meshes_.push_back(
      std::move(mesh));  // vector storage moves with it: the shared pointers stay valid
}

// The analytic solids as Embree user geometry, after the meshes; the unbounded ones reach as far
// as solid_reach says.
void RenderGeometry::attach_solids(const Scene& scene, const Transform& render_from_world) {
  Bounds3d bounded = bounds_;
  for (const Solid& solid : scene.solids) {
    const Bounds3d b = solid_bounds(solid, render_from_world);
    if (b.finite()) bounded.extend(b);
  }
  const Bounds3d reach = solid_reach(bounded);
  solids_.reserve(scene.solids.size());  // Embree keeps pointers to them
  embree_solids_.reserve(scene.solids.size());
  for (const Solid& solid : scene.solids) {
    const RenderSolid& added = solids_.emplace_back(solid, render_from_world, reach);
    const EmbreeSolid& attached = embree_solids_.emplace_back(EmbreeSolid{&added, shader_.get()});
    if (added.bounds().empty()) continue;
    if (added.bounded()) bounds_.extend(added.bounds());
    attach_solid(embree_->device, embree_->scene, attached,
                 unsigned(meshes_.size() + solids_.size() - 1));
  }
}

size_t RenderGeometry::count_own_bytes() const {
  size_t bytes = bytes_of(meshes_) + bytes_of(emitters_);
  for (const Mesh& mesh : meshes_) {
    bytes += bytes_of(mesh.positions) + bytes_of(mesh.normals) + bytes_of(mesh.indices) +
             bytes_of(mesh.texturing.tangents) + bytes_of(mesh.texturing.radial_tangents);
    for (const auto& texcoords : mesh.texturing.texcoords)
      bytes += bytes_of(texcoords);
  }
  return bytes;
}

RenderGeometry::~RenderGeometry() {
  live_bytes_total.fetch_sub(int64_t(own_bytes_), std::memory_order_relaxed);
}

size_t RenderGeometry::live_bytes() {
  return size_t(std::max<int64_t>(live_bytes_total.load(std::memory_order_relaxed), 0));
}

float RenderGeometry::embree_time(float time_s) const {
  const float t = (time_s - open_s_) * inverse_duration_;
  return t >= 0.f ? std::min(t, 1.f) : 0.f;  // NaN too: Embree wants a time in [0, 1]
}

bool RenderGeometry::intersect(const fb_ray& ray, fb_hit& hit, SurfaceArena* arena,
                               const FootprintSource& footprint) const {
  if (!traceable(ray)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const float time = embree_time(ray.time_s);
  RTCRayHit rh = to_embree_hit(ray, time);
  rtcIntersect1(embree_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  const HitRequest request{ray, arena, false, footprint};
  if (rh.hit.geomID >= meshes_.size()) return fill_solid_hit(rh.hit.geomID, request, hit);
  fill_hit(meshes_[rh.hit.geomID], rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, time, request,
           hit);
  return true;
}

void RenderGeometry::intersect_coherent(const fb_ray* rays, size_t count, fb_hit* hits,
                                        SurfaceArena* arena,
                                        const FootprintSource& footprints) const {
  thread_local std::vector<RTCRayHit> stream;
  stream.resize(count);
  for (size_t i = 0; i < count; ++i)
    stream[i] = to_embree_hit(rays[i], embree_time(rays[i].time_s));
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // Embree packs the stream into packets
  rtcIntersect1M(embree_->scene, &context, stream.data(), unsigned(count), sizeof(RTCRayHit));
  for (size_t i = 0; i < count; ++i) {
    const RTCRayHit& rh = stream[i];
    const HitRequest request{rays[i], arena, true, footprints.at(i)};
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      hits[i].t = HUGE_VALF;
    else if (rh.hit.geomID >= meshes_.size()) {
      if (!fill_solid_hit(rh.hit.geomID, request, hits[i])) hits[i].t = HUGE_VALF;
    } else
      fill_hit(meshes_[rh.hit.geomID], rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, rh.ray.time,
               request, hits[i]);
  }
}

SurfacePoint RenderGeometry::surface_point(const Mesh& mesh, uint32_t primitive, float u, float v) {
  const uint32_t* tri = &mesh.indices[3 * size_t(primitive)];
  const float b[3] = {1.f - u - v, u, v};
  SurfacePoint point;
  // At the first motion step: solid textures on moving meshes are not supported (only POV-Ray
  // scenes have them, and nothing moves there). From the first corner along the edges, so that a
  // coordinate all three corners share comes out exact: a plane at y = -1 tessellated from a
  // POV-Ray scene must give its checker y = -1, not -1 - 1 ulp (the barycentric sum rounds).
  const Vec3f p0 = mesh.positions[tri[0]];
  point.position = p0 + (mesh.positions[tri[1]] - p0) * u + (mesh.positions[tri[2]] - p0) * v;
  const VertexTextureData& data = mesh.texturing;
  for (uint32_t set = 0; set < VertexTextureData::kSets && !data.texcoords[set].empty(); ++set) {
    const std::vector<Vec2f>& uv = data.texcoords[set];
    point.uv[set] = uv[tri[0]] * b[0] + uv[tri[1]] * b[1] + uv[tri[2]] * b[2];
    point.uv_sets = set + 1;
  }
  if (!data.tangents.empty()) {
    Vec3f t{};
    for (int i = 0; i < 3; ++i) {
      const auto& c = data.tangents[tri[i]];
      t += Vec3f{c[0], c[1], c[2]} * b[i];
    }
    point.tangent = t;
    point.bitangent_sign = data.tangents[tri[0]][3] < 0.f ? -1.f : 1.f;
  }
  if (!data.radial_tangents.empty())
    point.radial_tangent = data.radial_tangents[tri[0]] * b[0] +
                           data.radial_tangents[tri[1]] * b[1] +
                           data.radial_tangents[tri[2]] * b[2];
  return point;
}

// Embree's filter for materials with alpha: SurfaceShader::covers decides, from a hash of the
// primitive, the hit's barycentrics and the ray's direction.
void RenderGeometry::alpha_filter(const RTCFilterFunctionNArguments* args) {
  const Mesh& mesh = *static_cast<const Mesh*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t primitive = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    const auto bits = [](float f) { return uint64_t(std::bit_cast<uint32_t>(f)); };
    const uint64_t hash = pcg_hash(uint64_t(primitive) << 32 | bits(u),
                                   bits(v) << 32 | bits(RTCRayN_dir_x(args->ray, args->N, i)),
                                   bits(RTCRayN_dir_y(args->ray, args->N, i)) << 32 |
                                       bits(RTCRayN_dir_z(args->ray, args->N, i)));
    if (!mesh.shader->covers(mesh.material, surface_point(mesh, primitive, u, v), hash))
      args->valid[i] = 0;
  }
}

Rgb RenderGeometry::emission_at(const EmissiveTriangle& emitter, float u, float v) const {
  return shader_->emission(emitter.material,
                           surface_point(meshes_[emitter.mesh], emitter.primitive, u, v));
}

namespace {

// Where shadow rays leave a triangle with vertex normals (Hanika 2021, "Hacking the Shadow
// Terminator", Ray Tracing Gems II ch. 4): the point moved onto each corner's tangent plane (of its
// vertex normal) where it lies below that plane, weighted by the barycentrics,
// P' = P - sum_i b_i min(0, (P - p_i).n_i) n_i. A convex triangle rises towards the smooth surface
// its normals describe; a flat or concave one stays. In double, so that the lift, far smaller than
// P, adds no rounding of P's magnitude: P' is rounded once, to float.
Vec3f lifted_onto_smooth_surface(Vec3f position, const Vec3f p[3], const Vec3f n[3],
                                 const float b[3]) {
  const Vec3d from(position);
  Vec3d lifted = from;
  for (int i = 0; i < 3; ++i) {
    const Vec3d normal(n[i]);
    const double len = length(normal);
    if (!(len > 0)) continue;
    const Vec3d unit = normal * (1 / len);
    lifted = lifted - unit * (double(b[i]) * std::min(0.0, dot(from - Vec3d(p[i]), unit)));
  }
  return Vec3f(lifted);
}

}  // namespace

void RenderGeometry::fill_hit(const Mesh& mesh, uint32_t primitive, float u, float v, float t,
                              float time, const HitRequest& request, fb_hit& hit) const {
  const uint32_t* tri = &mesh.indices[3 * size_t(primitive)];
  const float b[3] = {1.f - u - v, u, v};
  // The corners where Embree met them: at a motion step, or interpolated between two as Embree
  // does (lerp of the steps around the ray's time). Each corner's magnitude bounds its rounding.
  Vec3f p[3], magnitude[3], n[3];
  const bool moving = mesh.step_count > 1;
  float f = 0.f;
  const size_t first = moving ? time_segment(time, mesh.step_count - 1, f) * mesh.vertex_count : 0;
  const size_t next = moving ? first + mesh.vertex_count : 0;
  for (int i = 0; i < 3; ++i) {
    const Vec3f a = mesh.positions[first + tri[i]];
    if (!moving) {
      p[i] = a, magnitude[i] = abs(a);
      if (!mesh.normals.empty()) n[i] = mesh.normals[tri[i]];
      continue;
    }
    const Vec3f c = mesh.positions[next + tri[i]];
    p[i] = a * (1.f - f) + c * f;
    magnitude[i] = abs(a) + abs(c);
    if (!mesh.normals.empty())
      n[i] = mesh.normals[first + tri[i]] * (1.f - f) + mesh.normals[next + tri[i]] * f;
  }
  // Re-interpolating from the vertices puts the point on the triangle's plane up to rounding,
  // bounded by gamma(7) times the magnitudes summed (pbrt 4e §6.8.4); between motion steps, our
  // corners and Embree's each round a lerp too: gamma(7) more.
  const Vec3f position = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
  const Vec3f shadow =
      mesh.normals.empty() ? position : lifted_onto_smooth_surface(position, p, n, b);
  // The lifted point carries the position's error and one rounding more: one bound for both.
  const Vec3f error = (magnitude[0] * std::abs(b[0]) + magnitude[1] * std::abs(b[1]) +
                       magnitude[2] * std::abs(b[2])) *
                          gamma(moving ? 14 : 7) +
                      abs(shadow) * gamma(1);
  const Vec3f ng = normalize(cross(p[1] - p[0], p[2] - p[0]));
  Vec3f ns = ng;
  if (!mesh.normals.empty()) {
    const Vec3f interpolated = n[0] * b[0] + n[1] * b[1] + n[2] * b[2];
    const float len = length(interpolated);
    if (len > 0.f) ns = interpolated / len;
    if (dot(ns, ng) < 0.f) ns = -ns;
  }
  hit.t = t;
  position.store(hit.position);
  shadow.store(hit.shadow_position);
  error.store(hit.position_error);
  ng.store(hit.geometric_normal);
  ns.store(hit.shading_normal);
  hit.material = mesh.material;
  hit.emitter = mesh.first_emitter == FB_NONE ? FB_NONE : mesh.first_emitter + primitive;
  SurfacePoint point = surface_point(mesh, primitive, u, v);
  Vec3f dp_dx, dp_dy;
  if (point.uv_sets > 0 &&
      position_differentials(request.footprint, Vec3f(request.ray.origin),
                             Vec3f(request.ray.direction), position, ng, dp_dx, dp_dy))
    set_texture_differentials(p, tri, mesh.texturing, dp_dx, dp_dy, point);
  shade(mesh.material, point, request, hit);
}

bool RenderGeometry::fill_solid_hit(unsigned id, const HitRequest& request, fb_hit& hit) const {
  const fb_ray& ray = request.ray;
  const auto found =
      first_covered_hit(embree_solids_[id - meshes_.size()], Vec3d(Vec3f(ray.origin)),
                        Vec3d(Vec3f(ray.direction)), ray.t_min);
  if (!found) return false;  // cannot happen: Embree's hit came from the same computation
  hit.t = float(found->t);
  Vec3f(found->position).store(hit.position);
  Vec3f(found->position).store(hit.shadow_position);  // exact surfaces need no lift
  Vec3f(found->position_error).store(hit.position_error);
  Vec3f(found->normal).store(hit.geometric_normal);
  Vec3f(found->normal).store(hit.shading_normal);
  hit.material = found->material;
  hit.emitter = FB_NONE;
  SurfacePoint point;
  point.position = Vec3f(found->position);  // for solid textures (SurfacePoint::position)
  shade(found->material, point, request, hit);
  return true;
}

void RenderGeometry::shade(uint32_t material, const SurfacePoint& point, const HitRequest& request,
                           fb_hit& hit) const {
  if (!request.arena) {
    shader_->shade(material, point, hit);
    hit.surface = nullptr;
    return;
  }
  Surface& surface = request.camera ? request.arena->batch_next() : request.arena->ring_next();
  shader_->shade(material, point, Vec3f(request.ray.direction), request.camera, hit, surface);
  hit.surface = reinterpret_cast<const fb_surface*>(&surface);
}

bool RenderGeometry::occluded(const fb_ray& ray) const {
  if (!traceable(ray)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = to_embree(ray, embree_time(ray.time_s));
  rtcOccluded1(embree_->scene, &context, &r);
  return r.tfar < 0.f;  // Embree sets tfar to -inf on a hit
}

}  // namespace fb
