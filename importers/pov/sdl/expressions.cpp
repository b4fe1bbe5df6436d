// Expressions: floats, vectors (2 to 5 components), colours and strings with POV-Ray's promotion
// rules (manual 3.3.1): a float where a vector is expected fills every component, a vector where
// a colour is expected gives its red, green, blue (filter, transmit) in order.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "importers/pov/sdl/builtins.h"
#include "importers/pov/sdl/parser.h"

namespace fb::pov::sdl {
namespace {

bool is_colour_word(const std::string& w) {
  static constexpr std::string_view kWords[] = {
      "color",  "colour", "rgb",   "rgbf", "rgbt",   "rgbft",    "srgb", "srgbf", "srgbt",
      "srgbft", "red",    "green", "blue", "filter", "transmit", "gray", "grey"};
  for (std::string_view k : kWords) {
    if (w == k) return true;
  }
  return false;
}

double srgb_decode(double c) {
  // IEC 61966-2-1, which POV-Ray 3.7's srgb keyword applies
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// ---- the values only #declare and #local hold (POV-Ray 3.7 reference, "Declare") ----

// texture {..} [texture {..} ...]: the first, with the others layered over it.
Texture parse_layered_texture(Parser& p) {
  Texture texture = p.parse_texture();
  while (p.peek().word("texture")) {
    p.next();
    p.add_texture_layer(texture, p.parse_texture());
  }
  return texture;
}

// sky_sphere { [Identifier] pigment {..} ... transforms }.
SkySphere parse_sky_sphere(Parser& p) {
  SkySphere sky;
  p.expect("{");
  for (;;) {
    Tok item = p.next();
    if (item.symbol("}")) break;
    if (item.identifier && item.value.get<SkySphere>()) {
      sky = *item.value.get<SkySphere>();
    } else if (item.word("pigment")) {
      sky.pigments.push_back(p.parse_pigment());
    } else if (auto m = p.parse_transform_item(item)) {
      sky.transform = *m * sky.transform;
    } else if (item.word("emission")) {
      p.parse_colour();
    } else {
      p.fail("unexpected " + item.token.text + " in sky_sphere");
    }
  }
  return sky;
}

// Blocks declared by name but not evaluated: skipped, held as an opaque value that names them.
constexpr std::string_view kOpaqueBlocks[] = {
    "texture_map", "normal_map", "slope_map",        "density_map", "density",  "fog",
    "rainbow",     "spline",     "interior_texture", "photons",     "radiosity"};

bool is_opaque_block(std::string_view w) {
  for (std::string_view block : kOpaqueBlocks) {
    if (w == block) return true;
  }
  return false;
}

Value skip_opaque_block(Parser& p, const std::string& w) {
  p.skip_block();
  Value value;
  value.kind = ValueKind::kOpaque;
  value.text = w;
  return value;
}

// function [(params)] { ... }, compiled (function_compiler.cpp).
Value function_value(Parser& p) {
  Value value;
  value.kind = ValueKind::kFunction;
  value.function = std::make_shared<const FunctionValue>(p.parse_function());
  return value;
}

// The [n][m]... after `array`: each size at least 1, their product within the element limit.
std::vector<size_t> parse_array_sizes(Parser& p, double& total) {
  std::vector<size_t> sizes;
  total = 1;
  while (p.peek().symbol("[")) {
    p.next();
    double n = p.parse_float();
    p.expect("]");
    if (!(n >= 1)) p.fail("array size " + number_string(n) + ": an array needs at least 1");
    total *= n;
    if (!(total <= static_cast<double>(p.options().limits.array_elements))) {
      const std::string count =
          total < 1e15 ? std::to_string(static_cast<uint64_t>(total)) : number_string(total);
      p.fail("array of " + count + " elements: " + p.array_limit_message());
    }
    sizes.push_back(static_cast<size_t>(n));
  }
  if (sizes.empty()) p.fail("expected the array's size [n]");
  return sizes;
}

// The initialiser list of dimension `dim` and those nested in it, filling `array` in row-major
// order from `index`.
void fill_array(Parser& p, ArrayValue& array, size_t dim, size_t& index) {
  const std::vector<size_t>& sizes = array.sizes;
  p.expect("{");
  size_t n = 0;
  for (;;) {
    if (p.accept("}")) break;
    if (n > 0) p.accept(",");  // POV-Ray also takes elements separated by blanks
    if (p.accept("}")) break;
    if (n >= sizes[dim]) p.fail("too many array initialisers");
    if (dim + 1 < sizes.size()) {
      fill_array(p, array, dim + 1, index);
    } else {
      array.elements[index++] = p.parse_rvalue();
    }
    ++n;
  }
  if (n != sizes[dim])
    p.fail("array initialiser has " + std::to_string(n) + " elements, the array " +
           std::to_string(sizes[dim]));
}

// array[n][m]... [{ initialisers }] (POV-Ray 3.7 reference, "Array Identifiers").
Value parse_array(Parser& p) {
  double total = 1;
  std::vector<size_t> sizes = parse_array_sizes(p, total);
  p.count_array_elements(static_cast<uint64_t>(total));
  auto array = std::make_shared<ArrayValue>();
  array->sizes = sizes;
  array->elements.resize(static_cast<size_t>(total));
  if (p.peek().symbol("{")) {
    size_t index = 0;
    fill_array(p, *array, 0, index);
  }
  Value value;
  value.kind = ValueKind::kArray;
  value.array = std::move(array);
  return value;
}

}  // namespace

Colour to_colour(const Value& value, bool float_fills_filter_transmit) {
  Colour c;
  if (value.kind == ValueKind::kFloat) {
    c.r = c.g = c.b = value.v[0];
    if (float_fills_filter_transmit) c.filter = c.transmit = value.v[0];
    return c;
  }
  c.r = value.v[0];
  c.g = value.dims > 1 ? value.v[1] : 0;
  c.b = value.dims > 2 ? value.v[2] : 0;
  c.filter = value.dims > 3 ? value.v[3] : 0;
  c.transmit = value.dims > 4 ? value.v[4] : 0;
  return c;
}

bool Parser::starts_colour(const Tok& tok) const {
  if (tok.keyword()) return is_colour_word(tok.token.text);
  return false;
}

// `colour` bodies: keywords rgb/rgbf/... and red/green/... in any order, or an expression
// followed by component keywords (`Red filter 0.5`).
Colour Parser::parse_colour(bool float_fills_filter_transmit) {
  Colour c;
  bool any = false;
  for (;;) {
    Tok tok = next();
    const std::string& w = tok.token.text;
    if (tok.word("color") || tok.word("colour")) {
      if (!any) continue;
      unget(std::move(tok));  // the next colour of a list
      break;
    }
    if (tok.keyword() && (w.rfind("rgb", 0) == 0 || w.rfind("srgb", 0) == 0) && is_colour_word(w)) {
      if (any) {  // `checker rgb <1,0,0> rgb <0,1,0>`: a second vector starts the next colour,
        unget(std::move(tok));  // as in POV-Ray (component keywords still modify this one)
        break;
      }
      bool srgb = w[0] == 's';
      std::string channels = w.substr(srgb ? 4 : 3);
      int dims = 3 + static_cast<int>(channels.size());
      Value value = parse_expression();
      if (!value.numeric()) fail("expected a colour vector after " + w);
      double comp[5] = {0, 0, 0, 0, 0};
      for (int i = 0; i < dims; ++i) {
        comp[i] = value.kind == ValueKind::kFloat ? value.v[0] : (i < value.dims ? value.v[i] : 0);
      }
      c.r = comp[0];
      c.g = comp[1];
      c.b = comp[2];
      c.filter = c.transmit = 0;
      if (channels == "f" || channels == "ft") c.filter = comp[3];
      if (channels == "t") c.transmit = comp[3];
      if (channels == "ft") c.transmit = comp[4];
      if (srgb) {
        c.r = srgb_decode(c.r);
        c.g = srgb_decode(c.g);
        c.b = srgb_decode(c.b);
      }
      any = true;
    } else if (tok.keyword() && (w == "red" || w == "green" || w == "blue" || w == "filter" ||
                                 w == "transmit" || w == "gray" || w == "grey")) {
      double f = parse_float();
      if (w == "red") c.r = f;
      if (w == "green") c.g = f;
      if (w == "blue") c.b = f;
      if (w == "filter") c.filter = f;
      if (w == "transmit") c.transmit = f;
      if (w == "gray" || w == "grey") c.r = c.g = c.b = f;
      any = true;
    } else if (!any && tok.token.kind != TokenKind::kEnd && !tok.symbol("}") && !tok.symbol("]") &&
               !tok.symbol(",")) {
      unget(std::move(tok));
      Value value = parse_expression();
      if (!value.numeric()) fail("expected a colour");
      c = to_colour(value, float_fills_filter_transmit);
      any = true;
    } else {
      unget(std::move(tok));
      break;
    }
  }
  if (!any) fail("expected a colour");
  return c;
}

double Parser::parse_float() {
  Value value = parse_expression();
  if (value.kind != ValueKind::kFloat) {
    // POV-Ray takes the first component of a vector where a float is expected
    if (value.kind == ValueKind::kVector || value.kind == ValueKind::kColour) return value.v[0];
    fail("expected a float");
  }
  return value.v[0];
}

// A count before a list of vectors (`vertex_vectors { 3 <...>`): no comparison, so that the
// '<' opens the first vector.
double Parser::parse_count() {
  Nesting guard(*this);
  Value value = parse_additive();
  if (value.kind != ValueKind::kFloat) fail("expected a count");
  return value.v[0];
}

Value Parser::parse_numeric(int dims) {
  Value value = parse_expression();
  if (!value.numeric()) fail("expected a " + std::string(dims == 1 ? "float" : "vector"));
  Value out;
  out.kind = dims == 1 ? ValueKind::kFloat : ValueKind::kVector;
  out.dims = dims;
  for (int i = 0; i < dims; ++i) {
    out.v[i] = value.kind == ValueKind::kFloat ? value.v[0] : (i < value.dims ? value.v[i] : 0);
  }
  return out;
}

Vec3d Parser::parse_vector() {
  Value value = parse_numeric(3);
  return {value.v[0], value.v[1], value.v[2]};
}

bool Parser::starts_value(const Tok& tok) const {
  return tok.token.kind == TokenKind::kNumber || tok.symbol("(") || tok.symbol("!") ||
         tok.symbol("-") || tok.symbol("+") || tok.symbol("<") || tok.word("on") ||
         tok.word("off") || tok.word("true") || tok.word("false") || tok.word("yes") ||
         tok.word("no") || (tok.identifier && tok.value.numeric()) || starts_colour(tok);
}

bool Parser::parse_bool_option() {
  if (!starts_value(peek())) return true;
  return std::abs(parse_float()) > 1e-10;
}

namespace {

// The shape of a binary operation's result: floats promote to the other operand's size.
Value combine(Parser& parser, const Value& a, const Value& b, double (*op)(double, double)) {
  if (a.kind == ValueKind::kString || b.kind == ValueKind::kString) {
    parser.fail("arithmetic on a string");
  }
  if (!a.numeric() || !b.numeric()) parser.fail("arithmetic on something that is not a number");
  Value out;
  if (a.kind == ValueKind::kFloat && b.kind == ValueKind::kFloat) {
    out = Value::number(op(a.v[0], b.v[0]));
    return out;
  }
  out.kind = (a.kind == ValueKind::kColour || b.kind == ValueKind::kColour) ? ValueKind::kColour
                                                                            : ValueKind::kVector;
  out.dims = out.kind == ValueKind::kColour ? 5 : std::max(a.dims, b.dims);
  for (int i = 0; i < out.dims; ++i) {
    double x = a.kind == ValueKind::kFloat ? a.v[0] : (i < a.dims ? a.v[i] : 0);
    double y = b.kind == ValueKind::kFloat ? b.v[0] : (i < b.dims ? b.v[i] : 0);
    out.v[i] = op(x, y);
  }
  return out;
}

double truth(bool b) {
  return b ? 1.0 : 0.0;
}

}  // namespace

Value Parser::parse_rvalue() {
  Tok tok = next();
  if (tok.keyword()) {
    const std::string& w = tok.token.text;
    if (is_object_keyword(tok)) return Value::of(parse_object(tok));
    if (w == "pigment") return Value::of(parse_pigment());
    if (w == "finish") return Value::of(parse_finish(default_texture_.finish));
    if (w == "normal") return Value::of(parse_normal());
    if (w == "texture") return Value::of(parse_layered_texture(*this));
    if (w == "interior") return Value::of(parse_interior());
    if (w == "media") return Value::of(parse_media(tok));
    if (w == "material") return Value::of(parse_material());
    if (w == "camera") return Value::of(parse_camera(tok));
    if (w == "transform") return Value::of(parse_transform_block());
    if (w == "color_map" || w == "colour_map" || w == "pigment_map") {
      return Value::of(parse_colour_map(w == "pigment_map"));
    }
    if (w == "sky_sphere") return Value::of(parse_sky_sphere(*this));
    if (is_opaque_block(w)) return skip_opaque_block(*this, w);
    if (w == "function") return function_value(*this);
    if (w == "array") return parse_array(*this);
  }
  unget(std::move(tok));
  return parse_expression();
}

Value Parser::parse_expression() {
  Nesting guard(*this);
  return parse_ternary();
}

// The branches stay at the same nesting level, so a '>' after them still closes a vector.
Value Parser::parse_ternary() {
  Value cond = parse_logic();
  if (peek().symbol("?")) {
    next();
    if (cond.kind != ValueKind::kFloat) fail("expected a float before '?'");
    Value a = parse_ternary();
    expect(":");
    Value b = parse_ternary();
    return std::abs(cond.v[0]) > 1e-10 ? a : b;
  }
  return cond;
}

Value Parser::parse_logic() {
  Value left = parse_relation();
  for (;;) {
    const Tok& tok = peek();
    bool is_and = tok.symbol("&");
    if (!is_and && !tok.symbol("|")) return left;
    next();
    Value right = parse_relation();
    if (left.kind != ValueKind::kFloat || right.kind != ValueKind::kFloat) {
      fail("'&' and '|' need floats");
    }
    bool a = std::abs(left.v[0]) > 1e-10, b = std::abs(right.v[0]) > 1e-10;
    left = Value::number(truth(is_and ? a && b : a || b));
  }
}

Value Parser::parse_relation() {
  Value left = parse_additive();
  for (;;) {
    const Tok& tok = peek();
    if (tok.token.kind != TokenKind::kSymbol) return left;
    std::string op = tok.token.text;
    if (op != "<" && op != "<=" && op != "=" && op != "!=" && op != ">=" && op != ">") return left;
    if (op == ">" && nesting == vector_level_) return left;  // closes the vector literal
    // after a vector, '<' opens the next one (`box { <0,0,0> <1,1,1> }` needs no comma)
    if (left.kind == ValueKind::kVector && op != "=" && op != "!=") return left;
    next();
    Value right = parse_additive();
    if (left.kind == ValueKind::kString && right.kind == ValueKind::kString) {
      int c = left.text.compare(right.text);
      left = Value::number(truth(op == "<"    ? c < 0
                                 : op == "<=" ? c <= 0
                                 : op == "="  ? c == 0
                                 : op == "!=" ? c != 0
                                 : op == ">=" ? c >= 0
                                              : c > 0));
      continue;
    }
    if (left.kind != ValueKind::kFloat || right.kind != ValueKind::kFloat) {
      if (left.numeric() && right.numeric() && (op == "=" || op == "!=")) {
        Value diff = combine(*this, left, right, [](double a, double b) { return a - b; });
        bool equal = true;
        for (int i = 0; i < diff.dims; ++i)
          equal = equal && std::abs(diff.v[i]) < 1e-10;
        left = Value::number(truth(op == "=" ? equal : !equal));
        continue;
      }
      fail("comparison '" + op + "' needs floats");
    }
    double a = left.v[0], b = right.v[0];
    left = Value::number(truth(op == "<"    ? a < b
                               : op == "<=" ? a <= b
                               : op == "="  ? a == b
                               : op == "!=" ? a != b
                               : op == ">=" ? a >= b
                                            : a > b));
  }
}

Value Parser::parse_additive() {
  Value left = parse_multiplicative();
  for (;;) {
    const Tok& tok = peek();
    bool plus = tok.symbol("+");
    if (!plus && !tok.symbol("-")) return left;
    next();
    Value right = parse_multiplicative();
    left = plus ? combine(*this, left, right, [](double a, double b) { return a + b; })
                : combine(*this, left, right, [](double a, double b) { return a - b; });
  }
}

Value Parser::parse_multiplicative() {
  Value left = parse_unary();
  for (;;) {
    const Tok& tok = peek();
    bool times = tok.symbol("*");
    if (!times && !tok.symbol("/")) return left;
    next();
    Value right = parse_unary();
    // POV-Ray divides by zero without stopping; keep the result finite (manual: "division by
    // zero" is a warning) so no NaN reaches the scene
    left = times ? combine(*this, left, right, [](double a, double b) { return a * b; })
                 : combine(*this, left, right, [](double a, double b) {
                     return b == 0 ? (a == 0 ? 0.0 : std::copysign(1e300, a)) : a / b;
                   });
  }
}

Value Parser::parse_unary() {
  Nesting guard(*this);  // `- - - ... 1` recurses here, not through parse_expression
  Tok tok = next();
  if (tok.symbol("-") || tok.symbol("+")) {
    Value value = parse_unary();
    if (!value.numeric()) fail("expected a number after '" + tok.token.text + "'");
    if (tok.symbol("-")) {
      for (int i = 0; i < value.dims; ++i)
        value.v[i] = -value.v[i];
    }
    return value;
  }
  if (tok.symbol("!")) {
    Value value = parse_unary();
    if (value.kind != ValueKind::kFloat) fail("'!' needs a float");
    return Value::number(truth(std::abs(value.v[0]) <= 1e-10));
  }
  unget(std::move(tok));
  return parse_postfix();
}

Value Parser::parse_postfix() {
  Value value = parse_primary();
  while (peek().symbol(".")) {
    next();
    Tok member = next();
    if (member.token.kind != TokenKind::kWord) fail("expected a component name after '.'");
    const std::string& m = member.token.text;
    if (!value.numeric()) fail("'." + m + "' needs a vector or colour");
    int index = -1;
    if (m == "x" || m == "u" || m == "red") index = 0;
    if (m == "y" || m == "v" || m == "green") index = 1;
    if (m == "z" || m == "blue") index = 2;
    if (m == "t" || m == "filter") index = 3;
    if (m == "transmit") index = 4;
    if (m == "gray" || m == "grey") {
      // POV-Ray's grey: 0.297 R + 0.589 G + 0.114 B (colour.h GREY_SCALE)
      value = Value::number(0.297 * value.v[0] + 0.589 * value.v[1] + 0.114 * value.v[2]);
      continue;
    }
    if (index < 0) fail("unknown component '." + m + "'");
    if (value.kind == ValueKind::kFloat) {
      // a float promotes to a vector of any size, so every component is the float
      continue;
    }
    if (index >= value.dims)
      fail("'." + m + "' is past the vector's " + std::to_string(value.dims) + " components");
    value = Value::number(value.v[index]);
  }
  return value;
}

Value Parser::index_array(const Value& array_value) {
  const ArrayValue& array = *array_value.array;
  size_t index = 0;
  for (size_t d = 0; d < array.sizes.size(); ++d) {
    expect("[");
    double i = parse_float();
    expect("]");
    if (!(i >= 0 && i < static_cast<double>(array.sizes[d]))) {
      fail("array index " + number_string(i) + " out of range 0.." +
           std::to_string(array.sizes[d] - 1));
    }
    index = index * array.sizes[d] + static_cast<size_t>(i);
  }
  if (!array.elements[index]) fail("array element " + std::to_string(index) + " not initialised");
  return *array.elements[index];
}

Value Parser::parse_primary() {
  Tok tok = next();
  switch (tok.token.kind) {
    case TokenKind::kNumber:
      return Value::number(tok.token.number);
    case TokenKind::kString:
      return Value::string(tok.token.text);
    case TokenKind::kEnd:
      fail("unexpected end of file in an expression");
    case TokenKind::kDirective:
      fail("unexpected #" + tok.token.text + " in an expression");
    default:
      break;
  }
  if (tok.symbol("(")) {
    Value value = parse_expression();
    expect(")");
    return value;
  }
  if (tok.symbol("<")) {
    Value value;
    value.kind = ValueKind::kVector;
    value.dims = 0;
    int saved = vector_level_;
    vector_level_ = nesting + 1;
    for (;;) {
      Value c = parse_expression();
      if (c.kind != ValueKind::kFloat) fail("vector components must be floats");
      if (value.dims == 5) fail("a vector has at most 5 components");
      value.v[value.dims++] = c.v[0];
      if (peek().symbol(",")) {
        next();
        if (peek().symbol(">")) break;  // a trailing comma, which POV-Ray accepts
        continue;
      }
      // POV-Ray also reads components separated by blanks: <4 0 0>
      const Tok& more = peek();
      if (more.token.kind == TokenKind::kNumber || more.symbol("(") ||
          (more.identifier && more.value.kind == ValueKind::kFloat)) {
        continue;
      }
      break;
    }
    vector_level_ = saved;
    expect(">");
    if (value.dims == 1) return Value::number(value.v[0]);
    return value;
  }
  if (tok.token.kind == TokenKind::kSymbol)
    fail("unexpected '" + tok.token.text + "' in an expression");
  if (tok.identifier) {
    const Value& value = tok.value;
    // (parse_postfix reads a pigment function's .red, .gray ...)
    if (value.kind == ValueKind::kFunction && peek().symbol("("))
      return call_function(*value.function, tok);
    if (value.kind == ValueKind::kOpaque && value.text == "spline" && peek().symbol("(")) {
      skip_parenthesised();
      unsupported("spline", location_of(tok));
      return Value::vector({0, 0, 0});
    }
    return value;
  }
  const std::string& w = tok.token.text;
  if (is_colour_word(w)) {
    unget(std::move(tok));
    return Value::colour(parse_colour());
  }
  if (auto value = builtin(*this, tok)) return *value;
  fail("unknown identifier or keyword '" + w + "' in an expression");
}

}  // namespace fb::pov::sdl
