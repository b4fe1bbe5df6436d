// Cryptomatte (Friedman & Jones 2015, "Fully Automatic ID Mattes with Support for Motion Blur and
// Transparency"; docs/blender.md, "Cryptomatte"): per pixel, which named objects or materials the
// camera's samples met and with what share of the pixel filter's weight, written as Blender 3.4
// writes it so that its Cryptomatte node reads it. Each name's id is MurmurHash3_x86_32 (seed 0)
// of its UTF-8 bytes, stored as the bits of a float; the ids of a pixel are ranked by coverage and
// written two (id, coverage) pairs per RGBA layer (ViewLayer.CryptoObject00.r/g/b/a, 01, ...),
// with the names' manifest in the file's metadata.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/image/image.h"

namespace fb {

// Blender's Cryptomatte levels (View Layer > Passes > Cryptomatte > Levels,
// view_layer.pass_cryptomatte_depth): the ranks written per pixel, two per RGBA layer; an even
// number from 2 to 16, 6 by default.
inline constexpr uint32_t kDefaultCryptomatteLevels = 6;
inline constexpr uint32_t kMaxCryptomatteLevels = 16;
inline bool valid_cryptomatte_levels(uint32_t levels) {
  return levels >= 2 && levels <= kMaxCryptomatteLevels && levels % 2 == 0;
}

// MurmurHash3_x86_32 with seed 0 of the name's bytes: Cryptomatte's hash, and the manifest's value.
uint32_t cryptomatte_hash(std::string_view name);
// The hash as the float whose bits it becomes in the image: an exponent of all zeros or all ones
// (denormals, infinities, NaN, which a float pipeline may flush or mangle) is moved to 1 or 254,
// as Blender's BKE_cryptomatte_hash_to_float does (the specification flips bit 23: the same).
float cryptomatte_id(uint32_t hash);
// "0123abcd": the hash as the manifest and the metadata keys write it.
std::string cryptomatte_hex(uint32_t hash);

// What names a sample in a Cryptomatte pass: the object its camera ray met (Blender's
// CryptoObject), that object's material (CryptoMaterial), or the object's topmost parent
// (CryptoAsset).
enum class CryptomatteKey { kObject, kMaterial, kAsset };

// Blender's Cryptomatte passes filmback writes, as --passes takes them, and what names a sample in
// each; null for another name.
inline const CryptomatteKey* find_cryptomatte_pass(std::string_view pass) {
  static constexpr CryptomatteKey kObject = CryptomatteKey::kObject,
                                  kMaterial = CryptomatteKey::kMaterial,
                                  kAsset = CryptomatteKey::kAsset;
  return pass == "CryptoObject"     ? &kObject
         : pass == "CryptoMaterial" ? &kMaterial
         : pass == "CryptoAsset"    ? &kAsset
                                    : nullptr;
}

// One Cryptomatte pass and the names its samples may carry: a sample names one of them by index
// (RenderGeometry::SurfaceIdentity's object or material).
struct CryptomatteLayer {
  std::string pass;  // "CryptoObject"
  CryptomatteKey key;
  std::vector<std::string> names;
};

// The sample an index of kCryptomatteNothing names: a miss, which counts in the pixel's weight
// but carries no id (Cycles' background has none either).
inline constexpr uint32_t kCryptomatteNothing = UINT32_MAX;

// Accumulates each pixel's filter weight per id and layer. A pixel keeps `levels` slots per layer:
// once they are full, an id not among them replaces the lightest slot if this sample alone
// outweighs that slot's sum, and is dropped otherwise (Cycles drops every newcomer), so that what a
// pixel loses is what it covers least. Samples land in their own pixel in a fixed order
// (core/film/film.h), so the result does not depend on the thread count.
class CryptomatteFilm {
 public:
  // `levels` as valid_cryptomatte_levels() accepts (clamped into that range otherwise).
  CryptomatteFilm(uint32_t width, uint32_t height, std::vector<CryptomatteLayer> layers,
                  uint32_t levels = kDefaultCryptomatteLevels);

  // One sample of pixel (x, y): `names[k]` indexes layer k's names (or is kCryptomatteNothing).
  // A non-finite weight is dropped, as the film drops it.
  void add(uint32_t x, uint32_t y, const uint32_t* names, float weight);

  // Appends each layer's ranks to `image` (its size): levels / 2 RGBA layers
  // "<view_layer>.<pass>NN.r/g/b/a", the id of rank 2 NN in r, its coverage (its share of the
  // pixel's weight) in g, rank 2 NN + 1 in b and a.
  void append_layers(Image& image, std::string_view view_layer) const;
  // The metadata Blender writes beside them, per layer: cryptomatte/<key>/name, hash, conversion
  // and manifest (a JSON object of the names met in the image, each with its hash in hex). The key
  // is the first 7 hex digits of the hash of "<view_layer>.<pass>".
  std::vector<std::pair<std::string, std::string>> metadata(std::string_view view_layer) const;

  const std::vector<CryptomatteLayer>& layers() const { return layers_; }

 private:
  struct Slot {
    uint32_t name = kCryptomatteNothing;  // index into the layer's names
    float weight = 0.f;
  };
  // Slots of pixel `pixel` in layer `layer`.
  Slot* slots(size_t pixel, size_t layer) {
    return &slots_[(pixel * layers_.size() + layer) * levels_];
  }
  const Slot* slots(size_t pixel, size_t layer) const {
    return &slots_[(pixel * layers_.size() + layer) * levels_];
  }
  uint32_t width_, height_;
  uint32_t levels_;  // slots per pixel and layer
  std::vector<CryptomatteLayer> layers_;
  std::vector<std::vector<uint32_t>> hashes_;  // per layer, per name
  // Per layer and name, the first index with the same name: two glTF nodes may share a name, and
  // then they share an id and a slot.
  std::vector<std::vector<uint32_t>> first_of_name_;
  std::vector<Slot> slots_;     // per pixel, layer and slot
  std::vector<float> weights_;  // per pixel: every sample's, hits and misses
};

}  // namespace fb
