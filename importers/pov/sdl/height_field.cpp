// height_field { [type] "file" ... } (POV-Ray 3.7 reference, "Height Field"): the image's heights
// over the unit square of POV-Ray's x-z plane, two triangles a cell, as POV-Ray draws it: a
// triangle mesh from here on (docs/pov.md, "Geometry").
#include <algorithm>
#include <cmath>

#include "core/util/error.h"
#include "importers/pov/sdl/height_field_image.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// The image types height_field names before its file; POV-Ray 3.7 also reads a file without one.
constexpr std::string_view kHeightFieldTypes[] = {"gif",  "tga",  "iff", "ppm", "pgm", "png",
                                                  "jpeg", "tiff", "sys", "exr", "hdr", "pot"};

struct HeightFieldOptions {
  bool smooth = false;
  double water_level = 0;
};

// Vertex (column, row) of the image at x = column / (W - 1), y = its height, z = 1 - row / (H - 1):
// the image's top row lies at the far edge, z = 1, as in POV-Ray. Two triangles a cell (none
// where all three corners lie below the water level); with `smooth`, normals from the heights'
// central differences.
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
  const auto dry = [&](uint32_t a, uint32_t b, uint32_t c) {
    return std::max({o.vertices[a].y, o.vertices[b].y, o.vertices[c].y}) >= options.water_level;
  };
  for (uint32_t y = 0; y + 1 < h; ++y)
    for (uint32_t x = 0; x + 1 < w; ++x) {
      const uint32_t near_left = (y + 1) * w + x, near_right = near_left + 1, far_left = y * w + x,
                     far_right = far_left + 1;
      // Counter-clockwise seen from above (+y) in POV-Ray's left-handed space.
      if (dry(near_left, far_left, near_right))
        o.indices.insert(o.indices.end(), {near_left, far_left, near_right});
      if (dry(near_right, far_left, far_right))
        o.indices.insert(o.indices.end(), {near_right, far_left, far_right});
    }
}

}  // namespace

void Parser::parse_height_field(Object& o) {
  o.shape = Shape::kMesh;
  if (peek().keyword() && std::find(std::begin(kHeightFieldTypes), std::end(kHeightFieldTypes),
                                    peek().token.text) != std::end(kHeightFieldTypes))
    next();
  const SourceLocation where = location_of(peek());
  const Value name = parse_expression();
  if (name.kind != ValueKind::kString) fail_at(where, "height_field expects an image file name");
  HeightFieldOptions options;
  for (;;) {
    const Tok& tok = peek();
    if (tok.word("smooth")) {
      next();
      options.smooth = parse_bool_option();
    } else if (tok.word("water_level")) {
      next();
      options.water_level = parse_float();
    } else if (tok.word("hierarchy") || tok.word("premultiplied")) {
      next();
      parse_bool_option();  // a speed hint; an alpha channel is no height
    } else if (tok.word("gamma")) {
      next();
      parse_float();  // heights are data, read linear
    } else {
      break;
    }
  }
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
