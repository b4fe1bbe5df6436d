// A multi-element lens as pbrt-v4's RealisticCamera reads it (pbrt-v4 src/pbrt/cameras.cpp,
// "lensfile"): one line per refracting interface, front (object side) to back (film side), four
// numbers in mm: curvature radius, thickness (distance to the next interface along the axis),
// index of refraction of the medium behind the interface, aperture diameter. A radius of 0 is the
// aperture stop (index 0 or 1: it refracts nothing). `#` starts a comment. The `realistic` camera
// plugin and `filmback info` read the same file through this one parser (docs/camera-model.md,
// "Realistic lenses"). The file is untrusted: its size and element count are bounded, every number
// must be finite and within physical bounds, and each bad line is named as file:line:column.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fb {

struct LensInterface {
  double radius_mm;     // > 0: centre of curvature behind the vertex (towards the film); 0: stop
  double thickness_mm;  // to the next interface; the last one's is the film's, set by focusing
  double index;         // of the medium behind this interface (1 for air and for the stop)
  double aperture_diameter_mm;
  bool is_stop() const { return radius_mm == 0; }
};

// Front to back, with exactly one aperture stop.
using LensPrescription = std::vector<LensInterface>;

constexpr size_t kMaxLensFileBytes = 64 * 1024;
constexpr size_t kMaxLensInterfaces = 64;

namespace lens_detail {

// "name:line:column: what".
[[noreturn]] inline void fail_at(std::string_view name, size_t line, size_t column,
                                 const std::string& what) {
  throw std::invalid_argument(std::string(name) + ":" + std::to_string(line) + ":" +
                              std::to_string(column) + ": " + what);
}

inline bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

}  // namespace lens_detail

// The interfaces of a lens file's text; `name` (the file) prefixes every error.
inline LensPrescription parse_lens_prescription(std::string_view text, std::string_view name) {
  using lens_detail::fail_at;
  constexpr const char* kColumns[] = {"curvature radius, mm", "thickness, mm",
                                      "index of refraction", "aperture diameter, mm"};
  if (text.size() > kMaxLensFileBytes)
    fail_at(name, 1, 1,
            "a lens file holds at most " + std::to_string(kMaxLensFileBytes) + " bytes");
  LensPrescription lens;
  size_t line_number = 0, stops = 0;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find('\n', start), text.size());
    std::string line(text.substr(start, end - start));
    start = end + 1;
    ++line_number;
    if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    double numbers[4];
    size_t columns[4], count = 0, at = 0;
    while (true) {
      while (at < line.size() && lens_detail::is_blank(line[at]))
        ++at;
      if (at == line.size()) break;
      const size_t column = at + 1;
      if (count == 4)
        fail_at(name, line_number, column, "expected 4 numbers on a line, found more");
      const char* first = line.c_str() + at;
      char* after = nullptr;
      errno = 0;
      const double x = std::strtod(first, &after);
      const size_t length = size_t(after - first);
      if (length == 0 || (at + length < line.size() && !lens_detail::is_blank(line[at + length])))
        fail_at(name, line_number, column,
                std::string("expected a number (") + kColumns[count] + ")");
      if (!std::isfinite(x) || errno == ERANGE)
        fail_at(name, line_number, column,
                std::string("expected a finite number (") + kColumns[count] + ")");
      columns[count] = column;
      numbers[count++] = x;
      at += length;
    }
    if (count == 0) continue;
    if (count < 4)
      fail_at(name, line_number, line.size() + 1,
              std::string("expected 4 numbers, missing the ") + kColumns[count]);
    if (lens.size() == kMaxLensInterfaces)
      fail_at(name, line_number, 1,
              "a lens has at most " + std::to_string(kMaxLensInterfaces) + " interfaces");
    const LensInterface e{numbers[0], numbers[1], numbers[2] == 0 ? 1.0 : numbers[2], numbers[3]};
    if (std::abs(e.radius_mm) > 1e6)
      fail_at(name, line_number, columns[0], "expected a curvature radius within +-1e6 mm");
    if (!(e.thickness_mm >= 0 && e.thickness_mm <= 1e4))
      fail_at(name, line_number, columns[1], "expected a thickness in [0, 1e4] mm");
    if (!(e.index >= 1 && e.index <= 4))
      fail_at(name, line_number, columns[2],
              "expected an index of refraction in [1, 4] (0 or 1: air)");
    if (!(e.aperture_diameter_mm > 0 && e.aperture_diameter_mm <= 1e4))
      fail_at(name, line_number, columns[3], "expected an aperture diameter in (0, 1e4] mm");
    // A sphere narrower than the aperture cannot be that element's surface.
    if (!e.is_stop() && e.aperture_diameter_mm > 2 * std::abs(e.radius_mm))
      fail_at(name, line_number, columns[3],
              "expected an aperture diameter within the surface's sphere (at most twice the "
              "curvature radius)");
    if (e.is_stop() && (numbers[2] != 0 && numbers[2] != 1))
      fail_at(name, line_number, columns[2], "the aperture stop (radius 0) has index 0 or 1");
    stops += e.is_stop();
    if (stops > 1) fail_at(name, line_number, 1, "a lens has one aperture stop (radius 0)");
    lens.push_back(e);
  }
  if (stops == 0)
    fail_at(name, line_number + 1, 1,
            "expected an aperture stop (a line whose curvature radius is 0)");
  if (lens.size() < 2)
    fail_at(name, line_number + 1, 1, "expected a refracting interface besides the stop");
  return lens;
}

// The lens file at `path`, read with its size bounded (a path the user typed, so no scene can
// point it anywhere).
inline LensPrescription read_lens_file(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw std::invalid_argument(path + ": cannot open the lens file");
  std::string text(kMaxLensFileBytes + 1, '\0');
  const size_t size = std::fread(text.data(), 1, text.size(), file);
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) throw std::invalid_argument(path + ": cannot read the lens file");
  text.resize(size);
  return parse_lens_prescription(text, path);
}

}  // namespace fb
