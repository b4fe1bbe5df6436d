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

constexpr uint32_t kNoFace = UINT32_MAX;

// The rate - 1 inner points of one cage edge: at consecutive indices from `first`, in order from
// vertex `from`, made by the face that meets the edge first. A face meeting it with other UV
// values at either end (a seam) makes its own inner points, positions copied from these.
struct SharedEdge {
  uint32_t rate;
  uint32_t first = UINT32_MAX;
  uint32_t from = 0;
  uint32_t from_corner = 0, to_corner = 0;  // the owner's corner vertices (CornerSplitter ids)
};

// Where one face's output goes: its interior points and its triangles.
struct FaceLayout {
  uint32_t interior_first;
  uint64_t facet_first;
};

// Per entry of face_vertices: the output vertex of that corner, and the inner points of the edge
// that leaves it as this face sees them.
struct FaceEdge {
  uint32_t corner;
  uint32_t first;
  bool reversed;  // the points run from the edge's far end
};

// The points on cage corners and edges (the first `boundary` outputs) are evaluated by one face
// each: position by `position_face` (kNoFace: copied from another output after the evaluation),
// texture coordinates by `uv_face`.
struct Owners {
  std::vector<uint32_t> position_face, uv_face;
  std::vector<std::pair<uint32_t, uint32_t>> copies;  // (to, from): one surface point, split
  uint32_t add(uint32_t position_face_, uint32_t uv_face_) {
    position_face.push_back(position_face_);
    uv_face.push_back(uv_face_);
    return uint32_t(uv_face.size() - 1);
  }
};

struct Scratch {
  Bfr::Surface<float> surface;
  std::vector<Bfr::Surface<float>> uv_surfaces;
  std::vector<float> patch_points, uv_patch_points, coords;
  std::vector<int> rates, facets, boundary, quads;
};

}  // namespace

// Bfr (OpenSubdiv 3.5) evaluates each face's limit surface directly; a Tessellation with one rate
// per edge puts rate - 1 evenly spaced points inside each edge, so two faces that give a shared
// edge the same rate meet at the same points, and evaluating them once, by one of the faces
// (rather than by each), leaves no crack, not even of rounding size. Texture coordinates are
// Bfr's face-varying surfaces evaluated at the same parameters; where a channel has a seam the
// output vertex is split, and the copies take the one evaluated position.
Triangles tessellate(const Far::TopologyRefiner& refiner, const fb_subdiv_cage& cage,
                     const uint32_t* edge_rates, uint32_t quality, uint64_t max_triangles,
                     bool triangle_faces, bool polygon_normals) {
  // Blender (intern/opensubdiv) isolates irregular and semi-sharp features `quality` levels deep
  // before fitting patches; Bfr's approximation levels are that isolation. Measured against
  // Blender 3.4's evaluated meshes (tests/blender/blender_subdiv_test.cpp): within 1.2e-7 m on
  // 2 m cages, except at smooth boundary corners, where Blender's end patches differ.
  Bfr::SurfaceFactory::Options factory_options;
  factory_options.SetApproxLevelSmooth(int(quality)).SetApproxLevelSharp(int(quality));
  const Factory factory(refiner, factory_options);
  const Bfr::Tessellation::Options options;  // triangles, (u, v) pairs
  // The same points joined into quads where the pattern has them (every facet, with uniform
  // rates): the polygons whose normals Blender averages (polygon_normals).
  Bfr::Tessellation::Options quad_options;
  quad_options.SetFacetSize(4).PreserveQuads(true);
  std::vector<std::vector<uint32_t>> face_polygons(polygon_normals ? cage.face_count : 0);
  const uint32_t channels = cage.uv_channel_count;

  // Sequentially: the rates agree along every edge, every shared point (cage corner, edge
  // interior) gets its index and the faces that evaluate it, every face its output ranges.
  std::vector<uint32_t> first_face(cage.face_count + 1, 0);  // into face_vertices
  for (uint32_t f = 0; f < cage.face_count; ++f)
    first_face[f + 1] = first_face[f] + cage.face_sizes[f];
  std::unordered_map<uint64_t, SharedEdge> edges;
  CornerSplitter corners(cage.vertex_count, channels);
  std::vector<uint32_t> corner_output, values(channels);
  std::vector<uint32_t> vertex_output(cage.vertex_count, UINT32_MAX);  // its position's output
  std::vector<FaceEdge> face_edges(first_face[cage.face_count]);
  std::vector<FaceLayout> layout(cage.face_count);
  Owners owners;
  uint64_t triangles = 0;
  std::vector<int> rates;
  std::vector<uint32_t> interior(cage.face_count);
  for (uint32_t f = 0; f < cage.face_count; ++f) {
    const uint32_t n = cage.face_sizes[f], first = first_face[f];
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t a = cage.face_vertices[first + k];
      for (uint32_t c = 0; c < channels; ++c)
        values[c] = cage.uv_channels[c].corner_values[first + k];
      bool fresh;
      const uint32_t id = corners.add(a, values.data(), fresh);
      if (fresh) {
        // The first corner of a vertex evaluates its position; one split off it copies it.
        const bool first_of_vertex = vertex_output[a] == UINT32_MAX;
        corner_output.push_back(owners.add(first_of_vertex ? f : kNoFace, f));
        if (first_of_vertex)
          vertex_output[a] = corner_output.back();
        else
          owners.copies.push_back({corner_output.back(), vertex_output[a]});
      }
      face_edges[first + k].corner = id;
    }
    rates.assign(edge_rates + first, edge_rates + first + n);
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t a = cage.face_vertices[first + k], b = cage.face_vertices[first + (k + 1) % n];
      const uint32_t ca = face_edges[first + k].corner, cb = face_edges[first + (k + 1) % n].corner;
      const auto [it, fresh] = edges.try_emplace(edge_key(a, b), SharedEdge{uint32_t(rates[k])});
      SharedEdge& edge = it->second;
      const uint32_t inner = edge.rate - 1;
      FaceEdge& here = face_edges[first + k];
      if (!fresh && edge.rate != uint32_t(rates[k]))
        throw std::runtime_error("the two faces of the edge " + std::to_string(a) + "-" +
                                 std::to_string(b) + " ask for different rates; they would crack");
      if (fresh) {
        edge.first = uint32_t(owners.uv_face.size()), edge.from = a;
        edge.from_corner = ca, edge.to_corner = cb;
        for (uint32_t i = 0; i < inner; ++i)
          owners.add(f, f);
        here.first = edge.first, here.reversed = false;
      } else if (edge.from == a ? edge.from_corner == ca && edge.to_corner == cb
                                : edge.from_corner == cb && edge.to_corner == ca) {
        here.first = edge.first, here.reversed = edge.from != a;  // the same points
      } else {
        // A seam: this face's own points along the edge, in its direction, at the same places.
        here.first = uint32_t(owners.uv_face.size()), here.reversed = false;
        for (uint32_t i = 0; i < inner; ++i)
          owners.copies.push_back({owners.add(kNoFace, f),
                                   edge.from == a ? edge.first + i : edge.first + inner - 1 - i});
      }
      if (owners.uv_face.size() > INT32_MAX) throw std::runtime_error("more than 2^31 points");
    }
    const Bfr::Tessellation pattern(Bfr::Parameterization(refiner.GetSchemeType(), int(n)), int(n),
                                    rates.data(), options);
    if (!pattern.IsValid()) throw std::runtime_error("invalid tessellation rates");
    interior[f] = uint32_t(pattern.GetNumInteriorCoords());
    layout[f].facet_first = triangles;
    triangles += uint64_t(pattern.GetNumFacets());
  }
  for (FaceEdge& e : face_edges)
    e.corner = corner_output[e.corner];
  if (triangles > max_triangles)
    throw std::runtime_error("the tessellation makes " + std::to_string(triangles) +
                             " triangles, more than the limit of " + std::to_string(max_triangles));
  const uint32_t boundary = uint32_t(owners.uv_face.size());
  uint64_t points = boundary;
  for (uint32_t f = 0; f < cage.face_count; ++f) {
    layout[f].interior_first = uint32_t(points);
    points += interior[f];
    if (points > INT32_MAX) throw std::runtime_error("more than 2^31 points");
  }

  Triangles out;
  out.positions.resize(3 * points);
  out.normals.resize(3 * points);
  out.uvs.resize(2 * channels * points);
  out.indices.resize(3 * triangles);
  if (triangle_faces) out.triangle_faces.resize(triangles);
  tbb::enumerable_thread_specific<Scratch> scratch;
  tbb::parallel_for(uint32_t(0), cage.face_count, [&](uint32_t f) {
    Scratch& s = scratch.local();
    Bfr::Surface<float>& surface = s.surface;
    s.uv_surfaces.resize(channels);
    const uint32_t n = cage.face_sizes[f], first = first_face[f];
    std::vector<Bfr::SurfaceFactory::FVarID> ids(channels);  // the channels' indices
    for (uint32_t c = 0; c < channels; ++c)
      ids[c] = int(c);
    if (!factory.InitSurfaces(int(f), &surface, s.uv_surfaces.data(), ids.data(), int(channels)))
      throw std::runtime_error("OpenSubdiv cannot evaluate the limit surface of face " +
                               std::to_string(f));
    s.rates.assign(edge_rates + first, edge_rates + first + n);
    Bfr::Tessellation pattern(surface.GetParameterization(), int(n), s.rates.data(), options);
    const Bfr::Surface<float>::PointDescriptor point3(3), point2(2);
    s.patch_points.resize(size_t(surface.GetNumPatchPoints()) * 3);
    surface.PreparePatchPoints(cage.positions, point3, s.patch_points.data(), point3);
    // Each channel's patch points, one block after another.
    std::vector<size_t> uv_patch_first(channels + 1, 0);
    for (uint32_t c = 0; c < channels; ++c)
      uv_patch_first[c + 1] = uv_patch_first[c] + 2 * size_t(s.uv_surfaces[c].GetNumPatchPoints());
    s.uv_patch_points.resize(uv_patch_first[channels]);
    for (uint32_t c = 0; c < channels; ++c)
      s.uv_surfaces[c].PreparePatchPoints(cage.uv_channels[c].values, point2,
                                          s.uv_patch_points.data() + uv_patch_first[c], point2);
    s.coords.resize(size_t(pattern.GetNumCoords()) * 2);
    pattern.GetCoords(s.coords.data());
    const auto evaluate_position = [&](const float uv[2], uint32_t index) {
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
    const auto evaluate_uvs = [&](const float uv[2], uint32_t index) {
      for (uint32_t c = 0; c < channels; ++c)
        s.uv_surfaces[c].Evaluate(uv, s.uv_patch_points.data() + uv_patch_first[c], point2,
                                  &out.uvs[2 * (c * points + index)]);
    };
    const auto emit = [&](const float uv[2], uint32_t index) {
      if (index >= boundary || owners.position_face[index] == f) evaluate_position(uv, index);
      if (index >= boundary || owners.uv_face[index] == f) evaluate_uvs(uv, index);
    };
    // Boundary coordinates come first, counter-clockwise from vertex 0: each corner, then the
    // inner points of the edge that leaves it.
    s.boundary.assign(size_t(pattern.GetNumBoundaryCoords()), 0);
    size_t b = 0;
    for (uint32_t k = 0; k < n; ++k) {
      const FaceEdge& e = face_edges[first + k];
      emit(&s.coords[2 * b], e.corner);
      s.boundary[b++] = int(e.corner);
      const uint32_t inner = uint32_t(s.rates[k]) - 1;
      for (uint32_t i = 0; i < inner; ++i) {
        const uint32_t index = e.reversed ? e.first + inner - 1 - i : e.first + i;
        emit(&s.coords[2 * (b + i)], index);
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
    if (triangle_faces)
      std::fill_n(out.triangle_faces.begin() + ptrdiff_t(layout[f].facet_first),
                  pattern.GetNumFacets(), f);
    if (polygon_normals) {
      Bfr::Tessellation quads(surface.GetParameterization(), int(n), s.rates.data(), quad_options);
      if (quads.GetNumCoords() != pattern.GetNumCoords())
        throw std::runtime_error("the quad tessellation of face " + std::to_string(f) +
                                 " has other points than the triangles'");
      s.quads.resize(size_t(quads.GetNumFacets()) * 4);
      quads.GetFacets(s.quads.data());
      quads.TransformFacetCoordIndices(s.quads.data(), s.boundary.data(),
                                       int(layout[f].interior_first) - int(b));
      std::vector<uint32_t>& polygons = face_polygons[f];
      for (size_t q = 0; q < s.quads.size(); q += 4) {
        const uint32_t corners = s.quads[q + 3] < 0 ? 3 : 4;  // a triangle's fourth index is -1
        polygons.push_back(corners);
        for (uint32_t k = 0; k < corners; ++k)
          polygons.push_back(uint32_t(s.quads[q + k]));
      }
    }
  });
  // The split points of a seam take the position evaluated once, so the surface stays closed.
  for (const auto& [to, from] : owners.copies)
    for (int i = 0; i < 3; ++i) {
      out.positions[3 * size_t(to) + i] = out.positions[3 * size_t(from) + i];
      out.normals[3 * size_t(to) + i] = out.normals[3 * size_t(from) + i];
    }
  if (polygon_normals) {
    std::vector<uint32_t> polygons, owner(points);
    for (const std::vector<uint32_t>& face : face_polygons)
      polygons.insert(polygons.end(), face.begin(), face.end());
    for (uint32_t v = 0; v < points; ++v)
      owner[v] = v;
    for (const auto& [to, from] : owners.copies)
      owner[to] = from;
    mesh_normals(out.positions, polygons, owner, out.normals);
  }
  return out;
}

}  // namespace fb::subdiv
