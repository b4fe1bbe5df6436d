// height_field { [type] "file" ... } or { function W, H { ... } } (POV-Ray 3.7 reference, "Height
// Field"): the image's heights, or the function's sampled as POV-Ray samples it, over the unit
// square of POV-Ray's x-z plane, two triangles a cell, as POV-Ray draws it: a triangle mesh from
// here on (docs/pov.md, "Geometry").
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/function/user_function.h"
#include "core/util/error.h"
#include "importers/pov/sdl/height_field_image.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// The image types height_field names before its file that are read here (objects.cpp reports
// gif, pot, iff and sys unsupported); POV-Ray 3.7 also reads a file without one.
constexpr std::string_view kHeightFieldTypes[] = {"tga",  "ppm",  "pgm", "png",
                                                  "jpeg", "tiff", "exr", "hdr"};

struct HeightFieldOptions {
  bool smooth = false;
  double water_level = 0;
};

// The part of triangle `corners` at or above y = water_level, as POV-Ray clips its height field
// there (the field's box starts at the water level): whole, cut to a triangle or a quadrilateral
// (two triangles) with new vertices on the water line, or nothing.
void add_above_water(std::array<uint32_t, 3> corners, double water_level, Object& o) {
  const auto height = [&](uint32_t v) { return o.vertices[v].y; };
  const auto dry = [&](uint32_t v) { return height(v) >= water_level; };
  const int dry_count = dry(corners[0]) + dry(corners[1]) + dry(corners[2]);
  if (dry_count == 3) {
    o.indices.insert(o.indices.end(), corners.begin(), corners.end());
    return;
  }
  if (dry_count == 0) return;
  // Where edge (a, b) meets the water line.
  const auto shore = [&](uint32_t a, uint32_t b) {
    const double f = (water_level - height(a)) / (height(b) - height(a));
    o.vertices.push_back(o.vertices[a] + (o.vertices[b] - o.vertices[a]) * f);
    if (!o.normals.empty())
      o.normals.push_back(normalize(o.normals[a] + (o.normals[b] - o.normals[a]) * f));
    return uint32_t(o.vertices.size() - 1);
  };
  std::vector<uint32_t> polygon;  // the dry part, in the triangle's winding
  for (int i = 0; i < 3; ++i) {
    const uint32_t a = corners[size_t(i)], b = corners[size_t((i + 1) % 3)];
    if (dry(a)) polygon.push_back(a);
    if (dry(a) != dry(b)) polygon.push_back(shore(a, b));
  }
  for (size_t i = 1; i + 1 < polygon.size(); ++i)
    o.indices.insert(o.indices.end(), {polygon[0], polygon[i], polygon[i + 1]});
}

// Vertex (column, row) of the image at x = column / (W - 1), y = its height, z = 1 - row / (H - 1):
// the image's top row lies at the far edge, z = 1, as in POV-Ray. Two triangles a cell, clipped
// at the water level; with `smooth`, normals from the heights' central differences.
void height_field_mesh(const HeightImage& image, const HeightFieldOptions& options, Object& o) {
  const uint32_t w = image.width, h = image.height;
  const auto height = [&](int64_t x, int64_t y) {
    x = std::clamp<int64_t>(x, 0, w - 1), y = std::clamp<int64_t>(y, 0, h - 1);
    return image.heights[size_t(y) * w + size_t(x)];
  };
  const double dx = 1.0 / (w - 1), dz = 1.0 / (h - 1);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      o.vertices.push_back({x * dx, height(x, y), 1 - y * dz});
      if (!options.smooth) continue;
      // z grows with falling rows: dh/dz = (h(row - 1) - h(row + 1)) / 2 dz
      const double slope_x = (height(int64_t(x) + 1, y) - height(int64_t(x) - 1, y)) / (2 * dx);
      const double slope_z = (height(x, int64_t(y) - 1) - height(x, int64_t(y) + 1)) / (2 * dz);
      o.normals.push_back(normalize(Vec3d{-slope_x, 1, -slope_z}));
    }
  for (uint32_t y = 0; y + 1 < h; ++y)
    for (uint32_t x = 0; x + 1 < w; ++x) {
      const uint32_t near_left = (y + 1) * w + x, near_right = near_left + 1, far_left = y * w + x,
                     far_right = far_left + 1;
      // Counter-clockwise seen from above (+y) in POV-Ray's left-handed space.
      add_above_water({near_left, far_left, near_right}, options.water_level, o);
      add_above_water({near_right, far_left, far_right}, options.water_level, o);
    }
}

// The modifiers after the image or function, up to the first that is not the height field's own.
HeightFieldOptions read_height_field_options(Parser& p) {
  HeightFieldOptions options;
  for (;;) {
    Tok tok = p.next();  // directives run
    if (tok.word("smooth")) {
      options.smooth = p.parse_bool_option();
    } else if (tok.word("water_level")) {
      options.water_level = p.parse_float();
    } else if (tok.word("hierarchy") || tok.word("premultiplied")) {
      p.parse_bool_option();  // a speed hint; an alpha channel is no height
    } else if (tok.word("gamma")) {
      p.parse_float();  // heights are data, read linear
    } else {
      p.unget(std::move(tok));
      return options;
    }
  }
}

// The W x H image POV-Ray makes of a height_field's function (Make_Pattern_Image in POV-Ray 3.7's
// parser): pixel (column, row) holds f(column / (W - 1), row / (H - 1), 0) in a 16-bit grey image,
// so clamped to [0, 1] and rounded to 1/65535, then read as every 16-bit image is (65535 / 65536).
HeightImage sample_function(const UserFunction& f, uint32_t width, uint32_t height) {
  HeightImage image;
  image.width = width;
  image.height = height;
  image.heights.reserve(size_t(width) * height);
  double arguments[UserFunction::kMaxStack] = {};
  for (uint32_t row = 0; row < height; ++row)
    for (uint32_t column = 0; column < width; ++column) {
      arguments[0] = double(column) / (width - 1);
      arguments[1] = double(row) / (height - 1);
      const double value = f.evaluate({arguments, size_t(f.parameter_count())});
      // NaN (sqrt of a negative number) is a black pixel, as the clamp to the image's range makes
      // it
      const double grey = std::isnan(value) ? 0 : std::round(std::clamp(value, 0.0, 1.0) * 65535);
      image.heights.push_back(grey / 65536);
    }
  return image;
}

// function W, H { body }, after `function`.
HeightImage read_height_function(Parser& p) {
  const SourceLocation where = p.location_of(p.peek());
  const double width = p.parse_float();
  p.expect(",");
  const double height = p.parse_float();
  // POV-Ray rounds the resolution to the nearest integer
  const double columns = std::floor(width + 0.5), rows = std::floor(height + 0.5);
  if (!(columns >= 2 && rows >= 2))
    p.fail_at(where, "height_field function resolution " + number_string(width) + ", " +
                         number_string(height) + ": it needs at least 2, 2");
  if (!(columns * rows <= double(p.options().limits.objects)))
    p.fail_at(where, "height_field function resolution " + number_string(columns) + " x " +
                         number_string(rows) + " is past the scene's object limit");
  p.count_objects(2 * uint64_t(columns - 1) * uint64_t(rows - 1));
  const SourceLocation body = p.location_of(p.peek());
  const FunctionValue f = p.parse_function_body({"x", "y", "z"}, true);
  if (!f.unsupported.empty()) p.unsupported("function " + f.unsupported, body);
  return sample_function(*f.program, uint32_t(columns), uint32_t(rows));
}

}  // namespace

void Parser::parse_height_field(Object& o) {
  o.shape = Shape::kMesh;
  if (peek().word("function")) {
    next();
    const HeightImage image = read_height_function(*this);
    height_field_mesh(image, read_height_field_options(*this), o);
    return;
  }
  if (peek().keyword() && std::find(std::begin(kHeightFieldTypes), std::end(kHeightFieldTypes),
                                    peek().token.text) != std::end(kHeightFieldTypes))
    next();
  const SourceLocation where = location_of(peek());
  const Value name = parse_expression();
  if (name.kind != ValueKind::kString) fail_at(where, "height_field expects an image file name");
  const HeightFieldOptions options = read_height_field_options(*this);
  const std::optional<std::filesystem::path> file = resolve_include(name.text, nullptr, false);
  if (!file)
    fail_at(where, "cannot find the height_field image \"" + name.text +
                       "\" in the scene's folder or a library path (paths leaving those "
                       "folders, through '..' or a symbolic link, are refused)");
  HeightImage image;
  try {
    // Never more pixels than the scene may have triangles: the count below is then checked.
    image = read_height_image(*file, options_.limits.objects);
  } catch (const InputError& e) {
    fail_at(where, std::string("height_field: ") + e.what());
  }
  if (image.width < 2 || image.height < 2)
    fail_at(where, "height_field image \"" + name.text + "\" is " + std::to_string(image.width) +
                       "x" + std::to_string(image.height) + " pixels; it needs at least 2x2");
  count_objects(2 * uint64_t(image.width - 1) * (image.height - 1));
  height_field_mesh(image, options, o);
}

}  // namespace fb::pov::sdl
