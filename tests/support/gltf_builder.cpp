#include "support/gltf_builder.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <map>

namespace fb::test {

namespace fs = std::filesystem;

fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path dir = fs::temp_directory_path() / "filmback-tests" /
                 (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = uint32_t(bytes[i]) << 16 |
                       (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0);
    out += kDigits[n >> 18 & 63];
    out += kDigits[n >> 12 & 63];
    out += i + 1 < bytes.size() ? kDigits[n >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

struct GltfBuilder::Impl {
  tinygltf::Model model;

  int add_accessor(const void* data, size_t bytes, int component_type, int type, size_t count) {
    auto& buffer = model.buffers[0].data;
    while (buffer.size() % 4)
      buffer.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), p, p + bytes);
    model.bufferViews.push_back(view);
    tinygltf::Accessor accessor;
    accessor.bufferView = int(model.bufferViews.size() - 1);
    accessor.byteOffset = 0;
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = count;
    model.accessors.push_back(accessor);
    return int(model.accessors.size() - 1);
  }
};

namespace {

// Indices as unsigned bytes, shorts or ints (5121, 5123, 5125), little-endian.
std::vector<unsigned char> index_bytes(const std::vector<uint32_t>& indices, int component_type) {
  std::vector<unsigned char> bytes;
  for (uint32_t i : indices) {
    unsigned char b[4];
    std::memcpy(b, &i, 4);  // little-endian: the low bytes come first
    const size_t n = component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                     : component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                                                                : 4;
    bytes.insert(bytes.end(), b, b + n);
  }
  return bytes;
}

}  // namespace

GltfBuilder::GltfBuilder() : impl_(std::make_unique<Impl>()) {
  impl_->model.buffers.emplace_back();
  impl_->model.scenes.emplace_back();
  impl_->model.defaultScene = 0;
  impl_->model.asset.version = "2.0";
  impl_->model.asset.generator = "filmback tests";
}

GltfBuilder::~GltfBuilder() = default;

int GltfBuilder::material(Rgb base_color, Rgb emission, double emissive_strength,
                          bool double_sided) {
  tinygltf::Material m;
  m.pbrMetallicRoughness.baseColorFactor = {base_color.x, base_color.y, base_color.z, 1.0};
  m.pbrMetallicRoughness.metallicFactor = 0.0;
  // Lambertian: no specular layer (KHR_materials_specular), so tests can use closed forms.
  tinygltf::Value::Object specular;
  specular["specularFactor"] = tinygltf::Value(0.0);
  m.extensions["KHR_materials_specular"] = tinygltf::Value(specular);
  std::vector<std::string>& used = impl_->model.extensionsUsed;
  if (std::find(used.begin(), used.end(), "KHR_materials_specular") == used.end())
    used.push_back("KHR_materials_specular");
  m.emissiveFactor = {emission.x, emission.y, emission.z};
  m.doubleSided = double_sided;
  if (emissive_strength != 1.0) {
    tinygltf::Value::Object strength;
    strength["emissiveStrength"] = tinygltf::Value(emissive_strength);
    m.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(strength);
    impl_->model.extensionsUsed.push_back("KHR_materials_emissive_strength");
  }
  impl_->model.materials.push_back(m);
  return int(impl_->model.materials.size() - 1);
}

int GltfBuilder::mesh(const std::vector<Vec3f>& positions, const std::vector<uint32_t>& indices,
                      int material, int index_component_type, const std::vector<Vec3f>& normals) {
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = material;
  prim.attributes["POSITION"] =
      impl_->add_accessor(positions.data(), positions.size() * sizeof(Vec3f),
                          TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, positions.size());
  if (!normals.empty())
    prim.attributes["NORMAL"] =
        impl_->add_accessor(normals.data(), normals.size() * sizeof(Vec3f),
                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normals.size());
  if (index_component_type > 0) {
    const std::vector<unsigned char> bytes = index_bytes(indices, index_component_type);
    prim.indices = impl_->add_accessor(bytes.data(), bytes.size(), index_component_type,
                                       TINYGLTF_TYPE_SCALAR, indices.size());
  }
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  impl_->model.meshes.push_back(mesh);
  return int(impl_->model.meshes.size() - 1);
}

int GltfBuilder::perspective_camera(double yfov, double aspect_ratio, double znear, double zfar,
                                    const std::string& name) {
  tinygltf::Camera c;
  c.type = "perspective";
  c.name = name;
  c.perspective.yfov = yfov;
  c.perspective.aspectRatio = aspect_ratio;
  c.perspective.znear = znear;
  c.perspective.zfar = zfar;
  impl_->model.cameras.push_back(c);
  return int(impl_->model.cameras.size() - 1);
}

int GltfBuilder::orthographic_camera(double xmag, double ymag, double znear, double zfar) {
  tinygltf::Camera c;
  c.type = "orthographic";
  c.orthographic.xmag = xmag;
  c.orthographic.ymag = ymag;
  c.orthographic.znear = znear;
  c.orthographic.zfar = zfar;
  impl_->model.cameras.push_back(c);
  return int(impl_->model.cameras.size() - 1);
}

int GltfBuilder::point_light(Rgb color, double intensity_cd) {
  tinygltf::Light l;
  l.type = "point";
  l.color = {color.x, color.y, color.z};
  l.intensity = intensity_cd;
  impl_->model.lights.push_back(l);
  auto& used = impl_->model.extensionsUsed;
  if (std::find(used.begin(), used.end(), "KHR_lights_punctual") == used.end())
    used.push_back("KHR_lights_punctual");
  return int(impl_->model.lights.size() - 1);
}

int GltfBuilder::node(const Node& n, bool root) {
  tinygltf::Node node;
  node.name = n.name;
  node.mesh = n.mesh;
  node.camera = n.camera;
  node.skin = n.skin;
  node.weights = n.weights;
  node.children = n.children;
  if (!n.matrix.empty()) {
    node.matrix = n.matrix;
  } else {
    node.translation.assign(n.translation.begin(), n.translation.end());
    node.rotation.assign(n.rotation.begin(), n.rotation.end());
    node.scale.assign(n.scale.begin(), n.scale.end());
  }
  if (n.light >= 0) {
    tinygltf::Value::Object light;
    light["light"] = tinygltf::Value(n.light);
    node.extensions["KHR_lights_punctual"] = tinygltf::Value(light);
  }
  impl_->model.nodes.push_back(node);
  const int index = int(impl_->model.nodes.size() - 1);
  if (root) impl_->model.scenes[0].nodes.push_back(index);
  return index;
}

int GltfBuilder::skin(const std::vector<int>& joints, const std::vector<float>& inverse_binds) {
  tinygltf::Skin skin;
  skin.joints = joints;
  if (!inverse_binds.empty())
    skin.inverseBindMatrices = impl_->add_accessor(
        inverse_binds.data(), inverse_binds.size() * sizeof(float), TINYGLTF_COMPONENT_TYPE_FLOAT,
        TINYGLTF_TYPE_MAT4, inverse_binds.size() / 16);
  impl_->model.skins.push_back(skin);
  return int(impl_->model.skins.size() - 1);
}

void GltfBuilder::skin_weights(int mesh, int set, const std::vector<uint16_t>& joints,
                               const std::vector<float>& weights) {
  tinygltf::Primitive& prim = impl_->model.meshes[size_t(mesh)].primitives[0];
  prim.attributes["JOINTS_" + std::to_string(set)] = impl_->add_accessor(
      joints.data(), joints.size() * sizeof(uint16_t), TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
      TINYGLTF_TYPE_VEC4, joints.size() / 4);
  prim.attributes["WEIGHTS_" + std::to_string(set)] =
      impl_->add_accessor(weights.data(), weights.size() * sizeof(float),
                          TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, weights.size() / 4);
}

void GltfBuilder::morph_target(int mesh, const std::vector<Vec3f>& positions,
                               const std::vector<Vec3f>& normals) {
  std::map<std::string, int> target;
  target["POSITION"] =
      impl_->add_accessor(positions.data(), positions.size() * sizeof(Vec3f),
                          TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, positions.size());
  if (!normals.empty())
    target["NORMAL"] =
        impl_->add_accessor(normals.data(), normals.size() * sizeof(Vec3f),
                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, normals.size());
  impl_->model.meshes[size_t(mesh)].primitives[0].targets.push_back(target);
}

void GltfBuilder::evaluated_shapes(int node, const std::vector<double>& times_s,
                                   const std::vector<std::vector<Vec3f>>& positions,
                                   const std::vector<std::vector<Vec3f>>& normals,
                                   bool world_space) {
  const auto accessors = [&](const std::vector<std::vector<Vec3f>>& shapes) {
    tinygltf::Value::Array out;
    for (const std::vector<Vec3f>& shape : shapes)
      out.emplace_back(impl_->add_accessor(shape.data(), shape.size() * sizeof(Vec3f),
                                           TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                                           shape.size()));
    return tinygltf::Value(out);
  };
  tinygltf::Value::Object primitive;
  primitive["positions"] = accessors(positions);
  if (!normals.empty()) primitive["normals"] = accessors(normals);
  tinygltf::Value::Array times;
  for (double t : times_s)
    times.emplace_back(t);
  tinygltf::Value::Object ext;
  ext["times_s"] = tinygltf::Value(times);
  ext["world_space"] = tinygltf::Value(world_space);
  ext["primitives"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(primitive)});
  impl_->model.nodes[size_t(node)].extensions["FILMBACK_deformation"] = tinygltf::Value(ext);
  std::vector<std::string>& used = impl_->model.extensionsUsed;
  if (std::find(used.begin(), used.end(), "FILMBACK_deformation") == used.end())
    used.push_back("FILMBACK_deformation");
}

int GltfBuilder::sparse_vec3(size_t count, const std::vector<uint32_t>& indices,
                             const std::vector<Vec3f>& values, int base, int index_component_type,
                             int sparse_count) {
  const std::vector<unsigned char> index_data = index_bytes(indices, index_component_type);
  const int index_accessor =
      impl_->add_accessor(index_data.data(), index_data.size(), index_component_type,
                          TINYGLTF_TYPE_SCALAR, indices.size());
  const int value_accessor =
      impl_->add_accessor(values.data(), values.size() * sizeof(Vec3f),
                          TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, values.size());
  auto& model = impl_->model;
  // The indices and values are read through bufferViews of their own (their accessors stay,
  // unused).
  tinygltf::Accessor sparse = base >= 0 ? model.accessors[size_t(base)] : tinygltf::Accessor{};
  if (base < 0) {
    sparse.bufferView = -1;
    sparse.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    sparse.type = TINYGLTF_TYPE_VEC3;
  }
  sparse.count = count;
  sparse.sparse.isSparse = true;
  sparse.sparse.count = sparse_count >= 0 ? sparse_count : int(indices.size());
  sparse.sparse.indices.bufferView = model.accessors[size_t(index_accessor)].bufferView;
  sparse.sparse.indices.byteOffset = 0;
  sparse.sparse.indices.componentType = index_component_type;
  sparse.sparse.values.bufferView = model.accessors[size_t(value_accessor)].bufferView;
  sparse.sparse.values.byteOffset = 0;
  model.accessors.push_back(sparse);
  return int(model.accessors.size() - 1);
}

void GltfBuilder::attribute(int mesh, const std::string& name, int accessor) {
  impl_->model.meshes[size_t(mesh)].primitives[0].attributes[name] = accessor;
}

void GltfBuilder::morph_target_accessor(int mesh, int positions) {
  impl_->model.meshes[size_t(mesh)].primitives[0].targets.push_back({{"POSITION", positions}});
}

void GltfBuilder::morph_weights(int mesh, const std::vector<double>& weights) {
  impl_->model.meshes[size_t(mesh)].weights = weights;
}

void GltfBuilder::animate(int node, const std::string& path, const std::vector<float>& times_s,
                          const std::vector<float>& values, const std::string& interpolation) {
  auto& model = impl_->model;
  if (model.animations.empty()) model.animations.emplace_back();
  tinygltf::AnimationSampler sampler;
  sampler.interpolation = interpolation;
  sampler.input =
      impl_->add_accessor(times_s.data(), times_s.size() * sizeof(float),
                          TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, times_s.size());
  const bool rotation = path == "rotation", weights = path == "weights";
  const size_t width = weights ? 1 : rotation ? 4 : 3;
  sampler.output = impl_->add_accessor(values.data(), values.size() * sizeof(float),
                                       TINYGLTF_COMPONENT_TYPE_FLOAT,
                                       weights    ? TINYGLTF_TYPE_SCALAR
                                       : rotation ? TINYGLTF_TYPE_VEC4
                                                  : TINYGLTF_TYPE_VEC3,
                                       values.size() / width);
  tinygltf::Animation& animation = model.animations[0];
  animation.samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = int(animation.samplers.size() - 1);
  channel.target_node = node;
  channel.target_path = path;
  animation.channels.push_back(channel);
}

fs::path GltfBuilder::write(const fs::path& file) {
  // A file without geometry has no buffer: an empty data: URI is not valid glTF.
  if (impl_->model.buffers.size() == 1 && impl_->model.buffers[0].data.empty())
    impl_->model.buffers.clear();
  tinygltf::TinyGLTF writer;
  const bool binary = file.extension() == ".glb";
  EXPECT_TRUE(writer.WriteGltfSceneToFile(&impl_->model, file.string(), true, true, true, binary))
      << "could not write " << file;
  return file;
}

}  // namespace fb::test
