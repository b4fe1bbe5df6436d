// Reading glTF's JSON (tinygltf::Value) with errors that name the file, the JSON path of the value
// and what was expected: the one reader every part of the importer uses for extensions and extras.
// And writing its arrays of numbers, for the writer and the extensions' writers.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include <filmback/vec.h>

namespace tinygltf {
class Value;
}

namespace fb::gltf {

// "nodes[3]"
std::string index_path(const char* array, size_t i);

// "mesh index 5 is out of range (the file has 1 meshes)": what was found and what was expected.
std::string out_of_range(const char* what, long index, size_t count, const char* array);

// Whether `word` is `lower_case` in any case: Blender's enum words ("AUTO", "Gaussian").
bool same_word(const std::string& word, const char* lower_case);

// A JSON array of these numbers; of a vector's or a colour's three components.
tinygltf::Value number_array(std::initializer_list<double> values);
tinygltf::Value number_array(Vec3d v);
tinygltf::Value number_array(Rgb c);

// The members of one JSON object (anything else reads as an object without members). Each getter
// returns nothing for an absent member and throws InputError at `path.key` for a present one of
// the wrong type or range.
class Fields {
 public:
  Fields(const tinygltf::Value& object, std::string path, const std::string& file);

  bool has(const char* key) const;
  // What a member holds, for members that may be one of several things.
  enum class Type { kAbsent, kNumber, kArray, kObject, kString, kOther };
  Type type(const char* key) const;
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }

  std::optional<double> number(const char* key, double lo, double hi) const;
  std::optional<double> whole(const char* key, double lo, double hi) const;  // an integer
  std::optional<Rgb> color(const char* key) const;  // three finite, non-negative components
  std::optional<std::string> word(const char* key) const;
  std::optional<bool> flag(const char* key) const;
  // An array of at most `max_count` numbers, each in [lo, hi].
  std::optional<std::vector<double>> numbers(const char* key, size_t max_count, double lo,
                                             double hi) const;
  // An array of at most `max_count` strings.
  std::optional<std::vector<std::string>> words(const char* key, size_t max_count) const;
  // An array of at most `max_count` indices below `count`, or -1 (no index).
  std::optional<std::vector<long>> indices(const char* key, size_t max_count, size_t count) const;
  // A member object (absent: one without members), for nested fields.
  Fields object(const char* key) const;
  // A member array of at most `max_count` objects, each with its JSON path (absent: none).
  std::vector<Fields> objects(const char* key, size_t max_count) const;

  [[noreturn]] void fail(const char* key, const std::string& what) const;

 private:
  const tinygltf::Value& object_;
  std::string path_;
  const std::string& file_;
};

}  // namespace fb::gltf
