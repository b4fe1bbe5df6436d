#include "core/subdiv/refine_scene.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/scene/mesh_tangents.h"
#include "core/subdiv/face_varying.h"
#include "core/subdiv/subdiv_loader.h"
#include "core/util/error.h"

namespace fb {
namespace {

// A cage edge is never cut into more segments than this, however close the camera.
constexpr uint32_t kMaxEdgeRate = 4096;

// The cage as the module's C structs, pointing into these vectors and the surface's own.
struct CageData {
  std::vector<float> positions;
  std::vector<uint32_t> crease_edges, crease_vertices;
  std::vector<float> edge_sharpness, vertex_sharpness;
  std::vector<FaceVaryingChannel> uvs;
  std::vector<fb_subdiv_uv_channel> uv_channels;
  fb_subdiv_cage cage{};
};

// The modifier's uv_smooth as OpenSubdiv's face-varying rule, as Blender 3.4 maps it
// (blenkernel/intern/subdiv.c, BKE_subdiv_fvar_interpolation_from_uv_smooth, then
// subdiv_converter.c to OpenSubdiv's enum; Cycles' blender/mesh.cc maps it the same way).
uint32_t fvar_linear(SubdivisionSettings::UvSmooth uv_smooth) {
  using UvSmooth = SubdivisionSettings::UvSmooth;
  switch (uv_smooth) {
    case UvSmooth::kNone:
      return FB_SUBDIV_FVAR_LINEAR_ALL;
    case UvSmooth::kPreserveCorners:
      return FB_SUBDIV_FVAR_LINEAR_CORNERS_ONLY;
    case UvSmooth::kPreserveCornersAndJunctions:
      return FB_SUBDIV_FVAR_LINEAR_CORNERS_PLUS1;
    case UvSmooth::kPreserveCornersJunctionsAndConcave:
      return FB_SUBDIV_FVAR_LINEAR_CORNERS_PLUS2;
    case UvSmooth::kPreserveBoundaries:
      return FB_SUBDIV_FVAR_LINEAR_BOUNDARIES;
    case UvSmooth::kSmoothAll:
      return FB_SUBDIV_FVAR_LINEAR_NONE;
  }
  return FB_SUBDIV_FVAR_LINEAR_BOUNDARIES;
}

void fill_cage(const SubdivisionSurface& s, CageData& d) {
  d.positions.reserve(3 * s.cage_positions.size());
  for (const Vec3f& p : s.cage_positions)
    d.positions.insert(d.positions.end(), {p.x, p.y, p.z});
  const SubdivisionSettings& settings = s.settings;
  if (settings.use_creases) {
    for (const EdgeCrease& c : s.edge_creases)
      if (c.weight > 0) {
        d.crease_edges.insert(d.crease_edges.end(), {c.v0, c.v1});
        d.edge_sharpness.push_back(crease_sharpness(c.weight));
      }
    for (const VertexCrease& c : s.vertex_creases)
      if (c.weight > 0) {
        d.crease_vertices.push_back(c.vertex);
        d.vertex_sharpness.push_back(crease_sharpness(c.weight));
      }
  }
  fb_subdiv_cage& c = d.cage;
  c.struct_size = sizeof(fb_subdiv_cage);
  c.abi_version = FB_SUBDIV_ABI_VERSION;
  c.positions = d.positions.data();
  c.vertex_count = uint32_t(s.cage_positions.size());
  c.face_sizes = s.cage_face_sizes.data();
  c.face_count = uint32_t(s.cage_face_sizes.size());
  c.face_vertices = s.cage_face_vertices.data();
  c.crease_edges = d.crease_edges.data();
  c.crease_edge_sharpness = d.edge_sharpness.data();
  c.crease_edge_count = uint32_t(d.edge_sharpness.size());
  c.crease_vertices = d.crease_vertices.data();
  c.crease_vertex_sharpness = d.vertex_sharpness.data();
  c.crease_vertex_count = uint32_t(d.vertex_sharpness.size());
  c.scheme = settings.scheme == SubdivisionSettings::Scheme::kSimple ? FB_SUBDIV_BILINEAR
                                                                     : FB_SUBDIV_CATMULL_CLARK;
  c.boundary = settings.boundary_smooth == SubdivisionSettings::Boundary::kPreserveCorners
                   ? FB_SUBDIV_BOUNDARY_EDGE_AND_CORNER
                   : FB_SUBDIV_BOUNDARY_EDGE_ONLY;
  // The UV maps as face-varying channels, their corners joined as Blender joins them.
  for (const SubdivisionUvMap& map : s.uv_maps)
    d.uvs.push_back(
        join_uv_corners(s.cage_face_sizes, s.cage_face_vertices, c.vertex_count, map.corner_uvs));
  for (const FaceVaryingChannel& channel : d.uvs)
    d.uv_channels.push_back(
        {channel.values.data(), channel.value_count(), channel.corner_values.data()});
  c.uv_channels = d.uv_channels.data();
  c.uv_channel_count = uint32_t(d.uv_channels.size());
  c.fvar_linear = fvar_linear(settings.uv_smooth);
}

// The triangles of one part of the module's mesh (all of them when the surface has one part),
// their vertices renumbered, texture-coordinate slots filled from the channels the part reads and
// tangents from the slot its normal maps use.
TriangleMesh part_mesh(const SubdivisionSurface& s, const fb_subdiv_mesh& out, uint32_t part) {
  const SubdivisionPart& p = s.parts[part];
  TriangleMesh mesh;
  mesh.name = s.name + " (subdivided" +
              (s.parts.size() > 1 ? ", part " + std::to_string(part) : std::string()) + ")";
  mesh.material = p.material;
  constexpr uint32_t kUnused = 0xffffffffu;
  std::vector<uint32_t> renumber(out.vertex_count, kUnused);
  std::vector<uint32_t> from;  // the module's vertex of each of ours
  for (uint64_t t = 0; t < out.triangle_count; ++t) {
    if (s.parts.size() > 1 && s.face_parts[out.triangle_faces[t]] != part) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = out.indices[3 * t + k];
      if (renumber[v] == kUnused) renumber[v] = uint32_t(from.size()), from.push_back(v);
      mesh.indices.push_back(renumber[v]);
    }
  }
  mesh.positions.resize(from.size());
  mesh.normals.resize(from.size());
  for (size_t i = 0; i < from.size(); ++i) {
    const size_t v = from[i];
    mesh.positions[i] = {out.positions[3 * v], out.positions[3 * v + 1], out.positions[3 * v + 2]};
    mesh.normals[i] = {out.normals[3 * v], out.normals[3 * v + 1], out.normals[3 * v + 2]};
  }
  for (uint32_t slot = 0; slot < VertexTextureData::kSets; ++slot) {
    const uint32_t channel = p.slot_uv_maps[slot];
    if (channel >= s.uv_maps.size()) continue;
    std::vector<Vec2f>& uv = mesh.texturing.texcoords[slot];
    uv.resize(from.size());
    const float* values = out.uvs + 2 * size_t(channel) * out.vertex_count;
    for (size_t i = 0; i < from.size(); ++i)
      uv[i] = {values[2 * size_t(from[i])], values[2 * size_t(from[i]) + 1]};
  }
  if (p.tangent_slot < VertexTextureData::kSets &&
      !mesh.texturing.texcoords[p.tangent_slot].empty())
    mesh.texturing.tangents = mesh_tangents(mesh, mesh.texturing.texcoords[p.tangent_slot]);
  return mesh;
}

// The cage's vertices on the limit surface, in camera space: where the surface's edges run.
std::vector<Vec3d> limit_corners(const SubdivModule& module, const fb_subdiv_cage& cage,
                                 const SubdivisionSurface& s, const SubdivView& view,
                                 const std::string& where) {
  fb_subdiv_request request{};
  request.struct_size = sizeof request;
  request.cage_limit = 1;
  fb_subdiv_mesh out{};
  if (module.refine(&cage, &request, &out) != 0) throw InputError(where + ": " + out.error);
  const Transform camera_from_object = view.camera_from_world * s.world_from_object;
  std::vector<Vec3d> camera(out.vertex_count);
  for (size_t i = 0; i < camera.size(); ++i)
    camera[i] = camera_from_object.point(
        Vec3d(out.positions[3 * i], out.positions[3 * i + 1], out.positions[3 * i + 2]));
  module.free(&out);
  return camera;
}

// The image length in pixels of the segment a-b (camera space), or at least its length seen
// face-on from its nearer end: off the axis a perspective image stretches a segment (up to
// 1/cos^2 of the angle), and a segment along the view direction, which projects short, still
// shapes the surface seen from nearby.
double image_length_px(Vec3d a, Vec3d b, const SubdivView& view) {
  const double scale = std::max(view.fx, view.fy);
  if (view.orthographic) return length(b - a) * scale;
  const double nearer = std::max(std::min(length(a), length(b)), 1e-9);
  double px = length(b - a) * scale / nearer;
  if (a.z < 0 && b.z < 0)  // both in front: the projection itself
    px = std::max(
        px, std::hypot(view.fx * (a.x / -a.z - b.x / -b.z), view.fy * (a.y / -a.z - b.y / -b.z)));
  return px;
}

// Segments per cage edge (one per entry of cage_face_vertices) so that each is about
// `target_px` long on the image, measured between the edge's ends on the limit surface (the
// chord stands in for the limit curve, which is longer by a few per cent where the surface
// bends). A rate depends only on the edge, so the two faces of an edge agree: no cracks.
std::vector<uint32_t> edge_rates(const SubdivisionSurface& s, const std::vector<Vec3d>& camera,
                                 const SubdivView& view, double target_px, uint64_t& estimate) {
  std::vector<uint32_t> rates(s.cage_face_vertices.size());
  estimate = 0;
  for (size_t f = 0, first = 0; f < s.cage_face_sizes.size(); first += s.cage_face_sizes[f++]) {
    const size_t n = s.cage_face_sizes[f];
    double sum = 0;
    for (size_t k = 0; k < n; ++k) {
      const double px = image_length_px(camera[s.cage_face_vertices[first + k]],
                                        camera[s.cage_face_vertices[first + (k + 1) % n]], view);
      const double rate = std::clamp(std::ceil(px / target_px), 1.0, double(kMaxEdgeRate));
      rates[first + k] = uint32_t(rate);
      sum += rate;
    }
    // Bfr's pattern: an n-gon is n quads at half the rate, about 2 r^2 / 4 triangles each.
    const double mean = sum / double(n);
    estimate += uint64_t(double(n) * mean * mean / 2 + double(n));
  }
  return rates;
}

std::string where(const Scene& scene, const SubdivisionSurface& s) {
  return scene.file.string() + ": subdivision surface '" + s.name + "' (" + s.node + ")";
}

// What the importer guarantees and the module relies on: arrays parallel to the cage's corners
// and faces, parts in range.
void check_face_data(const Scene& scene, const SubdivisionSurface& s) {
  bool ok =
      !s.parts.empty() && (s.face_parts.empty() ? s.parts.size() == 1
                                                : s.face_parts.size() == s.cage_face_sizes.size());
  for (uint32_t p : s.face_parts)
    ok = ok && p < s.parts.size();
  for (const SubdivisionUvMap& map : s.uv_maps)
    ok = ok && map.corner_uvs.size() == s.cage_face_vertices.size();
  if (!ok)
    throw InputError(where(scene, s) +
                     ": its UV maps or face parts do not match its cage's corners and faces");
}

}  // namespace

SubdivReport refine_subdivision_surfaces(Scene& scene, SubdivMode mode, const SubdivView& view,
                                         uint64_t max_triangles) {
  SubdivReport report;
  if (scene.subdivision_surfaces.empty()) return report;
  const SubdivModule& module = subdiv_module();
  uint64_t made = 0;
  for (const SubdivisionSurface& s : scene.subdivision_surfaces) {
    check_face_data(scene, s);
    CageData data;
    fill_cage(s, data);
    fb_subdiv_request request{};
    request.struct_size = sizeof request;
    request.level = s.settings.levels_render;
    request.quality = s.settings.quality;
    request.max_triangles = max_triangles - made;
    std::vector<uint32_t> rates;
    std::string how = "level " + std::to_string(s.settings.levels_render);
    if (mode == SubdivMode::kAdaptive) {
      double target_px = 1;
      uint64_t estimate = 0;
      const std::vector<Vec3d> corners = limit_corners(module, data.cage, s, view, where(scene, s));
      rates = edge_rates(s, corners, view, target_px, estimate);
      if (estimate > request.max_triangles) {
        // Coarser segments, in proportion: the triangle count goes as the square of the rate.
        target_px *= 1.05 * std::sqrt(double(estimate) / double(request.max_triangles));
        rates = edge_rates(s, corners, view, target_px, estimate);
        report.warnings.push_back(where(scene, s) +
                                  ": adaptive subdivision would pass the limit "
                                  "of " +
                                  std::to_string(max_triangles) + " triangles; edges of about " +
                                  number_text(target_px) + " px instead of 1");
      }
      how = "adaptive, edges of ~" + number_text(target_px) + " px";
    } else if (s.settings.use_limit_surface && s.settings.levels_render > 0) {
      // Blender's limit surface at its level: 2^level segments on every cage edge samples the
      // parameters of uniform refinement's vertices.
      rates.assign(s.cage_face_vertices.size(), 1u << std::min(s.settings.levels_render, 16u));
    }
    // Otherwise (use_limit_surface off, or level 0: Blender's modifier leaves the cage) uniform
    // refinement of the cage itself.
    request.edge_rates = rates.empty() ? nullptr : rates.data();
    request.triangle_faces = s.parts.size() > 1;
    // Blender's modifier leaves a mesh whose normals Blender computes from its polygons, and
    // Cycles renders those; its adaptive subdivision evaluates the limit surface's.
    request.polygon_normals = mode != SubdivMode::kAdaptive;
    fb_subdiv_mesh out{};
    if (module.refine(&data.cage, &request, &out) != 0)
      throw InputError(where(scene, s) + ": " + out.error +
                       (mode == SubdivMode::kRender
                            ? " (lower the modifier's render level, or use --subdiv adaptive)"
                            : ""));
    const std::unique_ptr<fb_subdiv_mesh, fb_subdiv_free_fn> owned(&out, module.free);
    uint64_t triangles = 0;
    for (uint32_t part = 0; part < s.parts.size(); ++part) {
      TriangleMesh mesh = part_mesh(s, out, part);
      if (mesh.indices.empty()) continue;
      triangles += mesh.triangle_count();
      scene.instances.push_back(
          {uint32_t(scene.meshes.size()), s.world_from_object, s.node, s.node_index, s.asset});
      scene.meshes.push_back(std::move(mesh));
    }
    made += triangles;
    report.summary += std::string(report.summary.empty() ? "" : ", ") + "'" + s.name + "' " + how +
                      ": " + std::to_string(triangles) + " triangles";
  }
  scene.subdivision_surfaces.clear();
  report.summary = "subdivision (" + module.file.filename().string() + "): " + report.summary;
  return report;
}

}  // namespace fb
