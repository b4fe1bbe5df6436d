// blob { threshold T  sphere { C, R, [strength] S }  cylinder { A, B, R, [strength] S }
// component S, R, C  [sturm] [hierarchy] } (POV-Ray 3.7 reference, "Blob"): the components as
// written, each placed by its own transforms; the converter makes the solid (core/math/blob.h).
// No components is no error: a loop may place none (advanced/biscuit.pov's depend on inside(),
// which the evaluator answers with zero); the converter leaves the empty blob out, warning.
#include <cmath>

#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {

namespace {

// A component's radius and strength: a radius of zero or less would divide by zero, and a
// non-finite strength poisons the field.
void check_component(Parser& p, const SourceLocation& where, const BlobComponentStatement& c) {
  if (!(c.radius > 0 && std::isfinite(c.radius)))
    p.fail_at(where, "blob component radius " + number_string(c.radius) +
                         ": it must be positive and finite");
  if (!std::isfinite(c.strength))
    p.fail_at(where, "blob component strength " + number_string(c.strength) + ": not finite");
  if (c.cylinder && !(length(c.b - c.a) > 0))
    p.fail_at(where, "blob cylinder component with both ends at the same point");
}

}  // namespace

void Parser::parse_blob(Object& o) {
  o.shape = Shape::kBlob;
  o.r0 = 1;  // POV-Ray's default threshold
  for (;;) {
    Tok tok = next();  // directives run: #while loops write components
    if (tok.word("threshold")) {
      const SourceLocation where = location_of(peek());
      o.r0 = parse_float();
      if (!(o.r0 > 0 && std::isfinite(o.r0)))
        fail_at(where,
                "blob threshold " + number_string(o.r0) + ": it must be positive and finite");
    } else if (tok.word("sturm") || tok.word("hierarchy")) {
      parse_bool_option();               // the quartics are solved exactly either way; a speed hint
    } else if (tok.word("component")) {  // the old syntax: component Strength, Radius, Centre
      const SourceLocation where = location_of(tok);
      BlobComponentStatement c;
      c.strength = parse_float();
      accept(",");
      c.radius = parse_float();
      accept(",");
      c.a = parse_vector();
      check_component(*this, where, c);
      count_objects(1);
      o.blob_components.push_back(c);
    } else if (tok.word("sphere") || tok.word("cylinder")) {
      const SourceLocation where = location_of(tok);
      BlobComponentStatement c;
      c.cylinder = tok.word("cylinder");
      expect("{");
      c.a = parse_vector();
      accept(",");
      if (c.cylinder) {
        c.b = parse_vector();
        accept(",");
      }
      c.radius = parse_float();
      accept(",");
      if (peek().word("strength")) next();
      c.strength = parse_float();
      check_component(*this, where, c);
      for (;;) {
        Tok item = next();
        if (item.symbol("}")) break;
        if (std::optional<Matrix> m = parse_transform_item(item)) {
          c.blob_from_component = *m * c.blob_from_component;
        } else if (item.word("texture") || item.word("pigment") || item.word("finish") ||
                   item.word("normal")) {
          unsupported("blob component " + item.token.text, location_of(item));
          skip_block();  // the blob's own texture covers it
        } else {
          fail("unexpected '" + item.token.text + "' in a blob component");
        }
      }
      const double det = c.blob_from_component.determinant3x3();
      if (!(std::isfinite(det) && det != 0))
        fail_at(where, "blob component with a singular transform");
      count_objects(1);
      o.blob_components.push_back(c);
    } else {
      unget(std::move(tok));
      break;
    }
  }
}

}  // namespace fb::pov::sdl
