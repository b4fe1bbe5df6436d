#include "core/accel/render_geometry.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <string>

#include "core/accel/deformation_steps.h"
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
  uint32_t object = 0;                    // RenderGeometry::SurfaceIdentity's
  const SurfaceShader* shader = nullptr;  // set when the material has alpha: for the filter
  uint32_t first_emitter = FB_NONE;
  uint32_t step_count = 1;  // evenly spaced over the open shutter when more than one
  size_t vertex_count = 0;  // per step
  bool mirrored = false;    // placed by a mirroring transform: each triangle's corners 1, 2 swapped
};

// One placement of an instanced mesh (a prototype): render_from_object at each motion step, as a
// flattened copy would be transformed, and the normals' transforms with them.
struct RenderGeometry::Instance {
  uint32_t prototype = 0;
  uint32_t object = 0;                        // RenderGeometry::SurfaceIdentity's
  std::vector<Transform> render_from_object;  // evenly spaced over the open shutter when several
  std::vector<Transform> normal_from_object;
  // A mirroring transform: corners 1 and 2 swap (and Embree's u and v with them), as a flattened
  // copy swaps its indices, so the front face and the barycentrics come out the same.
  bool mirrored = false;
};

// A triangle as a hit rebuilds it, in render space: corners in front-face order, at the ray's time
// (`p`, with the magnitudes that bound their rounding, and vertex normals `n`) and at the first
// motion step (`rest`, where textures are evaluated).
struct RenderGeometry::HitTriangle {
  const Mesh* mesh = nullptr;          // texture coordinates, material, emitters
  const Instance* instance = nullptr;  // null when flattened: the mesh is in render space
  uint32_t primitive = 0;
  uint32_t corner[3] = {};  // vertex indices in `mesh`
  Vec3f p[3], magnitude[3], n[3], rest[3];
  bool moving = false;
  // Instanced: how far Embree's float transform of the ray may move the surface it meets from
  // these corners (fill_hit adds it to the position's error).
  Vec3f transform_magnitude;
};

struct RenderGeometry::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<RTCScene> prototypes;  // one per RenderGeometry::prototypes_ element
  std::string error;
  ~Embree() {
    if (scene) rtcReleaseScene(scene);
    for (RTCScene prototype : prototypes)
      rtcReleaseScene(prototype);
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

// |A| |p| + |t| per row for the affine map x -> A x + t: what bounds the rounding of its image of p
// (pbrt 4e §6.8.6, transforming points).
Vec3d transform_magnitude(const Transform& m, Vec3d p) {
  const auto row = [&](int r) {
    return std::abs(m(r, 0) * p.x) + std::abs(m(r, 1) * p.y) + std::abs(m(r, 2) * p.z) +
           std::abs(m(r, 3));
  };
  return {row(0), row(1), row(2)};
}

// A unit normal (or tangent) through `transform`; zero when it degenerates.
Vec3f unit_through(const Transform& transform, Vec3d v) {
  const Vec3d m = transform.vector(v);
  const double len = length(m);
  return Vec3f(len > 0 ? m / len : Vec3d{});
}

// Embree (Debian builds keep its assertions) aborts the process on a ray with a NaN or a component
// beyond FLT_LARGE (1.8e18); plugins must not be able to do that, so such rays are misses.
constexpr double kLargestCoordinate = 1e18;

// A vertex of a mesh placed by render_from_object, refused beyond Embree's reach.
Vec3d placed(const Transform& render_from_object, Vec3f p, const MeshInstance& instance,
             const TriangleMesh& source) {
  const Vec3d q = render_from_object.point(Vec3d(p));
  if (!(max_component(abs(q)) <= kLargestCoordinate))
    throw InputError("instance '" + instance.node + "' of mesh '" + source.name +
                     "': a vertex lies beyond 1e18 m of the camera (scales multiply too far)");
  return q;
}

// The instance's index in the scene, as SurfaceIdentity names it.
uint32_t scene_object_index(const Scene& scene, const MeshInstance& instance) {
  return uint32_t(&instance - scene.instances.data());
}

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
                                    const std::vector<Vec3d>& corners,
                                    const Transform& render_from_world, const ShotTimes& times,
                                    const MotionTolerance& tolerance) {
  const auto at = [&](double s) {
    return render_from_world *
           scene.world_from_object(instance, times.open_s + s * (times.close_s - times.open_s));
  };
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
    const MeshInstance& instance, const std::vector<Transform>& render_from_object_steps,
    const TriangleMesh& source, const std::vector<DeformedShape>& shapes) {
  Mesh mesh;
  mesh.material = source.material;
  mesh.step_count = uint32_t(render_from_object_steps.size());
  mesh.vertex_count = shapes.empty() ? source.positions.size() : shapes.front().positions.size();
  mesh.positions.reserve(mesh.vertex_count * mesh.step_count + 1);
  for (size_t k = 0; k < render_from_object_steps.size(); ++k) {
    const Transform& render_from_object = render_from_object_steps[k];
    const std::vector<Vec3f>& positions = shapes.empty() ? source.positions : shapes[k].positions;
    for (const Vec3f& p : positions) {
      const Vec3d q = placed(render_from_object, p, instance, source);
      bounds_.extend(q);
      mesh.positions.emplace_back(q);
    }
    const Transform normal_transform = render_from_object.normal_transform();
    const bool own_normals = !shapes.empty() && !shapes[k].normals.empty();
    for (const Vec3f& n : own_normals ? shapes[k].normals : source.normals)
      mesh.normals.push_back(unit_through(normal_transform, Vec3d(n)));
  }
  mesh.positions.emplace_back();
  mesh.texturing.texcoords = source.texturing.texcoords;
  const Transform& first = render_from_object_steps.front();
  for (const auto& t : source.texturing.tangents) {
    const Vec3f u = unit_through(first, Vec3d{t[0], t[1], t[2]});
    mesh.texturing.tangents.push_back({u.x, u.y, u.z, t[3]});
  }
  const Transform normal_from_object = first.normal_transform();  // Cycles: a normal's transform
  for (const Vec3f& t : source.texturing.radial_tangents)
    mesh.texturing.radial_tangents.emplace_back(normal_from_object.vector(Vec3d(t)));
  mesh.indices = source.indices;
  // A mirroring transform turns counter-clockwise into clockwise: swap two corners so the
  // winding (and with it the front face) survives, as glTF requires.
  mesh.mirrored = render_from_object_steps.front().determinant3x3() < 0;
  if (mesh.mirrored)
    for (size_t i = 0; i < mesh.indices.size(); i += 3)
      std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
  return mesh;
}

RenderGeometry::RenderGeometry(const Scene& scene, const Transform& render_from_world,
                               const ShotTimes& times, const MotionTolerance& tolerance,
                               Instancing instancing)
    : shader_(std::make_unique<SurfaceShader>(scene, render_from_world.inverse())),
      embree_(std::make_unique<Embree>()) {
  open_embree();
  const std::vector<bool> instanced = instanced_meshes(scene, instancing);
  // Alpha filters keep pointers to their mesh: neither vector may reallocate.
  meshes_.reserve(scene.instances.size());
  prototypes_.reserve(scene.meshes.size());
  prototype_of_mesh_.assign(scene.meshes.size(), FB_NONE);
  // Each mesh's object-space box corners, found at its first use: 10,000 instances of one mesh
  // must not scan its vertices 10,000 times.
  std::vector<std::vector<Vec3d>> corners(scene.meshes.size());
  const auto corners_of = [&](uint32_t mesh) -> const std::vector<Vec3d>& {
    if (corners[mesh].empty()) corners[mesh] = box_corners(scene.meshes[mesh].positions);
    return corners[mesh];
  };
  if (times.shutter_open()) {
    open_s_ = float(times.open_s - times.frame_s);
    inverse_duration_ = float(1 / (times.close_s - times.open_s));
  }
  std::vector<const MeshDeformation*> deformation_of(scene.meshes.size(), nullptr);
  for (const MeshDeformation& d : scene.deformations)
    deformation_of[d.mesh] = &d;
  for (const MeshInstance& instance : scene.instances) {
    if (scene.meshes[instance.mesh].indices.empty()) continue;
    if (const MeshDeformation* deformation = deformation_of[instance.mesh]) {
      add_deformed_mesh(scene, instance, *deformation, render_from_world, times, tolerance);
      continue;
    }
    const bool moving =
        times.shutter_open() && scene.moves(instance.node_index, times.open_s, times.close_s);
    std::vector<Transform> steps =
        moving
            ? motion_steps(scene, instance, corners_of(instance.mesh), render_from_world, times,
                           tolerance)
            : std::vector{render_from_world * scene.world_from_object(instance, times.still_s())};
    moving_instances_ += moving;
    most_motion_steps_ = std::max(most_motion_steps_, uint32_t(steps.size()));
    if (instanced[instance.mesh]) {
      add_instance(scene, instance, corners_of(instance.mesh), std::move(steps));
      continue;
    }
    Mesh mesh = build_mesh(instance, steps, scene.meshes[instance.mesh]);
    mesh.object = scene_object_index(scene, instance);
    if (max_component(scene.materials[mesh.material].emission) > 0.f) add_emitters(mesh, moving);
    attach_mesh(std::move(mesh));
  }
  object_count_ = uint32_t(scene.instances.size());
  attach_solids(scene, render_from_world);
  attach_instances();
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

// Posed at deformation_steps' times (core/accel/deformation_steps.h; a still mesh builds no
// motion data). Each step keeps only its positions and normals; a skinned or morphed mesh's first
// pose gives the rest.
void RenderGeometry::add_deformed_mesh(const Scene& scene, const MeshInstance& instance,
                                       const MeshDeformation& deformation,
                                       const Transform& render_from_world, const ShotTimes& times,
                                       const MotionTolerance& tolerance) {
  DeformationSteps steps =
      deformation_steps(scene, instance, deformation, render_from_world, times, tolerance);
  const bool moving = steps.times_s.size() > 1;
  moving_instances_ += moving;
  most_motion_steps_ = std::max(most_motion_steps_, uint32_t(steps.times_s.size()));
  const bool evaluated = !deformation.evaluated.empty();
  Mesh mesh =
      build_mesh(instance, steps.render_from_object,
                 evaluated ? scene.meshes[deformation.mesh] : steps.first_pose, steps.shapes);
  mesh.object = scene_object_index(scene, instance);
  if (max_component(scene.materials[mesh.material].emission) > 0.f) add_emitters(mesh, moving);
  attach_mesh(std::move(mesh));
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

uint32_t RenderGeometry::prototype_of(const Scene& scene, uint32_t mesh_index) {
  if (prototype_of_mesh_[mesh_index] != FB_NONE) return prototype_of_mesh_[mesh_index];
  const TriangleMesh& source = scene.meshes[mesh_index];
  Mesh& mesh = prototypes_.emplace_back();
  mesh.material = source.material;
  mesh.vertex_count = source.positions.size();
  mesh.positions.reserve(source.positions.size() + 1);  // Embree reads 16 bytes past the last
  mesh.positions.assign(source.positions.begin(), source.positions.end());
  mesh.positions.emplace_back();
  mesh.normals = source.normals;
  mesh.texturing = source.texturing;
  mesh.indices = source.indices;
  RTCScene prototype = embree_->prototypes.emplace_back(rtcNewScene(embree_->device));
  rtcSetSceneFlags(prototype, RTC_SCENE_FLAG_ROBUST);  // as the top-level scene: watertight
  RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                             mesh.positions.data(), 0, sizeof(Vec3f), mesh.vertex_count);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                             mesh.indices.data(), 0, 3 * sizeof(uint32_t), mesh.indices.size() / 3);
  if (shader_->has_alpha(mesh.material)) {
    // Coverage is decided in object space (its hash from Embree's object-space ray): as random,
    // though not the same draws as a flattened copy's.
    mesh.shader = shader_.get();
    rtcSetGeometryUserData(geometry, &mesh);
    rtcSetGeometryIntersectFilterFunction(geometry, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(geometry, alpha_filter);
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometryByID(prototype, geometry, 0);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(prototype);
  return prototype_of_mesh_[mesh_index] = uint32_t(prototypes_.size() - 1);
}

// An instance of its mesh's prototype; its bounds are those of the mesh's box at every step (the
// box's corners placed, rather than every vertex: 10,000 copies of a large mesh would cost as
// much to bound as to flatten).
void RenderGeometry::add_instance(const Scene& scene, const MeshInstance& placement,
                                  const std::vector<Vec3d>& corners,
                                  std::vector<Transform> render_from_object_steps) {
  const TriangleMesh& source = scene.meshes[placement.mesh];
  Instance& instance = instances_.emplace_back();
  instance.prototype = prototype_of(scene, placement.mesh);
  instance.object = scene_object_index(scene, placement);
  instance.mirrored = render_from_object_steps.front().determinant3x3() < 0;
  for (const Transform& render_from_object : render_from_object_steps) {
    for (const Vec3d& c : corners)
      bounds_.extend(placed(render_from_object, Vec3f(c), placement, source));
    instance.normal_from_object.push_back(render_from_object.normal_transform());
  }
  instance.render_from_object = std::move(render_from_object_steps);
  triangle_count_ += source.triangle_count();
}

// The instances as Embree instance geometry, after the solids, each transform at each motion step
// (Embree interpolates the matrices linearly, as a flattened copy's vertices are).
void RenderGeometry::attach_instances() {
  const size_t first_id = meshes_.size() + solids_.size();
  for (size_t k = 0; k < instances_.size(); ++k) {
    const Instance& instance = instances_[k];
    RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geometry, embree_->prototypes[instance.prototype]);
    rtcSetGeometryTimeStepCount(geometry, unsigned(instance.render_from_object.size()));
    for (size_t step = 0; step < instance.render_from_object.size(); ++step) {
      float row_major[12];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
          row_major[4 * r + c] = float(instance.render_from_object[step](r, c));
      rtcSetGeometryTransform(geometry, unsigned(step), RTC_FORMAT_FLOAT3X4_ROW_MAJOR, row_major);
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(embree_->scene, geometry, unsigned(first_id + k));
    rtcReleaseGeometry(geometry);
  }
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
  size_t bytes = bytes_of(meshes_) + bytes_of(emitters_) + bytes_of(prototypes_) +
                 bytes_of(prototype_of_mesh_) + bytes_of(instances_);
  for (const auto* meshes : {&meshes_, &prototypes_})
    for (const Mesh& mesh : *meshes) {
      bytes += bytes_of(mesh.positions) + bytes_of(mesh.normals) + bytes_of(mesh.indices) +
               bytes_of(mesh.texturing.tangents) + bytes_of(mesh.texturing.radial_tangents);
      for (const auto& texcoords : mesh.texturing.texcoords)
        bytes += bytes_of(texcoords);
    }
  for (const Instance& instance : instances_)
    bytes += bytes_of(instance.render_from_object) + bytes_of(instance.normal_from_object);
  return bytes;
}

RenderGeometry::~RenderGeometry() {
  live_bytes_total.fetch_sub(int64_t(own_bytes_), std::memory_order_relaxed);
}

size_t RenderGeometry::instanced_count() const {
  return instances_.size();
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
  return fill_embree_hit(rh, {ray, arena, false, footprint}, hit);
}

std::optional<RenderGeometry::SurfaceIdentity> RenderGeometry::identify(const fb_ray& ray) const {
  if (!traceable(ray)) return std::nullopt;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = to_embree_hit(ray, embree_time(ray.time_s));
  rtcIntersect1(embree_->scene, &context, &rh);
  const RTCHit& h = rh.hit;
  if (h.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  if (h.instID[0] != RTC_INVALID_GEOMETRY_ID) {
    const Instance& instance = instances_[h.instID[0] - meshes_.size() - solids_.size()];
    return SurfaceIdentity{instance.object,
                           prototypes_[instance.prototype].material,
                           rh.ray.tfar,
                           h.primID,
                           instance.mirrored ? h.v : h.u,
                           instance.mirrored ? h.u : h.v};
  }
  if (h.geomID < meshes_.size()) {
    // A mirrored copy swapped its corners 1 and 2 (build_mesh): so are Embree's weights.
    const Mesh& mesh = meshes_[h.geomID];
    return SurfaceIdentity{mesh.object,
                           mesh.material,
                           rh.ray.tfar,
                           h.primID,
                           mesh.mirrored ? h.v : h.u,
                           mesh.mirrored ? h.u : h.v};
  }
  // A solid's material is its primitive's: which one, only its exact intersection says.
  const unsigned solid = h.geomID - unsigned(meshes_.size());
  const auto found = first_covered_hit(embree_solids_[solid], Vec3d(Vec3f(ray.origin)),
                                       Vec3d(Vec3f(ray.direction)), ray.t_min);
  if (!found) return std::nullopt;  // cannot happen: Embree's hit came from the same computation
  return SurfaceIdentity{object_count_ + solid, found->material, float(found->t)};
}

bool RenderGeometry::fill_embree_hit(const RTCRayHit& found, const HitRequest& request,
                                     fb_hit& hit) const {
  const RTCHit& h = found.hit;
  if (h.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  if (h.instID[0] != RTC_INVALID_GEOMETRY_ID) {
    const Instance& instance = instances_[h.instID[0] - meshes_.size() - solids_.size()];
    // A mirrored instance's corners 1 and 2 are swapped: so are their barycentrics.
    const float u = instance.mirrored ? h.v : h.u, v = instance.mirrored ? h.u : h.v;
    fill_hit(instanced_triangle(instance, h.primID, found.ray.time), u, v, found.ray.tfar, request,
             hit);
    return true;
  }
  if (h.geomID >= meshes_.size()) return fill_solid_hit(h.geomID, request, hit);
  fill_hit(flat_triangle(meshes_[h.geomID], h.primID, found.ray.time), h.u, h.v, found.ray.tfar,
           request, hit);
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
  for (size_t i = 0; i < count; ++i)
    if (!fill_embree_hit(stream[i], {rays[i], arena, true, footprints.at(i)}, hits[i]))
      hits[i].t = HUGE_VALF;
}

RenderGeometry::HitTriangle RenderGeometry::flat_triangle(const Mesh& mesh, uint32_t primitive,
                                                          float time) {
  HitTriangle tri;
  tri.mesh = &mesh;
  tri.primitive = primitive;
  const uint32_t* corner = &mesh.indices[3 * size_t(primitive)];
  // The corners where Embree met them: at a motion step, or interpolated between two as Embree
  // does (lerp of the steps around the ray's time). Each corner's magnitude bounds its rounding.
  tri.moving = mesh.step_count > 1;
  float f = 0.f;
  const size_t first =
      tri.moving ? time_segment(time, mesh.step_count - 1, f) * mesh.vertex_count : 0;
  const size_t next = tri.moving ? first + mesh.vertex_count : 0;
  for (int i = 0; i < 3; ++i) {
    tri.corner[i] = corner[i];
    tri.rest[i] = mesh.positions[corner[i]];
    const Vec3f a = mesh.positions[first + corner[i]];
    if (!tri.moving) {
      tri.p[i] = a, tri.magnitude[i] = abs(a);
      if (!mesh.normals.empty()) tri.n[i] = mesh.normals[corner[i]];
      continue;
    }
    const Vec3f c = mesh.positions[next + corner[i]];
    tri.p[i] = a * (1.f - f) + c * f;
    tri.magnitude[i] = abs(a) + abs(c);
    if (!mesh.normals.empty())
      tri.n[i] = mesh.normals[first + corner[i]] * (1.f - f) + mesh.normals[next + corner[i]] * f;
  }
  return tri;
}

// The prototype's corners placed as build_mesh places a flattened copy's vertices (each step's
// render_from_object in double, rounded once to float) and interpolated between steps as
// flat_triangle does, so that a hit rebuilds the same triangle either way.
RenderGeometry::HitTriangle RenderGeometry::instanced_triangle(const Instance& instance,
                                                               uint32_t primitive,
                                                               float time) const {
  const Mesh& mesh = prototypes_[instance.prototype];
  HitTriangle tri;
  tri.mesh = &mesh;
  tri.instance = &instance;
  tri.primitive = primitive;
  const uint32_t* corner = &mesh.indices[3 * size_t(primitive)];
  const uint32_t steps = uint32_t(instance.render_from_object.size());
  tri.moving = steps > 1;
  float f = 0.f;
  const uint32_t first = tri.moving ? time_segment(time, steps - 1, f) : 0;
  const uint32_t next = tri.moving ? first + 1 : 0;
  Vec3d reach{};
  for (int i = 0; i < 3; ++i) {
    const uint32_t c = corner[instance.mirrored && i > 0 ? 3 - i : i];
    tri.corner[i] = c;
    const Vec3d object(mesh.positions[c]);
    const Vec3f a(instance.render_from_object[first].point(object));
    tri.rest[i] = first == 0 ? a : Vec3f(instance.render_from_object[0].point(object));
    reach = max(reach, transform_magnitude(instance.render_from_object[first], object));
    const Vec3f na = mesh.normals.empty()
                         ? Vec3f{}
                         : unit_through(instance.normal_from_object[first], Vec3d(mesh.normals[c]));
    if (!tri.moving) {
      tri.p[i] = a, tri.magnitude[i] = abs(a), tri.n[i] = na;
      continue;
    }
    const Vec3f b(instance.render_from_object[next].point(object));
    reach = max(reach, transform_magnitude(instance.render_from_object[next], object));
    tri.p[i] = a * (1.f - f) + b * f;
    tri.magnitude[i] = abs(a) + abs(b);
    if (!mesh.normals.empty())
      tri.n[i] = na * (1.f - f) +
                 unit_through(instance.normal_from_object[next], Vec3d(mesh.normals[c])) * f;
  }
  tri.transform_magnitude = Vec3f(reach);
  return tri;
}

SurfacePoint RenderGeometry::surface_point(const HitTriangle& tri, float u, float v) {
  const float b[3] = {1.f - u - v, u, v};
  SurfacePoint point;
  // At the first motion step: solid textures on moving meshes are not supported (only POV-Ray
  // scenes have them, and nothing moves there). From the first corner along the edges, so that a
  // coordinate all three corners share comes out exact: a plane at y = -1 tessellated from a
  // POV-Ray scene must give its checker y = -1, not -1 - 1 ulp (the barycentric sum rounds).
  const Vec3f p0 = tri.rest[0];
  point.position = p0 + (tri.rest[1] - p0) * u + (tri.rest[2] - p0) * v;
  const VertexTextureData& data = tri.mesh->texturing;
  const uint32_t* c = tri.corner;
  for (uint32_t set = 0; set < VertexTextureData::kSets && !data.texcoords[set].empty(); ++set) {
    const std::vector<Vec2f>& uv = data.texcoords[set];
    point.uv[set] = uv[c[0]] * b[0] + uv[c[1]] * b[1] + uv[c[2]] * b[2];
    point.uv_sets = set + 1;
  }
  // An instance's tangents are in object space: each corner's is placed as build_mesh places a
  // flattened copy's (render_from_object at the first step, then normalised; radial tangents by
  // the normals' transform) before they are interpolated.
  const Instance* instance = tri.instance;
  if (!data.tangents.empty()) {
    Vec3f t{};
    for (int i = 0; i < 3; ++i) {
      const auto& tangent = data.tangents[c[i]];
      const Vec3f corner{tangent[0], tangent[1], tangent[2]};
      t +=
          (instance ? unit_through(instance->render_from_object[0], Vec3d(corner)) : corner) * b[i];
    }
    point.tangent = t;
    point.bitangent_sign = data.tangents[c[0]][3] < 0.f ? -1.f : 1.f;
  }
  if (!data.radial_tangents.empty()) {
    Vec3f r[3];
    for (int i = 0; i < 3; ++i) {
      r[i] = data.radial_tangents[c[i]];
      if (instance) r[i] = Vec3f(instance->normal_from_object[0].vector(Vec3d(r[i])));
    }
    point.radial_tangent = r[0] * b[0] + r[1] * b[1] + r[2] * b[2];
  }
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
    if (!mesh.shader->covers(mesh.material,
                             surface_point(flat_triangle(mesh, primitive, 0.f), u, v), hash))
      args->valid[i] = 0;
  }
}

Rgb RenderGeometry::emission_at(const EmissiveTriangle& emitter, float u, float v) const {
  return shader_->emission(
      emitter.material,
      surface_point(flat_triangle(meshes_[emitter.mesh], emitter.primitive, 0.f), u, v));
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

void RenderGeometry::fill_hit(const HitTriangle& tri, float u, float v, float t,
                              const HitRequest& request, fb_hit& hit) const {
  const Mesh& mesh = *tri.mesh;
  const float b[3] = {1.f - u - v, u, v};
  const Vec3f* p = tri.p;
  // Re-interpolating from the vertices puts the point on the triangle's plane up to rounding,
  // bounded by gamma(7) times the magnitudes summed (pbrt 4e §6.8.4); between motion steps, our
  // corners and Embree's each round a lerp too: gamma(7) more.
  const Vec3f position = p[0] * b[0] + p[1] * b[1] + p[2] * b[2];
  const Vec3f shadow =
      mesh.normals.empty() ? position : lifted_onto_smooth_surface(position, p, tri.n, b);
  // The lifted point carries the position's error and one rounding more: one bound for both.
  Vec3f error = (tri.magnitude[0] * std::abs(b[0]) + tri.magnitude[1] * std::abs(b[1]) +
                 tri.magnitude[2] * std::abs(b[2])) *
                    gamma(tri.moving ? 14 : 7) +
                abs(shadow) * gamma(1);
  // An instance's surface, as Embree meets it, is the object-space triangle seen through the float
  // matrix and its float inverse applied to the ray (Embree 3's instance intersector): each a few
  // roundings of terms as large as |A| |p| + |t| (pbrt 4e §6.8.6), which gamma(16) covers.
  if (tri.instance) error += tri.transform_magnitude * gamma(16);
  const Vec3f ng = normalize(cross(p[1] - p[0], p[2] - p[0]));
  Vec3f ns = ng;
  if (!mesh.normals.empty()) {
    const Vec3f interpolated = tri.n[0] * b[0] + tri.n[1] * b[1] + tri.n[2] * b[2];
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
  hit.emitter = mesh.first_emitter == FB_NONE ? FB_NONE : mesh.first_emitter + tri.primitive;
  SurfacePoint point = surface_point(tri, u, v);
  Vec3f dp_dx, dp_dy;
  if (point.uv_sets > 0 &&
      position_differentials(request.footprint, Vec3f(request.ray.origin),
                             Vec3f(request.ray.direction), position, ng, dp_dx, dp_dy))
    set_texture_differentials(p, tri.corner, mesh.texturing, dp_dx, dp_dy, point);
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
