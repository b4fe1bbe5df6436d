// Image files as a user's tools read them back: OpenEXR's standard camera attributes, the PNG's
// transfer function, and nothing left behind when a write fails.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <filmback/camera_projection.h>

#include "core/image/image_io.h"
#include "core/render/render_job.h"
#include "core/util/error.h"
#include "support/gltf_builder.h"
#include "support/plugins.h"

namespace fb {
namespace {

namespace fs = std::filesystem;

// p' = p M with Imath's row-vector matrices, then the homogeneous divide.
Vec3d imath_transform(const float m[16], Vec3d p) {
  const double v[4] = {p.x, p.y, p.z, 1};
  double out[4] = {0, 0, 0, 0};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      out[c] += v[r] * m[r * 4 + c];
  return {out[0] / out[3], out[1] / out[3], out[2] / out[3]};
}

TEST(ImageOutput, ExrCarriesTheCameraAsOpenExrStandardAttributes) {
  Scene scene;
  scene.materials.emplace_back();
  SceneCamera camera;
  camera.name = "shot";
  camera.physical.focal_length_mm = 35;
  camera.physical.shift_x = 0.05;
  camera.physical.fstop = 2.8;
  camera.physical.focus_distance_m = 4;
  camera.world_from_camera =
      Transform::translate({3, 1, 12}) * Transform::rotate({0.1, 0.2, 0, 0.97});
  scene.cameras.push_back(camera);
  RenderOptions options;
  options.width = 64, options.height = 40, options.samples_per_pixel = 1,
  options.show_progress = false;
  const RenderJob job(scene, options, test::loader());
  const RenderResult result = job.run();
  const fs::path file = test::scratch_dir() / "shot.exr";
  write_images(result.image, {file}, job.metadata(result));

  auto in = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(in);
  const OIIO::ImageSpec& spec = in->spec();
  float world_to_camera[16], world_to_ndc[16];
  ASSERT_TRUE(spec.getattribute("worldToCamera", OIIO::TypeMatrix44, world_to_camera));
  ASSERT_TRUE(spec.getattribute("worldToNDC", OIIO::TypeMatrix44, world_to_ndc));
  EXPECT_EQ(spec.get_string_attribute("filmback/camera"), "shot");
  EXPECT_EQ(spec.get_int_attribute("filmback/samples_per_pixel"), 1);
  EXPECT_FLOAT_EQ(spec.get_float_attribute("filmback/focal_length_mm"), 35.f);
  EXPECT_FLOAT_EQ(spec.get_float_attribute("FNumber"), 2.8f);  // OpenEXR "aperture"
  EXPECT_FLOAT_EQ(spec.get_float_attribute("focus"), 4.f);

  // A world point in front of the camera: camera space by the inverse placement, raster by
  // Blender's view plane, NDC = raster / size with (0,0) at the top-left corner.
  const Transform camera_from_world = camera.world_from_camera.inverse();
  const ViewPlane v = view_plane(make_camera_setup(camera.physical, 64, 40));
  for (Vec3d world : {Vec3d{3.5, 0.8, 5}, Vec3d{1, 2, 2}}) {
    const Vec3d c = camera_from_world.point(world);
    ASSERT_LT(c.z, 0);
    // OpenEXR's camera space: x right, y up, +z the viewing direction (in front: z > 0).
    const Vec3d stored = imath_transform(world_to_camera, world);
    EXPECT_NEAR(stored.x, c.x, 1e-4);
    EXPECT_NEAR(stored.y, c.y, 1e-4);
    EXPECT_NEAR(stored.z, -c.z, 1e-4);
    EXPECT_GT(stored.z, 0);
    const Vec3d ndc = imath_transform(world_to_ndc, world);
    EXPECT_NEAR(ndc.x, (v.cx + v.fx * c.x / -c.z) / 64, 1e-5);
    EXPECT_NEAR(ndc.y, (v.cy - v.fy * c.y / -c.z) / 40, 1e-5);
  }
}

TEST(ImageOutput, PngUsesTheSrgbTransferAndClamps) {
  const Image image{
      3, 1, {"R", "G", "B"}, {0.5f, 0.5f, 0.5f, 0.0031308f, 0.f, 2.f, -1.f, 1.f, 0.18f}};
  const fs::path file = test::scratch_dir() / "ramp.png";
  write_images(image, {file}, {});
  const Image back = read_image(file);
  // IEC 61966-2-1: 0.5 -> 0.7354, 0.0031308 -> 0.04045, 0.18 -> 0.4614; out of range clamps.
  EXPECT_NEAR(back.at(0, 0, 0), 0.7354f, 0.5f / 255);
  EXPECT_NEAR(back.at(1, 0, 0), 0.04045f, 0.5f / 255);
  EXPECT_EQ(back.at(1, 0, 2), 1.f);
  EXPECT_EQ(back.at(2, 0, 0), 0.f);
  EXPECT_NEAR(back.at(2, 0, 2), 0.4614f, 0.5f / 255);
}

TEST(ImageOutput, AFailedWriteLeavesNoFileBehind) {
  const Image image{2, 2, {"R", "G", "B"}, std::vector<float>(12, 0.5f)};
  const fs::path dir = test::scratch_dir();
  fs::create_directory(dir / "taken.png");  // a folder where the second output should go
  EXPECT_THROW(write_images(image, {dir / "first.exr", dir / "taken.png"}, {}), InputError);
  size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir))
    ++entries;
  EXPECT_EQ(entries, 1u) << "only the folder may remain: no first.exr, no temporary file";
}

}  // namespace
}  // namespace fb
