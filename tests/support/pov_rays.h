// Primary rays of a POV-Ray camera two ways, in filmback's world: as POV-Ray 3.7 builds them
// (tracepixel.cpp CreateCameraRay, from the evaluated vectors) and as filmback's camera plugin
// builds them from the converted SceneCamera. The POV-Ray camera tests compare the two.
#pragma once

#include <cstdint>
#include <memory>

#include <filmback/vec.h>

#include "core/plugin/instances.h"
#include "importers/pov/pov_camera.h"

namespace fb::test {

// POV-Ray's `rotate <a, b, c>` (degrees) as a matrix in POV-Ray's space: about x by a, then y by
// b, then z by c, each by the right-hand rule's matrix (notes: povray-camera.md 1.1).
Transform pov_rotate(Vec3d degrees);

struct WorldRay {
  Vec3d origin, direction;  // direction normalised
  double weight = 1;        // 0: no ray (POV-Ray traces none; a camera plugin's weight 0)
};

// POV-Ray's ray through raster point (x_px, y_px) of a W x H image, pixel centres at i + 0.5,
// y down: x0 = x / W - 1/2, y0 = 1/2 - y / H (POV-Ray's pixel centres), for every camera type
// but mesh_camera, written from CreateCameraRay in POV-Ray's own space (the spherical camera's
// turns by its axis-rotation matrix) and mirrored into filmback's world at the end. Weight 0
// where POV-Ray traces no ray (outside a fisheye's circle, omnimax's floor).
WorldRay pov_ray(const pov::PovCameraVectors& camera, double x_px, double y_px, uint32_t width_px,
                 uint32_t height_px);

// The camera plugin the shot plan chooses for this camera, loaded with the plan's values and set up
// for a W x H image with the camera's pixel aspect.
std::unique_ptr<CameraInstance> make_camera_plugin(const pov::PovCamera& camera, uint32_t width_px,
                                                   uint32_t height_px);

// The plugin's ray for the sample, placed in the world by the camera's world_from_camera.
WorldRay filmback_ray(const CameraInstance& plugin, const SceneCamera& camera,
                      const fb_camera_sample& sample);

}  // namespace fb::test
