#include "core/film/cryptomatte.h"

#include <murmurhash.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <unordered_map>

namespace fb {

uint32_t cryptomatte_hash(std::string_view name) {
  uint32_t hash[1];
  lmmh_x86_32(name.data(), unsigned(name.size()), 0, hash);
  return hash[0];
}

float cryptomatte_id(uint32_t hash) {
  const uint32_t exponent = std::clamp<uint32_t>((hash >> 23) & 0xffu, 1u, 254u);
  return std::bit_cast<float>((hash & 0x807fffffu) | (exponent << 23));
}

std::string cryptomatte_hex(uint32_t hash) {
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", hash);
  return hex;
}

CryptomatteFilm::CryptomatteFilm(uint32_t width, uint32_t height,
                                 std::vector<CryptomatteLayer> layers, uint32_t levels)
    : width_(width),
      height_(height),
      levels_(std::clamp(levels + levels % 2, 2u, kMaxCryptomatteLevels)),
      layers_(std::move(layers)),
      slots_(size_t(width) * height * layers_.size() * levels_),
      weights_(size_t(width) * height, 0.f) {
  for (const CryptomatteLayer& layer : layers_) {
    std::vector<uint32_t>& hashes = hashes_.emplace_back();
    std::vector<uint32_t>& first = first_of_name_.emplace_back();
    std::unordered_map<std::string_view, uint32_t> seen;
    for (const std::string& name : layer.names) {
      hashes.push_back(cryptomatte_hash(name));
      first.push_back(seen.emplace(name, uint32_t(first.size())).first->second);
    }
  }
}

void CryptomatteFilm::add(uint32_t x, uint32_t y, const uint32_t* names, float weight) {
  if (!std::isfinite(weight)) return;
  const size_t pixel = size_t(y) * width_ + x;
  weights_[pixel] += weight;
  for (size_t layer = 0; layer < layers_.size(); ++layer) {
    if (names[layer] == kCryptomatteNothing) continue;
    const uint32_t name = first_of_name_[layer][names[layer]];
    Slot* s = slots(pixel, layer);
    Slot* free = nullptr;
    Slot* lightest = s;
    for (Slot* slot = s; slot != s + levels_; ++slot) {
      if (slot->name == name) {
        slot->weight += weight;
        free = lightest = nullptr;
        break;
      }
      if (slot->name == kCryptomatteNothing && !free) free = slot;
      if (slot->weight < lightest->weight) lightest = slot;
    }
    if (free)
      *free = {name, weight};
    else if (lightest && weight > lightest->weight)
      *lightest = {name, weight};
  }
}

void CryptomatteFilm::append_layers(Image& image, std::string_view view_layer) const {
  const uint32_t rgba_layers = levels_ / 2;
  const size_t old_n = image.channels.size();
  std::vector<std::string> names;
  for (const CryptomatteLayer& layer : layers_)
    for (uint32_t rgba = 0; rgba < rgba_layers; ++rgba)
      for (const char* c : {"r", "g", "b", "a"}) {
        char rank[12];  // any uint32_t, though levels / 2 is at most 8
        std::snprintf(rank, sizeof rank, "%02u", rgba);
        names.push_back(std::string(view_layer) + "." + layer.pass + rank + "." + c);
      }
  append_channels(image, names);
  const size_t n = image.channels.size();
  for (size_t pixel = 0; pixel < size_t(width_) * height_; ++pixel) {
    if (weights_[pixel] == 0.f) continue;  // no sample landed: no id, never NaN
    float* out = &image.pixels[pixel * n + old_n];
    for (size_t layer = 0; layer < layers_.size(); ++layer) {
      std::array<Slot, kMaxCryptomatteLevels> ranked;
      std::copy_n(slots(pixel, layer), levels_, ranked.begin());
      // Heaviest first; equal weights by name index, so that the order never depends on arrival.
      std::sort(ranked.begin(), ranked.begin() + levels_, [](const Slot& a, const Slot& b) {
        return a.weight != b.weight ? a.weight > b.weight : a.name < b.name;
      });
      float* ranks = out + layer * rgba_layers * 4;
      for (uint32_t r = 0; r < levels_; ++r) {
        if (ranked[r].name == kCryptomatteNothing) break;
        ranks[2 * r] = cryptomatte_id(hashes_[layer][ranked[r].name]);
        ranks[2 * r + 1] = ranked[r].weight / weights_[pixel];
      }
    }
  }
}

std::vector<std::pair<std::string, std::string>> CryptomatteFilm::metadata(
    std::string_view view_layer) const {
  std::vector<std::pair<std::string, std::string>> strings;
  for (size_t layer = 0; layer < layers_.size(); ++layer) {
    std::vector<bool> met(layers_[layer].names.size(), false);
    for (size_t pixel = 0; pixel < size_t(width_) * height_; ++pixel)
      for (const Slot* s = slots(pixel, layer); s != slots(pixel, layer) + levels_; ++s)
        if (s->name != kCryptomatteNothing) met[s->name] = true;
    nlohmann::json manifest = nlohmann::json::object();
    for (size_t name = 0; name < met.size(); ++name)
      if (met[name]) manifest[layers_[layer].names[name]] = cryptomatte_hex(hashes_[layer][name]);
    const std::string full_name = std::string(view_layer) + "." + layers_[layer].pass;
    const std::string key =
        "cryptomatte/" + cryptomatte_hex(cryptomatte_hash(full_name)).substr(0, 7);
    strings.insert(strings.end(),
                   {{key + "/name", full_name},
                    {key + "/hash", "MurmurHash3_32"},
                    {key + "/conversion", "uint32_to_float32"},
                    // Names are the scene's, untrusted: invalid UTF-8 is replaced, not thrown.
                    {key + "/manifest",
                     manifest.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)}});
  }
  return strings;
}

}  // namespace fb
