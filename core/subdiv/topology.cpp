#include <opensubdiv/far/error.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <stdexcept>

#include "core/subdiv/refine.h"

namespace fb::subdiv {
namespace {

namespace Sdc = OpenSubdiv::Sdc;

// Far reports a malformed topology through a global callback before Create() returns null.
thread_local std::string far_error;
void keep_far_error(Far::ErrorType, const char* message) {
  far_error = message;
}

}  // namespace

std::unique_ptr<Far::TopologyRefiner> make_refiner(const fb_subdiv_cage& cage) {
  // Far wants ints; the core has checked every index against the counts.
  const std::vector<int> sizes(cage.face_sizes, cage.face_sizes + cage.face_count);
  size_t total = 0;
  for (uint32_t n : sizes)
    total += n;
  const std::vector<int> vertices(cage.face_vertices, cage.face_vertices + total);
  const std::vector<int> crease_pairs(cage.crease_edges,
                                      cage.crease_edges + 2 * size_t(cage.crease_edge_count));
  const std::vector<int> corners(cage.crease_vertices,
                                 cage.crease_vertices + cage.crease_vertex_count);

  Far::TopologyDescriptor d;
  d.numVertices = int(cage.vertex_count);
  d.numFaces = int(cage.face_count);
  d.numVertsPerFace = sizes.data();
  d.vertIndicesPerFace = vertices.data();
  d.numCreases = int(cage.crease_edge_count);
  d.creaseVertexIndexPairs = crease_pairs.data();
  d.creaseWeights = cage.crease_edge_sharpness;
  d.numCorners = int(cage.crease_vertex_count);
  d.cornerVertexIndices = corners.data();
  d.cornerWeights = cage.crease_vertex_sharpness;
  // Each texture-coordinate channel as a face-varying channel: one value index per face corner.
  std::vector<std::vector<int>> corner_values(cage.uv_channel_count);
  std::vector<Far::TopologyDescriptor::FVarChannel> channels(cage.uv_channel_count);
  for (uint32_t c = 0; c < cage.uv_channel_count; ++c) {
    const fb_subdiv_uv_channel& channel = cage.uv_channels[c];
    corner_values[c].assign(channel.corner_values, channel.corner_values + total);
    channels[c].numValues = int(channel.value_count);
    channels[c].valueIndices = corner_values[c].data();
  }
  d.numFVarChannels = int(cage.uv_channel_count);
  d.fvarChannels = channels.data();

  // Blender's settings (intern/opensubdiv, BKE_subdiv_settings_init_from_modifier): the default
  // (uniform) creasing and Catmark triangle rule; the boundary rule and the face-varying one are
  // the modifier's (the core maps uv_smooth as BKE_subdiv_fvar_interpolation_from_uv_smooth).
  Sdc::Options options;
  options.SetFVarLinearInterpolation(Sdc::Options::FVarLinearInterpolation(cage.fvar_linear));
  options.SetVtxBoundaryInterpolation(cage.boundary == FB_SUBDIV_BOUNDARY_EDGE_AND_CORNER
                                          ? Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                          : Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  const Sdc::SchemeType scheme =
      cage.scheme == FB_SUBDIV_BILINEAR ? Sdc::SCHEME_BILINEAR : Sdc::SCHEME_CATMARK;
  far_error.clear();
  Far::SetErrorCallback(keep_far_error);
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Create(
          d, Far::TopologyRefinerFactory<Far::TopologyDescriptor>::Options(scheme, options)));
  Far::SetErrorCallback(nullptr);
  if (!refiner)
    throw std::runtime_error("OpenSubdiv cannot build the cage's topology" +
                             (far_error.empty() ? std::string() : ": " + far_error));
  return refiner;
}

}  // namespace fb::subdiv
