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

// The bytes of element i of a checked accessor: in the file's buffer, or in `owned` when the
// accessor is sparse (its base with the sparse values written over it).
struct AccessorView {
  const unsigned char* data;
  size_t stride;
  size_t count;
  std::vector<unsigned char> owned;
  const unsigned char* element(size_t i) const {
    return (owned.empty() ? data : owned.data()) + i * stride;
  }
};

// A sparse accessor without a bufferView is zeros under its sparse values (glTF 2.0 §3.6.2.3):
// its count is bounded here, as no buffer bounds it.
constexpr size_t kMaxSparseZeroElements = size_t(1) << 24;

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

const tinygltf::Accessor& checked_accessor(const AccessorContext& ctx, int index,
                                           const std::string& where) {
  if (index < 0 || size_t(index) >= ctx.model.accessors.size())
    throw_input(ctx.file, where,
                "accessor index " + std::to_string(index) + " is out of range (the file has " +
                    std::to_string(ctx.model.accessors.size()) + " accessors)");
  return ctx.model.accessors[size_t(index)];
}

// `count` elements of `element_size` bytes, `byte_offset` into bufferViews[buffer_view], at the
// view's byteStride when `strided` (else tightly packed), checked to lie inside the view and its
// buffer; `path` names the referring element for messages.
AccessorView buffer_view_bytes(const AccessorContext& ctx, int buffer_view, size_t byte_offset,
                               size_t count, size_t element_size, bool strided,
                               const std::string& path) {
  if (buffer_view < 0 || size_t(buffer_view) >= ctx.model.bufferViews.size())
    throw_input(ctx.file, path,
                "bufferView index " + std::to_string(buffer_view) +
                    " is out of range (the file has " +
                    std::to_string(ctx.model.bufferViews.size()) + " bufferViews)");
  const tinygltf::BufferView& bv = ctx.model.bufferViews[size_t(buffer_view)];
  const std::string bv_path = "bufferViews[" + std::to_string(buffer_view) + "]";
  if (bv.buffer < 0 || size_t(bv.buffer) >= ctx.model.buffers.size())
    throw_input(ctx.file, bv_path,
                "buffer index " + std::to_string(bv.buffer) + " is out of range (the file has " +
                    std::to_string(ctx.model.buffers.size()) + " buffers)");
  const size_t buffer_size = ctx.model.buffers[size_t(bv.buffer)].data.size();
  const size_t stride = strided && bv.byteStride ? bv.byteStride : element_size;
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
  if (byte_offset > available || available - byte_offset < element_size ||
      count - 1 > (available - byte_offset - element_size) / stride)
    throw_input(ctx.file, path,
                std::to_string(count) + " elements of " + std::to_string(element_size) +
                    " bytes at offset " + std::to_string(byte_offset) + " with stride " +
                    std::to_string(stride) + " do not fit in " + bv_path + " (" +
                    std::to_string(available) + " bytes)");
  return {ctx.model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + byte_offset,
          stride,
          count,
          {}};
}

// A sparse accessor (glTF 2.0 §3.6.2.3) made dense: its base (the bufferView's elements, or
// zeros), then each of `sparse.count` values written at its index. The indices must increase
// strictly (the specification's rule, which also keeps them distinct) and lie below the
// accessor's count; float values must be finite, named by their place in `sparse.values`.
AccessorView sparse_view(const AccessorContext& ctx, int accessor, size_t element_size,
                         const std::string& path) {
  const tinygltf::Accessor& a = ctx.model.accessors[size_t(accessor)];
  const std::string sparse_path = "accessors[" + std::to_string(accessor) + "].sparse";
  if (a.sparse.count < 1 || size_t(a.sparse.count) > a.count)
    throw_input(ctx.file, sparse_path + ".count",
                std::to_string(a.sparse.count) + ", expected 1 to the accessor's count (" +
                    std::to_string(a.count) + ")");
  if (a.bufferView < 0 && a.count > kMaxSparseZeroElements)
    throw_input(ctx.file, path,
                std::to_string(a.count) + " elements without a bufferView; at most " +
                    std::to_string(kMaxSparseZeroElements));
  if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
    throw_input(ctx.file, sparse_path, "a negative byteOffset");
  AccessorView out{nullptr, element_size, a.count, {}};
  if (a.bufferView >= 0) {
    const AccessorView base =
        buffer_view_bytes(ctx, a.bufferView, a.byteOffset, a.count, element_size, true, path);
    out.owned.resize(a.count * element_size);
    for (size_t i = 0; i < a.count; ++i)
      std::memcpy(out.owned.data() + i * element_size, base.element(i), element_size);
  } else {
    out.owned.assign(a.count * element_size, 0);
  }
  const int index_type = a.sparse.indices.componentType;
  const size_t index_size = index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                    index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                                    index_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT
                                ? component_size(index_type)
                                : 0;
  if (index_size == 0)
    throw_input(ctx.file, sparse_path + ".indices.componentType",
                std::to_string(index_type) +
                    ", expected 5121, 5123 or 5125 (unsigned byte, "
                    "short or int)");
  const size_t count = size_t(a.sparse.count);
  const AccessorView indices =
      buffer_view_bytes(ctx, a.sparse.indices.bufferView, size_t(a.sparse.indices.byteOffset),
                        count, index_size, false, sparse_path + ".indices");
  const AccessorView values =
      buffer_view_bytes(ctx, a.sparse.values.bufferView, size_t(a.sparse.values.byteOffset), count,
                        element_size, false, sparse_path + ".values");
  const size_t components = size_t(tinygltf::GetNumComponentsInType(a.type));
  for (size_t k = 0; k < count; ++k) {
    const uint32_t index = unsigned_component(indices.element(k), index_type);
    if (index >= a.count)
      throw_input(ctx.file, sparse_path + ".indices",
                  "element " + std::to_string(k) + " is " + std::to_string(index) +
                      ", past the accessor's " + std::to_string(a.count) + " elements");
    if (k > 0 && index <= unsigned_component(indices.element(k - 1), index_type))
      throw_input(ctx.file, sparse_path + ".indices",
                  "element " + std::to_string(k) + " is " + std::to_string(index) +
                      ", not above the one before it (sparse indices must increase strictly)");
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
      for (size_t c = 0; c < components; ++c) {
        float f;
        std::memcpy(&f, values.element(k) + c * 4, 4);
        if (!std::isfinite(f))
          throw_input(ctx.file, sparse_path + ".values",
                      "element " + std::to_string(k) + " (for element " + std::to_string(index) +
                          ") is not a finite number");
      }
    std::memcpy(out.owned.data() + size_t(index) * element_size, values.element(k), element_size);
  }
  return out;
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
  const size_t element_size =
      component_size(a.componentType) * size_t(tinygltf::GetNumComponentsInType(a.type));
  if (a.count == 0) return {nullptr, 0, 0, {}};
  if (a.sparse.isSparse) return sparse_view(ctx, index, element_size, path);
  if (a.bufferView < 0)
    throw_input(ctx.file, path,
                "no bufferView (glTF's all-zero accessor) is not supported here; expected data");
  return buffer_view_bytes(ctx, a.bufferView, a.byteOffset, a.count, element_size, true, path);
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
