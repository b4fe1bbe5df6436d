// The alignment test against Blender itself. Debian's Blender builds a shot with bpy (make_shot.py:
// a rotated, displaced camera and small emissive spheres on a black world), exports it with its
// own glTF exporter and renders it with Cycles; filmback renders the exported file at the same
// size with the same 1 px box filter. Each sphere's image centroid must agree within 0.1 px and
// its flux (sum of pixel values) within 2 %: an emitter of radiance L is L in both renderers.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "core/image/image_io.h"
#include "tests/blender/blobs.h"

namespace fb::test {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kSamplesPerPixel = 512;  // both renderers; centroid noise is then ~0.01 px
constexpr double kMaxCentroidErrorPx = 0.1;
constexpr double kMaxFluxError = 0.02;
// A blob belongs to a sphere when its centroid is this close to Blender's own projection of the
// sphere's centre (bpy_extras.object_utils.world_to_camera_view); the spheres are >40 px apart.
constexpr double kMatchRadiusPx = 1.0;
// Background pixels are exactly 0 (black world, emission only); anything brighter is a sphere.
constexpr double kBlobThreshold = 0.0;

std::optional<fs::path> find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string rest = path ? path : "";
  while (!rest.empty()) {
    const size_t colon = rest.find(':');
    const fs::path candidate = fs::path(rest.substr(0, colon)) / program;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate;
    rest = colon == std::string::npos ? "" : rest.substr(colon + 1);
  }
  return std::nullopt;
}

std::string quoted(const fs::path& path) {  // for /bin/sh: '...' with each ' written as '\''
  std::string out = "'";
  for (char c : path.string())
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string last_lines(const fs::path& file, size_t count) {
  std::ifstream in(file);
  std::deque<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
    if (lines.size() > count) lines.pop_front();
  }
  std::string out;
  for (const std::string& line : lines)
    out += line + "\n";
  return out;
}

// Runs a shell command with its output in `log`; returns the wall time, or fails the test
// with the log's tail.
double run_logged(const std::string& command, const fs::path& log) {
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system((command + " > " + quoted(log) + " 2>&1").c_str());
  const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
  const bool ok = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  EXPECT_TRUE(ok) << "command failed (status " << status << "): " << command << "\n"
                  << "last lines of " << log << ":\n"
                  << last_lines(log, 30);
  return seconds.count();
}

struct Sphere {
  std::string name;
  double x_px = 0, y_px = 0;  // Blender's projection of the centre
};

std::vector<Sphere> read_spheres(const fs::path& file) {
  std::ifstream in(file);
  std::vector<Sphere> spheres;
  for (Sphere s; in >> s.name >> s.x_px >> s.y_px;)
    spheres.push_back(s);
  return spheres;
}

double distance_px(double ax, double ay, double bx, double by) {
  return std::hypot(ax - bx, ay - by);
}

const Blob* blob_at(const std::vector<Blob>& blobs, const Sphere& sphere) {
  for (const Blob& blob : blobs)
    if (distance_px(blob.x_px, blob.y_px, sphere.x_px, sphere.y_px) < kMatchRadiusPx) return &blob;
  return nullptr;
}

TEST(BlenderAlignment, SpheresHaveTheSameCentroidAndFluxAsInCycles) {
  const std::optional<fs::path> blender = find_on_path("blender");
  if (!blender)
    GTEST_SKIP() << "Blender is not installed: no `blender` on PATH. Install Debian's package "
                    "`blender` (apt-get install blender) to run the alignment test.";
  const fs::path work = FILMBACK_BLENDER_WORK_DIR;
  fs::remove_all(work);
  fs::create_directories(work);

  const double blender_s =
      run_logged(quoted(*blender) + " -b --factory-startup --python-exit-code 1 --python " +
                     quoted(FILMBACK_MAKE_SHOT_PY) + " -- " + quoted(work) + " " +
                     std::to_string(kSamplesPerPixel),
                 work / "blender.log");
  ASSERT_FALSE(HasFailure());
  const Image cycles = read_image(work / "cycles.exr");
  const std::string resolution = std::to_string(cycles.width) + "x" + std::to_string(cycles.height);
  const double filmback_s =
      run_logged(quoted(FILMBACK_EXE) + " render " + quoted(work / "shot.gltf") + " -o " +
                     quoted(work / "filmback.exr") + " --res " + resolution + " --spp " +
                     std::to_string(kSamplesPerPixel) + " --filter box -q",
                 work / "filmback.log");
  ASSERT_FALSE(HasFailure());
  const Image filmback = read_image(work / "filmback.exr");
  ASSERT_EQ(filmback.width, cycles.width);
  ASSERT_EQ(filmback.height, cycles.height);

  const std::vector<Sphere> spheres = read_spheres(work / "spheres.txt");
  ASSERT_FALSE(spheres.empty()) << "make_shot.py wrote no spheres to " << work / "spheres.txt";
  const std::vector<Blob> cycles_blobs = find_blobs(cycles, kBlobThreshold);
  const std::vector<Blob> filmback_blobs = find_blobs(filmback, kBlobThreshold);
  ASSERT_EQ(cycles_blobs.size(), spheres.size()) << "blobs in the Cycles render";
  ASSERT_EQ(filmback_blobs.size(), spheres.size()) << "blobs in the filmback render";

  std::printf(
      "Blender alignment, %s at %u spp, 1 px box filter; Blender (build, export, Cycles) "
      "%.1f s, filmback %.1f s\n",
      resolution.c_str(), kSamplesPerPixel, blender_s, filmback_s);
  std::printf("%-20s %9s %9s %9s %9s %8s %8s %8s %11s %10s %8s\n", "sphere", "cycles_x", "cycles_y",
              "fb_x", "fb_y", "dx_px", "dy_px", "|d|_px", "cycles_flux", "fb_flux", "ratio");
  double worst_px = 0, worst_flux = 0;
  for (const Sphere& sphere : spheres) {
    const Blob* c = blob_at(cycles_blobs, sphere);
    const Blob* f = blob_at(filmback_blobs, sphere);
    ASSERT_NE(c, nullptr) << sphere.name << ": no Cycles blob within " << kMatchRadiusPx
                          << " px of Blender's projection (" << sphere.x_px << ", " << sphere.y_px
                          << ")";
    ASSERT_NE(f, nullptr) << sphere.name << ": no filmback blob within " << kMatchRadiusPx
                          << " px of Blender's projection (" << sphere.x_px << ", " << sphere.y_px
                          << ")";
    const double d_px = distance_px(f->x_px, f->y_px, c->x_px, c->y_px);
    const double ratio = f->flux / c->flux;
    worst_px = std::max(worst_px, d_px);
    worst_flux = std::max(worst_flux, std::abs(ratio - 1));
    std::printf("%-20s %9.4f %9.4f %9.4f %9.4f %+8.4f %+8.4f %8.4f %11.4f %10.4f %8.5f\n",
                sphere.name.c_str(), c->x_px, c->y_px, f->x_px, f->y_px, f->x_px - c->x_px,
                f->y_px - c->y_px, d_px, c->flux, f->flux, ratio);
    EXPECT_LT(d_px, kMaxCentroidErrorPx) << sphere.name << ": centroids differ";
    EXPECT_NEAR(ratio, 1.0, kMaxFluxError) << sphere.name << ": flux filmback / Cycles";
  }
  std::printf(
      "max centroid difference %.4f px (limit %.2f), max flux error %.3f %% (limit %.0f %%)\n",
      worst_px, kMaxCentroidErrorPx, 100 * worst_flux, 100 * kMaxFluxError);
}

}  // namespace
}  // namespace fb::test
