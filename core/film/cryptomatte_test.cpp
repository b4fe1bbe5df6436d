#include "core/film/cryptomatte.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace fb {
namespace {

TEST(Cryptomatte, HashIsMurmurHash3X86With32BitsAndSeedZero) {
  // SMHasher's MurmurHash3_x86_32 with seed 0 (the vectors other ports test against).
  EXPECT_EQ(cryptomatte_hash(""), 0u);
  EXPECT_EQ(cryptomatte_hash("hello"), 0x248bfa47u);
  EXPECT_EQ(cryptomatte_hash("The quick brown fox jumps over the lazy dog"), 0x2e4ff723u);
}

TEST(Cryptomatte, HashesAreBlenderManifestsAndLayerKeys) {
  // A Cycles render by Blender 3.4 (`blender -b`, CryptoObject and CryptoMaterial on, written to a
  // multi-layer EXR, read with `oiiotool --info -v`): its manifests and its metadata keys.
  const std::map<std::string, std::string> blender = {{"Left", "63a5d310"},
                                                      {"Right", "8eb27afa"},
                                                      {"RedMat", "7b9cad36"},
                                                      {"BlueMat", "d07dd25b"},
                                                      {"default_surface", "78d05529"}};
  for (const auto& [name, hex] : blender)
    EXPECT_EQ(cryptomatte_hex(cryptomatte_hash(name)), hex) << name;
  EXPECT_EQ(cryptomatte_hex(cryptomatte_hash("ViewLayer.CryptoObject")).substr(0, 7), "542cafa");
  EXPECT_EQ(cryptomatte_hex(cryptomatte_hash("ViewLayer.CryptoMaterial")).substr(0, 7), "c7dbf5e");
  EXPECT_EQ(cryptomatte_hex(cryptomatte_hash("ViewLayer.CryptoAsset")).substr(0, 7), "aa21542");
}

TEST(Cryptomatte, IdIsTheHashsBitsWithTheExponentKeptOffZeroAndAllOnes) {
  EXPECT_EQ(std::bit_cast<uint32_t>(cryptomatte_id(0x63a5d310u)), 0x63a5d310u);
  // Exponent 0 (a denormal) becomes 1, exponent 255 (Inf, NaN) becomes 254; sign and mantissa
  // stay: the specification's flip of bit 23 gives the same.
  EXPECT_EQ(std::bit_cast<uint32_t>(cryptomatte_id(0x80123456u)), 0x80123456u ^ (1u << 23));
  EXPECT_EQ(std::bit_cast<uint32_t>(cryptomatte_id(0x7f812345u)), 0x7f812345u ^ (1u << 23));
  EXPECT_TRUE(std::isfinite(cryptomatte_id(0xffffffffu)));
  EXPECT_TRUE(std::isnormal(cryptomatte_id(0u)));
}

// The channel of `image` called `name`.
size_t crypto_channel(const Image& image, const std::string& name) {
  const auto it = std::find(image.channels.begin(), image.channels.end(), name);
  EXPECT_NE(it, image.channels.end()) << name;
  return size_t(it - image.channels.begin());
}

TEST(Cryptomatte, RanksAreCoverageOfThePixelsWeightHeaviestFirst) {
  CryptomatteFilm film(2, 1, {{"CryptoObject", CryptomatteKey::kObject, {"a", "b", "a"}}});
  const uint32_t a = 0, b = 1, a_again = 2, miss = kCryptomatteNothing;
  film.add(0, 0, &a, 1.f);
  film.add(0, 0, &b, 1.5f);
  film.add(0, 0, &a_again, 0.5f);  // the same name: the same id and slot as `a`
  film.add(0, 0, &miss, 1.f);
  Image image{2, 1, {"R"}, {0.25f, 0.75f}};
  film.append_layers(image, "ViewLayer");
  ASSERT_EQ(image.channels.size(), 1u + 12u);
  EXPECT_EQ(image.at(0, 0, 0), 0.25f);  // what was there stays
  EXPECT_EQ(image.at(1, 0, 0), 0.75f);
  const size_t r = crypto_channel(image, "ViewLayer.CryptoObject00.r");
  EXPECT_EQ(image.at(0, 0, r), cryptomatte_id(cryptomatte_hash("a")));  // 1.5 of 4: a tie, "a"
  EXPECT_FLOAT_EQ(image.at(0, 0, r + 1), 1.5f / 4.f);                   // first by index
  EXPECT_EQ(image.at(0, 0, r + 2), cryptomatte_id(cryptomatte_hash("b")));
  EXPECT_FLOAT_EQ(image.at(0, 0, r + 3), 1.5f / 4.f);
  const size_t rank2 = crypto_channel(image, "ViewLayer.CryptoObject01.r");
  EXPECT_EQ(image.at(0, 0, rank2), 0.f);  // nothing more: id 0, coverage 0
  EXPECT_EQ(image.at(0, 0, rank2 + 1), 0.f);
  for (size_t c = 1; c < image.channels.size(); ++c)
    EXPECT_EQ(image.at(1, 0, c), 0.f) << image.channels[c];  // a pixel without samples
}

TEST(Cryptomatte, AFullPixelDropsWhatItCoversLeast) {
  std::vector<std::string> names;
  for (int i = 0; i < 8; ++i)
    names.push_back("object" + std::to_string(i));
  CryptomatteFilm film(1, 1, {{"CryptoObject", CryptomatteKey::kObject, names}});
  // Six ids fill the slots (weights 2..7); a light seventh is dropped, a heavy eighth replaces
  // the lightest.
  for (uint32_t i = 0; i < 6; ++i)
    film.add(0, 0, &i, float(i + 2));
  const uint32_t light = 6, heavy = 7;
  film.add(0, 0, &light, 1.f);
  film.add(0, 0, &heavy, 10.f);
  Image image{1, 1, {}, {}};
  film.append_layers(image, "ViewLayer");
  const float total = 2 + 3 + 4 + 5 + 6 + 7 + 1 + 10;
  EXPECT_EQ(image.at(0, 0, 0), cryptomatte_id(cryptomatte_hash("object7")));
  EXPECT_FLOAT_EQ(image.at(0, 0, 1), 10.f / total);
  EXPECT_EQ(image.at(0, 0, 10), cryptomatte_id(cryptomatte_hash("object1")));  // rank 5: 3
  EXPECT_FLOAT_EQ(image.at(0, 0, 11), 3.f / total);
  const auto manifest = nlohmann::json::parse(film.metadata("ViewLayer").back().second);
  EXPECT_EQ(manifest.size(), 6u);
  EXPECT_FALSE(manifest.contains("object0"));
  EXPECT_FALSE(manifest.contains("object6"));
  EXPECT_EQ(manifest["object7"], cryptomatte_hex(cryptomatte_hash("object7")));
}

TEST(Cryptomatte, MetadataNamesTheLayerAsBlenderDoes) {
  CryptomatteFilm film(1, 1, {{"CryptoMaterial", CryptomatteKey::kMaterial, {"Red\"Mat", "x"}}});
  const uint32_t red = 0;
  film.add(0, 0, &red, 1.f);
  const auto m = film.metadata("ViewLayer");
  const std::map<std::string, std::string> strings(m.begin(), m.end());
  EXPECT_EQ(strings.at("cryptomatte/c7dbf5e/name"), "ViewLayer.CryptoMaterial");
  EXPECT_EQ(strings.at("cryptomatte/c7dbf5e/hash"), "MurmurHash3_32");
  EXPECT_EQ(strings.at("cryptomatte/c7dbf5e/conversion"), "uint32_to_float32");
  // Only the names met; a quote in a name is escaped.
  EXPECT_EQ(strings.at("cryptomatte/c7dbf5e/manifest"),
            "{\"Red\\\"Mat\":\"" + cryptomatte_hex(cryptomatte_hash("Red\"Mat")) + "\"}");
}

}  // namespace
}  // namespace fb
