#include "importers/gltf/gltf_file.h"

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/util/error.h"

namespace fb::gltf {
namespace {

namespace fs = std::filesystem;

// Images stay encoded (PNG, JPEG bytes in Image::image, width 0): the render decodes the ones a
// material uses through OpenImageIO (core/texture/surface_shader.cpp), which checks their size.
// tinygltf reads external ones through the confined callbacks below.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + std::max(size, 0));
  image->width = image->height = 0;
  return true;
}

// The GLB container (glTF 2.0 §4.4): a 12-byte header (magic "glTF", version 2, total length)
// and chunks of (length, type, data), the first one JSON. Checked before tinygltf sees the bytes:
// tinygltf 2.7.0 compares a BIN chunk's length with the file size without the chunk's 8-byte
// header, so a chunk claiming 8 bytes too many is read past the end of the file.
void check_glb_container(const std::vector<unsigned char>& bytes, const std::string& file) {
  auto fail = [&](const std::string& what) {
    throw_input(file, "", "not a valid glTF binary file: " + what);
  };
  auto u32 = [&](size_t at) {  // little-endian, whatever the host
    return uint32_t(bytes[at]) | uint32_t(bytes[at + 1]) << 8 | uint32_t(bytes[at + 2]) << 16 |
           uint32_t(bytes[at + 3]) << 24;
  };
  const size_t size = bytes.size();
  if (size < 12)
    fail("the file has " + std::to_string(size) + " bytes, expected at least the 12-byte header");
  if (std::memcmp(bytes.data(), "glTF", 4) != 0)
    fail("expected the magic bytes 'glTF' at the start");
  if (u32(4) != 2) fail("container version " + std::to_string(u32(4)) + ", expected 2");
  if (u32(8) != size)
    fail("the header gives a length of " + std::to_string(u32(8)) + " bytes, but the file has " +
         std::to_string(size) + (u32(8) > size ? " (truncated?)" : ""));
  constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
  size_t at = 12;
  for (size_t chunk = 0; at < size || chunk == 0; ++chunk) {
    const std::string where = "chunk " + std::to_string(chunk) + " at byte " + std::to_string(at);
    if (size - at < 8)
      fail(where + ": expected an 8-byte chunk header, found " + std::to_string(size - at) +
           " bytes");
    if (u32(at) > size - at - 8)
      fail(where + ": " + std::to_string(u32(at)) +
           " bytes of data reach past the end of the file (" + std::to_string(size) + " bytes)");
    if (chunk == 0 && u32(at + 4) != kJsonChunk) fail(where + ": expected the JSON chunk first");
    at += 8 + size_t(u32(at));
  }
}

// Nesting depth of JSON text, outside strings. Returns the byte offset where kMaxJsonDepth is
// exceeded, or npos.
size_t too_deep_at(const unsigned char* text, size_t size) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < size; ++i) {
    const unsigned char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;  // skip the escaped character
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

void check_json_depth(const unsigned char* text, size_t size, size_t offset,
                      const std::string& file, bool binary) {
  const size_t at = too_deep_at(text, size);
  if (at == std::string::npos) return;
  const std::string what =
      "JSON nested more than " + std::to_string(kMaxJsonDepth) + " levels deep";
  if (binary) throw_input(file, "JSON chunk, byte " + std::to_string(offset + at), what);
  size_t line = 1, column = 1;
  for (size_t i = 0; i < at; ++i)
    text[i] == '\n' ? (++line, column = 1) : ++column;
  throw InputError(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + what);
}

// A URI as tinygltf turns it into a path: percent-escapes decoded (RFC 3986 §2.1).
std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// What is wrong with a buffer's or image's `uri`, or "": only data: URIs and paths relative to the
// scene's folder are read. A scheme (file:, http:, https: ...; RFC 3986 §3.1: a relative path
// whose first segment holds a ':' must be written "./a:b") is refused, so nothing is ever fetched
// and no other folder is named; absolute paths and '..' escapes are refused here by name, and
// confined_read catches what only the file system shows (symbolic links out of the folder).
std::string uri_problem(const std::string& uri) {
  if (uri.starts_with("data:")) {
    // base64 holds 3 bytes in 4 characters; the cap is the external files' own.
    if (uri.size() / 4 * 3 > kMaxExternalFileBytes)
      return "a data: URI of more than " + std::to_string(kMaxExternalFileBytes) +
             " bytes is refused";
    return {};
  }
  const std::string path = percent_decoded(uri);
  const size_t colon = path.find(':');
  if (colon != std::string::npos && colon > 0 &&
      std::isalpha(static_cast<unsigned char>(path[0])) &&
      path.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789+.-") ==
          colon)
    return "'" + uri + "' is a '" + path.substr(0, colon + 1) +
           "' URI: filmback reads only files inside the scene's folder and data: URIs, and never "
           "opens a network connection";
  if (path.empty()) return "an empty URI, expected a path relative to the scene's folder";
  if (fs::path(path).is_absolute())
    return "'" + uri + "' is an absolute path: expected a path relative to the scene's folder";
  const fs::path normal = fs::path(path).lexically_normal();
  if (!normal.empty() && *normal.begin() == "..")
    return "'" + uri + "' refers outside the scene's folder";
  return {};
}

// Every buffers[i].uri and images[i].uri, checked before tinygltf opens or decodes anything, so
// the message names the element. JSON tinygltf cannot parse is left for it to report.
void check_uris(const unsigned char* json, size_t size, const std::string& file) {
  const nlohmann::json doc = nlohmann::json::parse(json, json + size, nullptr, false);
  if (!doc.is_object()) return;
  for (const char* array : {"buffers", "images"}) {
    const auto elements = doc.find(array);
    if (elements == doc.end() || !elements->is_array()) continue;
    for (size_t i = 0; i < elements->size(); ++i) {
      const nlohmann::json& element = (*elements)[i];
      if (!element.is_object()) continue;
      const auto uri = element.find("uri");
      if (uri == element.end() || !uri->is_string()) continue;
      if (const std::string problem = uri_problem(uri->get<std::string>()); !problem.empty())
        throw_input(file, std::string(array) + "[" + std::to_string(i) + "].uri", problem);
    }
  }
}

std::vector<unsigned char> read_scene_file(const fs::path& file, const std::string& name) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) throw_input(name, "", "is a folder, expected a glTF file");
  if (!fs::is_regular_file(file, ec)) throw_input(name, "", "no such file");
  const uintmax_t size = fs::file_size(file, ec);
  // tinygltf takes 32-bit sizes; a GLB's length field is 32-bit too (glTF 2.0 §4.4.2).
  if (!ec && size > std::numeric_limits<uint32_t>::max())
    throw_input(name, "", std::to_string(size) + " bytes, expected at most 4 GiB");
  std::ifstream in(file, std::ios::binary);
  std::vector<unsigned char> bytes(ec ? 0 : size);
  if (ec || !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size())))
    throw_input(name, "", "cannot read the file");
  if (bytes.empty()) throw_input(name, "", "the file is empty, expected a glTF document");
  return bytes;
}

// tinygltf's file callbacks, confined to the scene's folder: no path escapes (.., absolute paths,
// symbolic links out), no devices or pipes that could block, no file larger than the cap. The
// default ExpandFilePath would also expand ~ and environment variables; this one does not.
struct Confinement {
  fs::path folder;  // canonical
};

bool inside(const fs::path& path, const fs::path& folder) {
  const auto [f, p] = std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
  return f == folder.end();
}

std::string confined_problem(const std::string& path, void* user) {
  const fs::path& folder = static_cast<Confinement*>(user)->folder;
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(path, ec);
  if (ec || !inside(real, folder)) return "refers outside the scene's folder";
  if (!fs::exists(real, ec)) return "not found";
  if (!fs::is_regular_file(real, ec)) return "is not a regular file";
  if (fs::file_size(real, ec) > kMaxExternalFileBytes || ec)
    return "is larger than " + std::to_string(kMaxExternalFileBytes) + " bytes";
  return {};
}

// Only whether something is there (stat never blocks); confined_read says what is wrong with it.
bool any_file_exists(const std::string& path, void*) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(path, ec));
}

std::string unexpanded(const std::string& path, void*) {
  return path;
}

bool confined_read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user) {
  const std::string problem = confined_problem(path, user);
  const std::string shown =
      fs::path(path).lexically_relative(static_cast<Confinement*>(user)->folder).string();
  if (!problem.empty()) {
    if (err) *err += "'" + shown + "' " + problem + "\n";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->resize(fs::file_size(path));
  if (!in.read(reinterpret_cast<char*>(out->data()), std::streamsize(out->size()))) {
    if (err) *err += "cannot read '" + shown + "'\n";
    return false;
  }
  return true;
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "filmback never writes through the glTF loader\n";
  return false;
}

}  // namespace

fs::path confined_external_file(const fs::path& scene_file, const std::string& uri,
                                const std::string& where) {
  std::error_code ec;
  Confinement confinement{fs::weakly_canonical(fs::absolute(scene_file, ec).parent_path(), ec)};
  if (const std::string problem = uri_problem(uri); !problem.empty() || uri.starts_with("data:"))
    throw_input(scene_file.string(), where,
                problem.empty() ? "expected a path relative to the scene's folder" : problem);
  const fs::path path = confinement.folder / fs::path(percent_decoded(uri));
  const std::string problem = confined_problem(path.string(), &confinement);
  if (!problem.empty()) throw_input(scene_file.string(), where, "'" + uri + "' " + problem);
  return fs::weakly_canonical(path, ec);
}

void load_model(const fs::path& file, tinygltf::Model& model) {
  const std::string name = file.string();
  const std::vector<unsigned char> bytes = read_scene_file(file, name);
  const bool binary = file.extension() == ".glb";
  if (binary) {
    check_glb_container(bytes, name);
    uint32_t json_length;
    std::memcpy(&json_length, &bytes[12], 4);  // checked by check_glb_container
    check_json_depth(bytes.data() + 20, json_length, 20, name, true);
    check_uris(bytes.data() + 20, json_length, name);
  } else {
    check_json_depth(bytes.data(), bytes.size(), 0, name, false);
    check_uris(bytes.data(), bytes.size(), name);
  }

  std::error_code ec;
  Confinement confinement{fs::weakly_canonical(fs::absolute(file, ec).parent_path(), ec)};
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_encoded_image, nullptr);
  loader.SetFsCallbacks({any_file_exists, unexpanded, confined_read, refuse_write, &confinement});
  std::string err, warnings;
  const std::string folder = confinement.folder.string();  // external files are relative to it
  const auto size = unsigned(bytes.size());
  const bool ok =
      binary
          ? loader.LoadBinaryFromMemory(&model, &err, &warnings, bytes.data(), size, folder)
          : loader.LoadASCIIFromString(&model, &err, &warnings,
                                       reinterpret_cast<const char*>(bytes.data()), size, folder);
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' '))
      err.pop_back();
    throw_input(name, "",
                "not a valid glTF " + std::string(binary ? "binary" : "JSON") +
                    " file: " + (err.empty() ? "unknown reason" : err));
  }
}

}  // namespace fb::gltf
