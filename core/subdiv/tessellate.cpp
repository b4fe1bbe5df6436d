#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/tessellation.h>

#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "core/subdiv/refine.h"

namespace fb::subdiv {
namespace {

namespace Bfr = OpenSubdiv::Bfr;

uint64_t edge_key(uint32_t a, uint32_t b) {
  return (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

// The rate - 1 inner points of one cage edge, once the first of its faces has made them: at
// consecutive indices from `first`, in order from vertex `from`.
struct SharedEdge {
  uint32_t rate;
  uint32_t first = UINT32_MAX;
  uint32_t from = 0;
};

}  // namespace

// Bfr (OpenSubdiv 3.5) evaluates each face's limit surface directly; a Tessellation with one rate
// per edge puts rate - 1 evenly spaced points inside each edge, so two faces that give a shared
// edge the same rate meet at the same points, and reusing the first face's points (rather than
// evaluating them twice) leaves no crack, not even of rounding size.
Triangles tessellate(const Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage,
                     const uint32_t* edge_rates, uint32_t quality, uint64_t max_triangles) {
  // Blender (intern/opensubdiv) isolates irregular and semi-sharp features `quality` levels deep
  // before fitting patches; Bfr's approximation levels are that isolation. Measured against
  // Blender 3.4's evaluated meshes (tests/blender/blender_subdiv_test.cpp): within 1.2e-7 m on
  // 2 m cages, except at smooth boundary corners, where Blender's end patches differ.
  Bfr::SurfaceFactory::Options factory_options;
  factory_options.SetApproxLevelSmooth(int(quality)).SetApproxLevelSharp(int(quality));
  const Bfr::RefinerSurfaceFactory<> factory(refiner, factory_options);
  const Bfr::Tessellation::Options options;  // triangles, (u, v) pairs

  // First pass: the rates agree along every edge, and the triangle count is within the cap.
  std::unordered_map<uint64_t, SharedEdge> edges;
  uint64_t triangles = 0;
  std::vector<int> rates;
  for (uint32_t f = 0, first = 0; f < cage.face_count; first += cage.face_sizes[f++]) {
    const uint32_t n = cage.face_sizes[f];
    rates.assign(edge_rates + first, edge_rates + first + n);
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t a = cage.face_vertices[first + k], b = cage.face_vertices[first + (k + 1) % n];
      const auto [it, fresh] = edges.try_emplace(edge_key(a, b), SharedEdge{uint32_t(rates[k])});
      if (!fresh && it->second.rate != uint32_t(rates[k]))
        throw std::runtime_error("the two faces of the edge " + std::to_string(a) + "-" +
                                 std::to_string(b) + " ask for different rates; they would crack");
    }
    const Bfr::Tessellation pattern(Bfr::Parameterization(refiner.GetSchemeType(), int(n)), int(n),
                                    rates.data(), options);
    if (!pattern.IsValid()) throw std::runtime_error("invalid tessellation rates");
    triangles += uint64_t(pattern.GetNumFacets());
  }
  if (triangles > max_triangles)
    throw std::runtime_error("the tessellation makes " + std::to_string(triangles) +
                             " triangles, more than the limit of " + std::to_string(max_triangles));

  Triangles out;
  out.indices.reserve(3 * triangles);
  std::vector<uint32_t> corner(cage.vertex_count, UINT32_MAX);
  Bfr::Surface<float> surface;
  std::vector<float> patch_points, coords;
  std::vector<int> facets, boundary;
  const Bfr::Surface<float>::PointDescriptor point3(3);
  const auto emit = [&](const float uv[2]) {
    float p[3], du[3], dv[3];
    surface.Evaluate(uv, patch_points.data(), point3, p, du, dv);
    float n[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2],
                  du[0] * dv[1] - du[1] * dv[0]};
    float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) {
      // At an extraordinary corner the parametrisation degenerates (one derivative vanishes):
      // take the normal a little way towards the face's centre.
      float centre[2], near[2], q[3];
      surface.GetParameterization().GetCenterCoord(centre);
      for (int i = 0; i < 2; ++i)
        near[i] = uv[i] + 1e-3f * (centre[i] - uv[i]);
      surface.Evaluate(near, patch_points.data(), point3, q, du, dv);
      n[0] = du[1] * dv[2] - du[2] * dv[1], n[1] = du[2] * dv[0] - du[0] * dv[2],
      n[2] = du[0] * dv[1] - du[1] * dv[0];
      len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    }
    for (int i = 0; i < 3; ++i) {
      out.positions.push_back(p[i]);
      out.normals.push_back(len > 0 ? n[i] / len : 0);
    }
    return uint32_t(out.positions.size() / 3 - 1);
  };

  for (uint32_t f = 0, first = 0; f < cage.face_count; first += cage.face_sizes[f++]) {
    const uint32_t n = cage.face_sizes[f];
    if (!factory.InitVertexSurface(int(f), &surface))
      throw std::runtime_error("OpenSubdiv cannot evaluate the limit surface of face " +
                               std::to_string(f));
    rates.assign(edge_rates + first, edge_rates + first + n);
    Bfr::Tessellation pattern(surface.GetParameterization(), int(n), rates.data(), options);
    patch_points.resize(size_t(surface.GetNumPatchPoints()) * 3);
    surface.PreparePatchPoints(cage.positions, point3, patch_points.data(), point3);
    coords.resize(size_t(pattern.GetNumCoords()) * 2);
    pattern.GetCoords(coords.data());
    // Boundary coordinates come first, counter-clockwise from vertex 0: each corner, then the
    // inner points of the edge that leaves it.
    boundary.assign(size_t(pattern.GetNumBoundaryCoords()), 0);
    size_t b = 0;
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t a = cage.face_vertices[first + k], c = cage.face_vertices[first + (k + 1) % n];
      if (corner[a] == UINT32_MAX) corner[a] = emit(&coords[2 * b]);
      boundary[b++] = int(corner[a]);
      SharedEdge& edge = edges.at(edge_key(a, c));
      const uint32_t inner = uint32_t(rates[k]) - 1;
      if (edge.first == UINT32_MAX) {
        edge.first = uint32_t(out.positions.size() / 3), edge.from = a;
        for (uint32_t i = 0; i < inner; ++i)
          emit(&coords[2 * (b + i)]);
      }
      for (uint32_t i = 0; i < inner; ++i)
        boundary[b + i] = int(edge.from == a ? edge.first + i : edge.first + inner - 1 - i);
      b += inner;
    }
    const uint32_t interior = uint32_t(out.positions.size() / 3);
    for (size_t i = b; i < size_t(pattern.GetNumCoords()); ++i)
      emit(&coords[2 * i]);
    facets.resize(size_t(pattern.GetNumFacets()) * 3);
    pattern.GetFacets(facets.data());
    pattern.TransformFacetCoordIndices(facets.data(), boundary.data(), int(interior) - int(b));
    for (int i : facets)
      out.indices.push_back(uint32_t(i));
  }
  return out;
}

}  // namespace fb::subdiv
