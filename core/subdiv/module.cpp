// libfilmback_subdiv.so's two exported functions (subdiv_module.h). No C++ exception crosses
// them: every failure becomes the mesh's error text and a non-zero return.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>

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

extern "C" __attribute__((visibility("default"))) int filmback_subdiv_refine(
    const fb_subdiv_cage* cage, const fb_subdiv_request* request, fb_subdiv_mesh* out) {
  *out = fb_subdiv_mesh{};
  try {
    if (cage->struct_size < sizeof(fb_subdiv_cage) || cage->abi_version != FB_SUBDIV_ABI_VERSION ||
        request->struct_size < sizeof(fb_subdiv_request))
      throw std::runtime_error("the caller was built for another version of this module");
    auto refiner = fb::subdiv::make_refiner(*cage);
    const fb::subdiv::Triangles t =
        request->cage_limit ? fb::subdiv::cage_limit(*refiner, *cage)
        : request->edge_rates
            ? fb::subdiv::tessellate(*refiner, *cage, request->edge_rates, request->quality,
                                     request->max_triangles)
            : fb::subdiv::refine_uniform(*refiner, *cage, request->level, request->max_triangles);
    out->positions = copy_out(t.positions);
    out->normals = copy_out(t.normals);
    out->indices = copy_out(t.indices);
    out->vertex_count = t.positions.size() / 3;
    out->triangle_count = t.indices.size() / 3;
    return 0;
  } catch (const std::bad_alloc&) {
    std::snprintf(out->error, sizeof out->error, "out of memory");
  } catch (const std::exception& e) {
    std::snprintf(out->error, sizeof out->error, "%s", e.what());
  }
  std::free(out->positions), std::free(out->normals), std::free(out->indices);
  out->positions = out->normals = nullptr, out->indices = nullptr;
  return 1;
}

extern "C" __attribute__((visibility("default"))) void filmback_subdiv_free(fb_subdiv_mesh* mesh) {
  std::free(mesh->positions), std::free(mesh->normals), std::free(mesh->indices);
  mesh->positions = mesh->normals = nullptr, mesh->indices = nullptr;
}
