#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/bfr/surfaceFactoryCache.h>
#include <opensubdiv/bfr/tessellation.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <climits>
#include <cmath>
#include <mutex>
#include <shared_mutex>
#include <stdexcept>
#include <unordered_map>

#include "core/subdiv/refine.h"

namespace fb::subdiv {
namespace {

namespace Bfr = OpenSubdiv::Bfr;

// Faces are evaluated in parallel; they share the factory's cache of irregular patches.
using Factory = Bfr::RefinerSurfaceFactory<Bfr::SurfaceFactoryCacheThreaded<
    std::shared_mutex, std::shared_lock<std::shared_mutex>, std::unique_lock<std::shared_mutex>>>;

uint64_t edge_key(uint32_t a, uint32_t b) {
  return (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

// The rate - 1 inner points of one cage edge: at consecutive indices from `first`, in order from
// vertex `from`, made by the face that meets the edge first.
struct SharedEdge {
  uint32_t rate;
  uint32_t first = UINT32_MAX;
  uint32_t from = 0;
  uint32_t owner = 0;  // the face that evaluates them
};

// Where one face's output goes: its interior points and its triangles.
struct FaceLayout {
  uint32_t interior_first;
  uint64_t facet_first;
};

struct Scratch {
  Bfr::Surface<float> surface;
  std::vector<float> patch_points, coords;
  std::vector<int> rates, facets, boundary;
};

}  // namespace

// Bfr (OpenSubdiv 3.5) evaluates each face's limit surface directly; a Tessellation with one rate
// per edge puts rate - 1 evenly spaced points inside each edge, so two faces that give a shared
// edge the same rate meet at the same points, and evaluating them once, by one of the faces
// (rather than by each), leaves no crack, not even of rounding size.
Triangles tessellate(const Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage,
                     const uint32_t* edge_rates, uint32_t quality, uint64_t max_triangles) {
  // Blender (intern/opensubdiv) isolates irregular and semi-sharp features `quality` levels deep
  // before fitting patches; Bfr's approximation levels are that isolation. Measured against
  // Blender 3.4's evaluated meshes (tests/blender/blender_subdiv_test.cpp): within 1.2e-7 m on
  // 2 m cages, except at smooth boundary corners, where Blender's end patches differ.
  Bfr::SurfaceFactory::Options factory_options;
  factory_options.SetApproxLevelSmooth(int(quality)).SetApproxLevelSharp(int(quality));
  const Factory factory(refiner, factory_options);
  const Bfr::Tessellation::Options options;  // triangles, (u, v) pairs

  // Sequentially: the rates agree along every edge, every shared point (cage corner, edge
  // interior) gets its index and the face that evaluates it, every face its output ranges.
  std::vector<uint32_t> first_face(cage.face_count + 1, 0);  // into face_vertices
  for (uint32_t f = 0; f < cage.face_count; ++f)
    first_face[f + 1] = first_face[f] + cage.face_sizes[f];
  std::unordered_map<uint64_t, SharedEdge> edges;
  std::vector<uint32_t> corner(cage.vertex_count, UINT32_MAX), corner_owner(cage.vertex_count);
  std::vector<FaceLayout> layout(cage.face_count);
  uint64_t points = 0, triangles = 0;
  std::vector<int> rates;
  std::vector<uint32_t> interior(cage.face_count);
  for (uint32_t f = 0; f < cage.face_count; ++f) {
    const uint32_t n = cage.face_sizes[f], first = first_face[f];
    rates.assign(edge_rates + first, edge_rates + first + n);
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t a = cage.face_vertices[first + k], b = cage.face_vertices[first + (k + 1) % n];
      if (corner[a] == UINT32_MAX) corner[a] = uint32_t(points++), corner_owner[a] = f;
      const auto [it, fresh] = edges.try_emplace(edge_key(a, b), SharedEdge{uint32_t(rates[k])});
      SharedEdge& edge = it->second;
      if (fresh) {
        edge.first = uint32_t(points), edge.from = a, edge.owner = f;
        points += edge.rate - 1;
      } else if (edge.rate != uint32_t(rates[k])) {
        throw std::runtime_error("the two faces of the edge " + std::to_string(a) + "-" +
                                 std::to_string(b) + " ask for different rates; they would crack");
      }
    }
    const Bfr::Tessellation pattern(Bfr::Parameterization(refiner.GetSchemeType(), int(n)), int(n),
                                    rates.data(), options);
    if (!pattern.IsValid()) throw std::runtime_error("invalid tessellation rates");
    interior[f] = uint32_t(pattern.GetNumInteriorCoords());
    layout[f].facet_first = triangles;
    triangles += uint64_t(pattern.GetNumFacets());
    if (points > INT32_MAX) throw std::runtime_error("more than 2^31 points");
  }
  if (triangles > max_triangles)
    throw std::runtime_error("the tessellation makes " + std::to_string(triangles) +
                             " triangles, more than the limit of " + std::to_string(max_triangles));
  for (uint32_t f = 0; f < cage.face_count; ++f) {
    layout[f].interior_first = uint32_t(points);
    points += interior[f];
    if (points > INT32_MAX) throw std::runtime_error("more than 2^31 points");
  }

  Triangles out;
  out.positions.resize(3 * points);
  out.normals.resize(3 * points);
  out.indices.resize(3 * triangles);
  tbb::enumerable_thread_specific<Scratch> scratch;
  tbb::parallel_for(uint32_t(0), cage.face_count, [&](uint32_t f) {
    Scratch& s = scratch.local();
    Bfr::Surface<float>& surface = s.surface;
    const uint32_t n = cage.face_sizes[f], first = first_face[f];
    if (!factory.InitVertexSurface(int(f), &surface))
      throw std::runtime_error("OpenSubdiv cannot evaluate the limit surface of face " +
                               std::to_string(f));
    s.rates.assign(edge_rates + first, edge_rates + first + n);
    Bfr::Tessellation pattern(surface.GetParameterization(), int(n), s.rates.data(), options);
    const Bfr::Surface<float>::PointDescriptor point3(3);
    s.patch_points.resize(size_t(surface.GetNumPatchPoints()) * 3);
    surface.PreparePatchPoints(cage.positions, point3, s.patch_points.data(), point3);
    s.coords.resize(size_t(pattern.GetNumCoords()) * 2);
    pattern.GetCoords(s.coords.data());
    const auto emit = [&](const float uv[2], uint32_t index) {
      float p[3], du[3], dv[3];
      surface.Evaluate(uv, s.patch_points.data(), point3, p, du, dv);
      float nrm[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2],
                      du[0] * dv[1] - du[1] * dv[0]};
      float len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
      if (!(len > 0)) {
        // At an extraordinary corner the parametrisation degenerates (one derivative vanishes):
        // take the normal a little way towards the face's centre.
        float centre[2], near[2], q[3];
        surface.GetParameterization().GetCenterCoord(centre);
        for (int i = 0; i < 2; ++i)
          near[i] = uv[i] + 1e-3f * (centre[i] - uv[i]);
        surface.Evaluate(near, s.patch_points.data(), point3, q, du, dv);
        nrm[0] = du[1] * dv[2] - du[2] * dv[1], nrm[1] = du[2] * dv[0] - du[0] * dv[2],
        nrm[2] = du[0] * dv[1] - du[1] * dv[0];
        len = std::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
      }
      for (int i = 0; i < 3; ++i) {
        out.positions[3 * size_t(index) + i] = p[i];
        out.normals[3 * size_t(index) + i] = len > 0 ? nrm[i] / len : 0;
      }
    };
    // Boundary coordinates come first, counter-clockwise from vertex 0: each corner, then the
    // inner points of the edge that leaves it.
    s.boundary.assign(size_t(pattern.GetNumBoundaryCoords()), 0);
    size_t b = 0;
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t a = cage.face_vertices[first + k], c = cage.face_vertices[first + (k + 1) % n];
      if (corner_owner[a] == f) emit(&s.coords[2 * b], corner[a]);
      s.boundary[b++] = int(corner[a]);
      const SharedEdge& edge = edges.at(edge_key(a, c));
      const uint32_t inner = uint32_t(s.rates[k]) - 1;
      for (uint32_t i = 0; i < inner; ++i) {
        const uint32_t index = edge.from == a ? edge.first + i : edge.first + inner - 1 - i;
        if (edge.owner == f) emit(&s.coords[2 * (b + i)], index);
        s.boundary[b + i] = int(index);
      }
      b += inner;
    }
    for (size_t i = b; i < size_t(pattern.GetNumCoords()); ++i)
      emit(&s.coords[2 * i], layout[f].interior_first + uint32_t(i - b));
    s.facets.resize(size_t(pattern.GetNumFacets()) * 3);
    pattern.GetFacets(s.facets.data());
    pattern.TransformFacetCoordIndices(s.facets.data(), s.boundary.data(),
                                       int(layout[f].interior_first) - int(b));
    std::copy(s.facets.begin(), s.facets.end(),
              out.indices.begin() + ptrdiff_t(3 * layout[f].facet_first));
  });
  return out;
}

}  // namespace fb::subdiv
