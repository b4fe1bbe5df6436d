#include "importers/gltf/gltf_json.h"

#include <tiny_gltf.h>

#include <cctype>
#include <cmath>

#include "core/util/error.h"

namespace fb::gltf {

std::string index_path(const char* array, size_t i) {
  return std::string(array) + "[" + std::to_string(i) + "]";
}

std::string out_of_range(const char* what, long index, size_t count, const char* array) {
  return std::string(what) + " index " + std::to_string(index) + " is out of range (the file has " +
         std::to_string(count) + " " + array + ")";
}

bool same_word(const std::string& word, const char* lower_case) {
  if (word.size() != std::char_traits<char>::length(lower_case)) return false;
  for (size_t i = 0; i < word.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(word[i])) != lower_case[i]) return false;
  return true;
}

tinygltf::Value number_array(std::initializer_list<double> values) {
  tinygltf::Value::Array array;
  for (double v : values)
    array.emplace_back(v);
  return tinygltf::Value(std::move(array));
}
tinygltf::Value number_array(Vec3d v) {
  return number_array({v.x, v.y, v.z});
}
tinygltf::Value number_array(Rgb c) {
  return number_array({c.x, c.y, c.z});
}

namespace {
const tinygltf::Value kNoMembers;

double as_number(const tinygltf::Value& v) {
  return v.IsNumber() ? v.GetNumberAsDouble() : NAN;
}
}  // namespace

Fields::Fields(const tinygltf::Value& object, std::string path, const std::string& file)
    : object_(object), path_(std::move(path)), file_(file) {}

bool Fields::has(const char* key) const {
  return object_.IsObject() && object_.Has(key);
}

Fields::Type Fields::type(const char* key) const {
  if (!has(key)) return Type::kAbsent;
  const tinygltf::Value& v = object_.Get(key);
  if (v.IsNumber()) return Type::kNumber;
  if (v.IsArray()) return Type::kArray;
  if (v.IsObject()) return Type::kObject;
  if (v.IsString()) return Type::kString;
  return Type::kOther;
}

std::optional<double> Fields::number(const char* key, double lo, double hi) const {
  if (!has(key)) return std::nullopt;
  const double x = as_number(object_.Get(key));
  if (!(x >= lo && x <= hi))
    fail(key, "expected a number in [" + number_text(lo) + ", " + number_text(hi) + "]");
  return x;
}

std::optional<double> Fields::whole(const char* key, double lo, double hi) const {
  if (!has(key)) return std::nullopt;
  const double x = as_number(object_.Get(key));
  if (!(x >= lo && x <= hi) || x != std::floor(x))
    fail(key, "expected a whole number in [" + number_text(lo) + ", " + number_text(hi) + "]");
  return x;
}

std::optional<Rgb> Fields::color(const char* key) const {
  const auto c = numbers(key, 3, 0, HUGE_VAL);
  if (!c) return std::nullopt;
  if (c->size() != 3 || !is_finite(Rgb(float((*c)[0]), float((*c)[1]), float((*c)[2]))))
    fail(key, "expected three finite, non-negative linear colour components");
  return Rgb(float((*c)[0]), float((*c)[1]), float((*c)[2]));
}

std::optional<std::string> Fields::word(const char* key) const {
  if (!has(key)) return std::nullopt;
  const tinygltf::Value& v = object_.Get(key);
  if (!v.IsString()) fail(key, "expected a string");
  return v.Get<std::string>();
}

std::optional<bool> Fields::flag(const char* key) const {
  if (!has(key)) return std::nullopt;
  const tinygltf::Value& v = object_.Get(key);
  if (!v.IsBool()) fail(key, "expected true or false");
  return v.Get<bool>();
}

std::optional<std::vector<double>> Fields::numbers(const char* key, size_t max_count, double lo,
                                                   double hi) const {
  if (!has(key)) return std::nullopt;
  const tinygltf::Value& v = object_.Get(key);
  if (!v.IsArray() || v.ArrayLen() > max_count)
    fail(key, "expected an array of at most " + std::to_string(max_count) + " numbers");
  std::vector<double> out(v.ArrayLen());
  for (size_t i = 0; i < out.size(); ++i) {
    out[i] = as_number(v.Get(int(i)));
    if (!(out[i] >= lo && out[i] <= hi))
      throw_input(file_, path_ + "." + key + "[" + std::to_string(i) + "]",
                  "expected a number in [" + number_text(lo) + ", " + number_text(hi) + "]");
  }
  return out;
}

std::optional<std::vector<std::string>> Fields::words(const char* key, size_t max_count) const {
  if (!has(key)) return std::nullopt;
  const tinygltf::Value& v = object_.Get(key);
  if (!v.IsArray() || v.ArrayLen() > max_count)
    fail(key, "expected an array of at most " + std::to_string(max_count) + " strings");
  std::vector<std::string> out(v.ArrayLen());
  for (size_t i = 0; i < out.size(); ++i) {
    if (!v.Get(int(i)).IsString())
      throw_input(file_, path_ + "." + key + "[" + std::to_string(i) + "]", "expected a string");
    out[i] = v.Get(int(i)).Get<std::string>();
  }
  return out;
}

std::optional<std::vector<long>> Fields::indices(const char* key, size_t max_count,
                                                 size_t count) const {
  if (!has(key)) return std::nullopt;
  const tinygltf::Value& v = object_.Get(key);
  if (!v.IsArray() || v.ArrayLen() > max_count)
    fail(key, "expected an array of at most " + std::to_string(max_count) + " indices");
  std::vector<long> out(v.ArrayLen(), -1);
  for (size_t i = 0; i < out.size(); ++i) {
    const double x = as_number(v.Get(int(i)));
    if (!(x >= -1 && x < double(count)) || x != std::floor(x))
      throw_input(file_, path_ + "." + key + "[" + std::to_string(i) + "]",
                  "expected -1 (none) or an index below " + std::to_string(count));
    out[i] = long(x);
  }
  return out;
}

Fields Fields::object(const char* key) const {
  if (!has(key)) return Fields(kNoMembers, path_ + "." + key, file_);
  const tinygltf::Value& v = object_.Get(key);
  if (!v.IsObject()) fail(key, "expected an object");
  return Fields(v, path_ + "." + key, file_);
}

std::vector<Fields> Fields::objects(const char* key, size_t max_count) const {
  std::vector<Fields> out;
  if (!has(key)) return out;
  const tinygltf::Value& v = object_.Get(key);
  if (!v.IsArray() || v.ArrayLen() > max_count)
    fail(key, "expected an array of at most " + std::to_string(max_count) + " objects");
  for (size_t i = 0; i < v.ArrayLen(); ++i) {
    const std::string at = path_ + "." + key + "[" + std::to_string(i) + "]";
    if (!v.Get(int(i)).IsObject()) throw_input(file_, at, "expected an object");
    out.emplace_back(v.Get(int(i)), at, file_);
  }
  return out;
}

void Fields::fail(const char* key, const std::string& what) const {
  throw_input(file_, path_ + "." + key, what);
}

}  // namespace fb::gltf
