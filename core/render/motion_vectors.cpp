#include "core/render/motion_vectors.h"

#include "core/render/shot_plan.h"
#include "core/util/error.h"

namespace fb {
namespace {

// The camera's lens at `frame`: its lens track's values there (focal length, shift...), but for
// those typed on the command line, which hold for every frame.
PhysicalCamera lens_at_frame(const SceneCamera& camera, double frame) {
  PhysicalCamera lens = camera.physical;
  if (!camera.lens_track) return lens;
  camera.lens_track->apply(frame, lens);
  for (const CameraValue v : LensTrack::kTracked)
    if (camera.origin(v).typed()) set_camera_value(lens, v, camera_value(camera.physical, v));
  return lens;
}

}  // namespace

MotionVectors::MotionVectors(const Scene& scene, const ShotPlan& plan,
                             const Transform& render_from_world)
    : orthographic_(blender_projection(plan.camera_model) == FB_PROJECTION_ORTHOGRAPHIC),
      world_from_render_(render_from_world.inverse()),
      moving_of_object_(scene.instances.size() + scene.solids.size(), kStill) {
  const SceneCamera& camera = plan.camera;
  const std::string& model = plan.camera_model.name;
  if (!blender_projection(plan.camera_model) || !camera.lens_distortion.empty())
    throw UsageError("--passes Vector: the camera is '" + model +
                     (camera.lens_distortion.empty() ? "'" : "' with lens distortion") +
                     "; expected perspective, thinlens or orthographic without lens distortion, "
                     "Blender's projections, by which the pass places points");
  const double frame_s = plan.times.frame_s, frame_length_s = 1 / plan.fps;
  for (int k = 0; k < 3; ++k) {
    const double time_s = frame_s + (k - 1) * frame_length_s;
    // The current frame's lens is the plan's (the focal length at the shutter's centre).
    const PhysicalCamera lens =
        k == 1 ? camera.physical : lens_at_frame(camera, plan.frame + k - 1);
    cameras_[k] = {
        scene.world_from_camera(camera, time_s).inverse(),
        view_plane(make_camera_setup(lens, plan.width_px, plan.height_px, plan.pixel_aspect))};
  }
  deformed_of_object_.assign(moving_of_object_.size(), kStill);
  std::vector<const MeshDeformation*> deformation_of(scene.meshes.size(), nullptr);
  for (const MeshDeformation& d : scene.deformations)
    if (d.evaluated.empty() &&
        deforms(d, scene.hierarchy, frame_s - frame_length_s, frame_s + frame_length_s))
      deformation_of[d.mesh] = &d;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    const MeshInstance& instance = scene.instances[i];
    if (const MeshDeformation* deformation = deformation_of[instance.mesh]) {
      DeformedPoses& poses = deformed_.emplace_back();
      poses.indices = &scene.meshes[instance.mesh].indices;
      for (int k = 0; k < 3; ++k) {
        const double time_s = frame_s + (k - 1) * frame_length_s;
        const Transform render_from_object =
            render_from_world * scene.world_from_object(instance, time_s);
        for (const Vec3f& p : posed_mesh(scene, *deformation, time_s).positions)
          poses.render_positions[k].emplace_back(render_from_object.point(Vec3d(p)));
      }
      deformed_of_object_[i] = uint32_t(deformed_.size() - 1);
      continue;
    }
    if (!scene.moves(instance.node_index, frame_s - frame_length_s, frame_s + frame_length_s))
      continue;
    const Transform object_from_world = scene.world_from_object(instance, frame_s).inverse();
    moving_of_object_[i] = uint32_t(moving_.size());
    moving_.push_back(
        {scene.world_from_object(instance, frame_s - frame_length_s) * object_from_world,
         scene.world_from_object(instance, frame_s + frame_length_s) * object_from_world});
  }
}

bool MotionVectors::raster(const CameraMoment& camera, Vec3d p, Vec2d& out) const {
  const Vec3d c = camera.camera_from_world.point(p);
  // raster = (cx + fx X / -Z, cy - fy Y / -Z) in perspective, without the division in ortho
  // (filmback/camera_projection.h).
  const double depth = orthographic_ ? 1.0 : -c.z;
  if (!(depth > 0)) return false;
  out = {camera.plane.cx + camera.plane.fx * c.x / depth,
         camera.plane.cy - camera.plane.fy * c.y / depth};
  return true;
}

std::array<Vec3d, 3> MotionVectors::deformed_points(
    const DeformedPoses& d, const RenderGeometry::SurfaceIdentity& met) const {
  std::array<Vec3d, 3> points;
  const uint32_t* corner = d.indices->data() + size_t(met.primitive) * 3;
  for (int k = 0; k < 3; ++k) {
    const std::vector<Vec3f>& p = d.render_positions[k];
    points[k] = world_from_render_.point(Vec3d(p[corner[0]]) * double(1.f - met.u - met.v) +
                                         Vec3d(p[corner[1]]) * double(met.u) +
                                         Vec3d(p[corner[2]]) * double(met.v));
  }
  return points;
}

std::array<float, 4> MotionVectors::at(const fb_ray& ray,
                                       const RenderGeometry::SurfaceIdentity& met) const {
  const uint32_t object = met.object;
  const Vec3f hit = Vec3f(ray.origin) + Vec3f(ray.direction) * met.t;
  Vec3d before, now = world_from_render_.point(Vec3d(hit)), after;
  const uint32_t moving = object < moving_of_object_.size() ? moving_of_object_[object] : kStill;
  const uint32_t deformed =
      object < deformed_of_object_.size() ? deformed_of_object_[object] : kStill;
  if (deformed != kStill &&
      (size_t(met.primitive) + 1) * 3 <= deformed_[deformed].indices->size()) {
    const std::array<Vec3d, 3> points = deformed_points(deformed_[deformed], met);
    before = points[0], now = points[1], after = points[2];
  } else {
    before = moving == kStill ? now : moving_[moving][0].point(now);
    after = moving == kStill ? now : moving_[moving][1].point(now);
  }
  Vec2d current, previous, next;
  std::array<float, 4> motion{0.f, 0.f, 0.f, 0.f};
  if (!raster(cameras_[1], now, current)) return motion;
  // Raster y runs down; Cycles' vectors run up.
  if (raster(cameras_[0], before, previous))
    motion[0] = float(previous.x - current.x), motion[1] = float(current.y - previous.y);
  if (raster(cameras_[2], after, next))
    motion[2] = float(current.x - next.x), motion[3] = float(next.y - current.y);
  return motion;
}

}  // namespace fb
