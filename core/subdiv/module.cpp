// libfilmback_subdiv.so's two exported functions (subdiv_module.h). No C++ exception crosses
// them: every failure becomes the mesh's error text and a non-zero return.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "core/subdiv/refine.h"

namespace {

template <typename T>
T* copy_out(const std::vector<T>& v) {
  if (v.empty()) return nullptr;
  T* p = static_cast<T*>(std::malloc(v.size() * sizeof(T)));
  if (!p) throw std::bad_alloc();
  std::memcpy(p, v.data(), v.size() * sizeof(T));
  return p;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) void filmback_subdiv_free(fb_subdiv_mesh* mesh) {
  for (float* p : {mesh->positions, mesh->normals, mesh->uvs})
    std::free(p);
  std::free(mesh->indices), std::free(mesh->triangle_faces);
  mesh->positions = mesh->normals = mesh->uvs = nullptr;
  mesh->indices = mesh->triangle_faces = nullptr;
}

extern "C" __attribute__((visibility("default"))) int filmback_subdiv_refine(
    const fb_subdiv_cage* cage, const fb_subdiv_request* request, fb_subdiv_mesh* out) {
  *out = fb_subdiv_mesh{};
  try {
    if (cage->struct_size < sizeof(fb_subdiv_cage) || cage->abi_version != FB_SUBDIV_ABI_VERSION ||
        request->struct_size < sizeof(fb_subdiv_request))
      throw std::runtime_error("the caller was built for another version of this module");
    if (cage->fvar_linear > FB_SUBDIV_FVAR_LINEAR_ALL)
      throw std::runtime_error("unknown face-varying interpolation " +
                               std::to_string(cage->fvar_linear));
    const bool faces = request->triangle_faces != 0;
    const bool polygon_normals = request->polygon_normals != 0;
    auto refiner = fb::subdiv::make_refiner(*cage);
    const fb::subdiv::Triangles t =
        request->cage_limit ? fb::subdiv::cage_limit(*refiner, *cage)
        : request->edge_rates
            ? fb::subdiv::tessellate(*refiner, *cage, request->edge_rates, request->quality,
                                     request->max_triangles, faces, polygon_normals)
            : fb::subdiv::refine_uniform(*refiner, *cage, request->level, request->max_triangles,
                                         faces, polygon_normals);
    out->positions = copy_out(t.positions);
    out->normals = copy_out(t.normals);
    out->uvs = copy_out(t.uvs);
    out->indices = copy_out(t.indices);
    out->triangle_faces = copy_out(t.triangle_faces);
    out->vertex_count = t.positions.size() / 3;
    out->triangle_count = t.indices.size() / 3;
    return 0;
  } catch (const std::bad_alloc&) {
    std::snprintf(out->error, sizeof out->error, "out of memory");
  } catch (const std::exception& e) {
    std::snprintf(out->error, sizeof out->error, "%s", e.what());
  }
  filmback_subdiv_free(out);
  return 1;
}
