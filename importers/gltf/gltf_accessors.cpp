#include "importers/gltf/gltf_accessors.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/util/error.h"

namespace fb::gltf {
namespace {

size_t component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
  }
  return 0;
}

// The accessor "type" as written in the JSON (glTF 2.0 §5.1.3).
const char* type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
  }
  return "unknown";
}

// The bytes of element i of a checked accessor.
struct AccessorView {
  const unsigned char* data;
  size_t stride;
  size_t count;
  const unsigned char* element(size_t i) const { return data + i * stride; }
};

const tinygltf::Accessor& checked_accessor(const AccessorContext& ctx, int index,
                                           const std::string& where) {
  if (index < 0 || size_t(index) >= ctx.model.accessors.size())
    throw_input(ctx.file, where,
                "accessor index " + std::to_string(index) + " is out of range (the file has " +
                    std::to_string(ctx.model.accessors.size()) + " accessors)");
  return ctx.model.accessors[size_t(index)];
}

AccessorView view(const AccessorContext& ctx, int index, const std::string& where, int type,
                  std::initializer_list<int> component_types) {
  const tinygltf::Accessor& a = checked_accessor(ctx, index, where);
  const std::string path = where + " (accessors[" + std::to_string(index) + "])";
  if (a.type != type)
    throw_input(ctx.file, path,
                std::string("type ") + type_name(a.type) + ", expected " + type_name(type));
  bool known = false;
  std::string expected;
  for (int t : component_types) {
    known |= a.componentType == t;
    expected += (expected.empty() ? "" : " or ") + std::to_string(t);
  }
  if (!known)
    throw_input(ctx.file, path,
                "componentType " + std::to_string(a.componentType) + ", expected " + expected);
  if (a.sparse.isSparse) throw_input(ctx.file, path, "sparse accessors are not supported yet");
  if (a.count == 0) return {nullptr, 0, 0};
  if (a.bufferView < 0)
    throw_input(ctx.file, path,
                "no bufferView (glTF's all-zero accessor) is not supported here; expected data");
  if (size_t(a.bufferView) >= ctx.model.bufferViews.size())
    throw_input(ctx.file, path,
                "bufferView index " + std::to_string(a.bufferView) +
                    " is out of range (the file has " +
                    std::to_string(ctx.model.bufferViews.size()) + " bufferViews)");
  const tinygltf::BufferView& bv = ctx.model.bufferViews[size_t(a.bufferView)];
  const std::string bv_path = "bufferViews[" + std::to_string(a.bufferView) + "]";
  if (bv.buffer < 0 || size_t(bv.buffer) >= ctx.model.buffers.size())
    throw_input(ctx.file, bv_path,
                "buffer index " + std::to_string(bv.buffer) + " is out of range (the file has " +
                    std::to_string(ctx.model.buffers.size()) + " buffers)");
  const size_t buffer_size = ctx.model.buffers[size_t(bv.buffer)].data.size();
  const size_t element_size =
      component_size(a.componentType) * size_t(tinygltf::GetNumComponentsInType(a.type));
  const size_t stride = bv.byteStride ? bv.byteStride : element_size;
  if (stride < element_size)
    throw_input(ctx.file, bv_path,
                "byteStride " + std::to_string(stride) + " is smaller than one element (" +
                    std::to_string(element_size) + " bytes)");
  // Overflow-safe: each term is checked against the sizes it must fit in before it is added.
  if (bv.byteOffset > buffer_size || bv.byteLength > buffer_size - bv.byteOffset)
    throw_input(ctx.file, bv_path,
                "bytes " + std::to_string(bv.byteOffset) + "+" + std::to_string(bv.byteLength) +
                    " reach past the end of buffers[" + std::to_string(bv.buffer) + "] (" +
                    std::to_string(buffer_size) + " bytes)");
  const size_t available = bv.byteLength;
  // needs byteOffset + (count - 1) * stride + element_size <= available
  if (a.byteOffset > available || available - a.byteOffset < element_size ||
      a.count - 1 > (available - a.byteOffset - element_size) / stride)
    throw_input(ctx.file, path,
                std::to_string(a.count) + " elements of " + std::to_string(element_size) +
                    " bytes at offset " + std::to_string(a.byteOffset) + " with stride " +
                    std::to_string(stride) + " do not fit in " + bv_path + " (" +
                    std::to_string(available) + " bytes)");
  const unsigned char* base =
      ctx.model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + a.byteOffset;
  return {base, stride, a.count};
}

// An unsigned byte, short or int component at `e`.
uint32_t unsigned_component(const unsigned char* e, int type) {
  if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return e[0];
  if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
    uint16_t s;
    std::memcpy(&s, e, 2);
    return s;
  }
  uint32_t i;
  std::memcpy(&i, e, 4);
  return i;
}

}  // namespace

std::vector<Vec3f> read_vec3(const AccessorContext& ctx, int accessor, const std::string& where) {
  const AccessorView v =
      view(ctx, accessor, where, TINYGLTF_TYPE_VEC3, {TINYGLTF_COMPONENT_TYPE_FLOAT});
  std::vector<Vec3f> out(v.count);
  for (size_t i = 0; i < v.count; ++i) {
    float xyz[3];
    std::memcpy(xyz, v.element(i), sizeof xyz);  // glTF data need not be aligned
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2]))
      throw_input(ctx.file, where + " (accessors[" + std::to_string(accessor) + "])",
                  "element " + std::to_string(i) + " is not a finite number");
    out[i] = Vec3f(xyz);
  }
  return out;
}

std::vector<uint32_t> read_indices(const AccessorContext& ctx, int accessor,
                                   const std::string& where, size_t vertex_count) {
  const AccessorView v =
      view(ctx, accessor, where, TINYGLTF_TYPE_SCALAR,
           {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
  const int type = ctx.model.accessors[size_t(accessor)].componentType;
  std::vector<uint32_t> out(v.count);
  for (size_t i = 0; i < v.count; ++i) {
    const uint32_t index = unsigned_component(v.element(i), type);
    if (index >= vertex_count)
      throw_input(ctx.file, where + " (accessors[" + std::to_string(accessor) + "])",
                  "index " + std::to_string(i) + " is " + std::to_string(index) +
                      ", but there are only " + std::to_string(vertex_count) + " vertices");
    out[i] = index;
  }
  return out;
}

std::vector<double> read_animation_values(const AccessorContext& ctx, int accessor,
                                          const std::string& where, int type,
                                          bool normalized_integers) {
  const AccessorView v =
      normalized_integers
          ? view(ctx, accessor, where, type,
                 {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                  TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT})
          : view(ctx, accessor, where, type, {TINYGLTF_COMPONENT_TYPE_FLOAT});
  const tinygltf::Accessor& a = ctx.model.accessors[size_t(accessor)];
  const std::string path = where + " (accessors[" + std::to_string(accessor) + "])";
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && !a.normalized)
    throw_input(ctx.file, path, "integer values must be normalized here (normalized: true)");
  const size_t width = size_t(tinygltf::GetNumComponentsInType(a.type));
  const size_t size = component_size(a.componentType);
  std::vector<double> out(v.count * width);
  for (size_t i = 0; i < v.count; ++i)
    for (size_t c = 0; c < width; ++c) {
      const unsigned char* e = v.element(i) + c * size;
      double x;
      // glTF 2.0 §3.11: normalized integers map to [-1, 1] or [0, 1].
      switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
          float f;
          std::memcpy(&f, e, 4);
          x = f;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE:
          x = std::max(double(int8_t(e[0])) / 127.0, -1.0);
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          x = double(e[0]) / 255.0;
          break;
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
          int16_t h;
          std::memcpy(&h, e, 2);
          x = std::max(double(h) / 32767.0, -1.0);
          break;
        }
        default: {
          uint16_t h;
          std::memcpy(&h, e, 2);
          x = double(h) / 65535.0;
        }
      }
      if (!std::isfinite(x))
        throw_input(ctx.file, path, "element " + std::to_string(i) + " is not a finite number");
      out[i * width + c] = x;
    }
  return out;
}

std::vector<uint32_t> read_joint_indices(const AccessorContext& ctx, int accessor,
                                         const std::string& where) {
  const AccessorView v =
      view(ctx, accessor, where, TINYGLTF_TYPE_VEC4,
           {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
  const int type = ctx.model.accessors[size_t(accessor)].componentType;
  const size_t size = component_size(type);
  std::vector<uint32_t> out(v.count * 4);
  for (size_t i = 0; i < v.count; ++i)
    for (size_t c = 0; c < 4; ++c)
      out[i * 4 + c] = unsigned_component(v.element(i) + c * size, type);
  return out;
}

}  // namespace fb::gltf
