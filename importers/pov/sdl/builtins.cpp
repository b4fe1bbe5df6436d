#include "importers/pov/sdl/builtins.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "importers/pov/sdl/keyword_table.h"
#include "importers/pov/sdl/object_queries.h"

namespace fb::pov::sdl {

std::string number_string(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;

// str(F, L, P): L the minimum width (negative: padded with zeros), P the digits after the point
// (negative: 6, as POV-Ray 3.7 prints str(2.5, 6, -1) as "2.500000").
std::string format_float(double f, double width, double precision) {
  int w = static_cast<int>(std::clamp(width, -64.0, 64.0));
  int p = precision < 0 ? 6 : static_cast<int>(std::min(precision, 20.0));
  char text[160];
  if (w < 0) {
    std::snprintf(text, sizeof text, "%0*.*f", -w, p, f);
  } else {
    std::snprintf(text, sizeof text, "%*.*f", w, p, f);
  }
  return text;
}

Vec3d to_vec3(const Value& v) {
  if (v.kind == ValueKind::kFloat) return {v.v[0], v.v[0], v.v[0]};
  return {v.v[0], v.dims > 1 ? v.v[1] : 0, v.dims > 2 ? v.v[2] : 0};
}

Value from_vec3(Vec3d v) {
  return Value::vector({v.x, v.y, v.z});
}

// Right-hand rotation of `v` about unit `axis` by `angle` radians (Rodrigues), which is what
// POV-Ray's rotate does numerically (../shared/notes/povray-camera.md 1.1).
Vec3d rotate_about(Vec3d v, Vec3d axis, double angle) {
  double c = std::cos(angle), s = std::sin(angle);
  Vec3d k = axis;
  Vec3d kxv{k.y * v.z - k.z * v.y, k.z * v.x - k.x * v.z, k.x * v.y - k.y * v.x};
  double kdv = k.x * v.x + k.y * v.y + k.z * v.z;
  return {v.x * c + kxv.x * s + k.x * kdv * (1 - c), v.y * c + kxv.y * s + k.y * kdv * (1 - c),
          v.z * c + kxv.z * s + k.z * kdv * (1 - c)};
}

class Args {
 public:
  Args(Parser& parser, const std::string& name) : p_(parser), name_(name) { p_.expect("("); }
  void comma() { p_.expect(","); }
  Value any() {
    if (count_++ > 0) comma();
    return p_.parse_expression();
  }
  double f() {
    Value v = any();
    if (v.kind != ValueKind::kFloat) p_.fail(name_ + "() expects a float argument");
    return v.v[0];
  }
  Vec3d vec() {
    Value v = any();
    if (!v.numeric()) p_.fail(name_ + "() expects a vector argument");
    return to_vec3(v);
  }
  std::string s() {
    Value v = any();
    if (v.kind != ValueKind::kString) p_.fail(name_ + "() expects a string argument");
    return v.text;
  }
  bool more() { return p_.peek().symbol(","); }
  void end() { p_.expect(")"); }

 private:
  Parser& p_;
  std::string name_;
  int count_ = 0;
};

Value boolean(bool b) {
  return Value::number(b ? 1 : 0);
}

// ---- constants and render settings (POV-Ray 3.7 reference, "Float Identifiers" and
// "Built-in Vector Identifiers") ----

struct Constant {
  std::string_view name;
  Value (*value)(const EvaluateOptions&);
};

using O = const EvaluateOptions&;
constexpr Constant kConstants[] = {
    {"pi", [](O) { return Value::number(std::numbers::pi); }},
    {"tau", [](O) { return Value::number(2 * std::numbers::pi); }},
    {"true", [](O) { return Value::number(1); }},
    {"yes", [](O) { return Value::number(1); }},
    {"on", [](O) { return Value::number(1); }},
    {"false", [](O) { return Value::number(0); }},
    {"no", [](O) { return Value::number(0); }},
    {"off", [](O) { return Value::number(0); }},
    {"x",
     [](O) {
       return Value::vector({1, 0, 0});
     }},
    {"y",
     [](O) {
       return Value::vector({0, 1, 0});
     }},
    {"z",
     [](O) {
       return Value::vector({0, 0, 1});
     }},
    {"t",
     [](O) {
       return Value::vector({0, 0, 0, 1});
     }},
    {"u",
     [](O) {
       return Value::vector({1, 0});
     }},
    {"v",
     [](O) {
       return Value::vector({0, 1});
     }},
    {"clock", [](O o) { return Value::number(o.clock); }},
    {"clock_delta",
     [](O o) { return Value::number(o.animation ? o.animation->clock_delta() : 0); }},
    {"clock_on", [](O o) { return Value::number(o.animation ? 1 : 0); }},
    {"initial_clock",
     [](O o) { return Value::number(o.animation ? o.animation->initial_clock : o.clock); }},
    {"final_clock",
     [](O o) { return Value::number(o.animation ? o.animation->final_clock : o.clock); }},
    {"frame_number", [](O o) { return Value::number(o.frame_number); }},
    {"initial_frame",
     [](O o) { return Value::number(o.animation ? o.animation->initial_frame : o.frame_number); }},
    // A cyclic animation reads one frame more, as POV-Ray 3.7 reports it.
    {"final_frame",
     [](O o) {
       return Value::number(o.animation ? o.animation->final_frame + (o.animation->cyclic ? 1 : 0)
                                        : o.frame_number);
     }},
    {"image_width", [](O o) { return Value::number(o.image_width); }},
    {"image_height", [](O o) { return Value::number(o.image_height); }},
    {"version", [](O) { return Value::number(3.7); }},
};

// ---- float functions of one float (POV-Ray 3.7 reference, "Float Functions") ----

// The domain is checked before the call, so that ln(0) names its cause instead of "overflows".
struct UnaryMath {
  std::string_view name;
  double (*apply)(Parser&, double);
};

using P = Parser&;
constexpr UnaryMath kUnaryMath[] = {
    {"abs", [](P, double x) { return std::abs(x); }},
    {"acos", [](P, double x) { return std::acos(std::clamp(x, -1.0, 1.0)); }},
    {"acosh", [](P, double x) { return std::acosh(std::max(x, 1.0)); }},
    {"asin", [](P, double x) { return std::asin(std::clamp(x, -1.0, 1.0)); }},
    {"asinh", [](P, double x) { return std::asinh(x); }},
    {"atan", [](P, double x) { return std::atan(x); }},
    {"atanh", [](P, double x) { return std::atanh(std::clamp(x, -1.0 + 1e-15, 1.0 - 1e-15)); }},
    {"ceil", [](P, double x) { return std::ceil(x); }},
    {"cos", [](P, double x) { return std::cos(x); }},
    {"cosh", [](P, double x) { return std::cosh(x); }},
    {"degrees", [](P, double x) { return x * kDegrees; }},
    {"radians", [](P, double x) { return x / kDegrees; }},
    {"exp", [](P, double x) { return std::exp(x); }},
    {"floor", [](P, double x) { return std::floor(x); }},
    {"int", [](P, double x) { return std::trunc(x); }},
    {"ln",
     [](P p, double x) { return x > 0 ? std::log(x) : (p.fail("ln of a number <= 0"), 0.0); }},
    {"log",
     [](P p, double x) { return x > 0 ? std::log10(x) : (p.fail("log of a number <= 0"), 0.0); }},
    {"sin", [](P, double x) { return std::sin(x); }},
    {"sinh", [](P, double x) { return std::sinh(x); }},
    {"sqrt",
     [](P p, double x) {
       return x >= 0 ? std::sqrt(x) : (p.fail("sqrt of a negative number"), 0.0);
     }},
    {"sqr", [](P, double x) { return x * x; }},
    {"tan", [](P, double x) { return std::tan(x); }},
    {"tanh", [](P, double x) { return std::tanh(x); }},
};

Value unary_math(Parser& p, const std::string& word, const UnaryMath& f) {
  Args a(p, word);
  double x = a.f();
  if (f.name == "atan" && a.more()) {
    double y = a.f();  // POV-Ray 3.7 accepts atan(a, b) as atan2
    a.end();
    return Value::number(std::atan2(x, y));
  }
  a.end();
  double r = f.apply(p, x);
  if (!std::isfinite(r)) p.fail(word + "() overflows");
  return Value::number(r);
}

// ---- float functions of two floats ----

struct BinaryMath {
  std::string_view name;
  double (*apply)(Parser&, double, double);
};

// The bitwise functions work on the floats' integer parts, clamped so that the cast is defined.
int64_t integer_part(double d) {
  return static_cast<int64_t>(std::clamp(d, -9e18, 9e18));
}

constexpr BinaryMath kBinaryMath[] = {
    {"atan2", [](P, double x, double y) { return std::atan2(x, y); }},
    {"div", [](P p, double x,
               double y) { return y == 0 ? (p.fail("div() by zero"), 0.0) : std::trunc(x / y); }},
    {"mod", [](P p, double x,
               double y) { return y == 0 ? (p.fail("mod() by zero"), 0.0) : std::fmod(x, y); }},
    {"pow", [](P, double x, double y) { return std::pow(x, y); }},
    {"bitwise_and",
     [](P, double x, double y) { return static_cast<double>(integer_part(x) & integer_part(y)); }},
    {"bitwise_or",
     [](P, double x, double y) { return static_cast<double>(integer_part(x) | integer_part(y)); }},
    {"bitwise_xor",
     [](P, double x, double y) { return static_cast<double>(integer_part(x) ^ integer_part(y)); }},
};

Value binary_math(Parser& p, const std::string& word, const BinaryMath& f) {
  Args a(p, word);
  double x = a.f(), y = a.f();
  a.end();
  double r = f.apply(p, x, y);
  if (!std::isfinite(r)) p.fail(word + "() gives no finite number");
  return Value::number(r);
}

// ---- the other functions, one handler per family; each reads its own arguments ----

using Handler = Value (*)(Parser&, const Tok&);

Value min_max(Parser& p, const Tok& tok) {
  const std::string& word = tok.token.text;
  Args a(p, word);
  double r = a.f();
  while (a.more())
    r = word == "max" ? std::max(r, a.f()) : std::min(r, a.f());
  a.end();
  return Value::number(r);
}

// select(A, B, C [, D]): B if A < 0, C if A == 0 (or A >= 0 with three arguments), else D.
Value select_by_sign(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  double s = a.f();
  Value neg = a.any(), zero = a.any();
  if (a.more()) {
    Value pos = a.any();
    a.end();
    return s < 0 ? neg : s == 0 ? zero : pos;
  }
  a.end();
  return s < 0 ? neg : zero;
}

// ---- vector functions (POV-Ray 3.7 reference, "Vector Functions") ----

Value vector_length(Parser& p, const Tok& tok) {
  const std::string& word = tok.token.text;
  Args a(p, word);
  Vec3d v = a.vec();
  a.end();
  double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  if (word == "vlength") return Value::number(len);
  if (len == 0) return from_vec3({0, 0, 0});  // POV-Ray warns and returns <0,0,0>
  return from_vec3({v.x / len, v.y / len, v.z / len});
}

Value vector_product(Parser& p, const Tok& tok) {
  const std::string& word = tok.token.text;
  Args a(p, word);
  Vec3d u = a.vec(), v = a.vec();
  a.end();
  if (word == "vdot") return Value::number(u.x * v.x + u.y * v.y + u.z * v.z);
  return from_vec3({u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x});
}

Value vrotate(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  Vec3d v = a.vec(), r = a.vec();
  a.end();
  // about x, then y, then z, as `rotate`
  v = rotate_about(v, {1, 0, 0}, r.x / kDegrees);
  v = rotate_about(v, {0, 1, 0}, r.y / kDegrees);
  v = rotate_about(v, {0, 0, 1}, r.z / kDegrees);
  return from_vec3(v);
}

Value vaxis_rotate(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  Vec3d v = a.vec(), axis = a.vec();
  double angle = a.f();
  a.end();
  double len = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
  if (len == 0) p.fail("vaxis_rotate about a zero axis");
  return from_vec3(rotate_about(v, {axis.x / len, axis.y / len, axis.z / len}, angle / kDegrees));
}

Value vturbulence(Parser& p, const Tok& tok) {
  // approximated: no displacement (docs/pov.md)
  Args a(p, tok.token.text);
  a.f();
  a.f();
  a.f();
  a.vec();
  a.end();
  return from_vec3({0, 0, 0});
}

// ---- string functions (POV-Ray 3.7 reference, "String Functions") ----

Value vstr(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  double n = a.f();
  Value v = a.any();
  std::string sep = a.s();
  double width = a.f(), precision = a.f();
  a.end();
  std::string out;
  int dims = static_cast<int>(std::clamp(n, 1.0, 5.0));
  for (int i = 0; i < dims; ++i) {
    if (i) out += sep;
    double c = v.kind == ValueKind::kFloat ? v.v[0] : (i < v.dims ? v.v[i] : 0);
    out += format_float(c, width, precision);
  }
  return Value::string(out);
}

Value str(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  double f = a.f(), width = a.f(), precision = a.f();
  a.end();
  return Value::string(format_float(f, width, precision));
}

Value concat(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  std::string out = a.s();
  while (a.more()) {
    out += a.s();
    p.check_string(out);
  }
  a.end();
  return Value::string(out);
}

Value chr(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  double c = a.f();
  a.end();
  return Value::string(std::string(1, static_cast<char>(static_cast<int>(c) & 0xff)));
}

// The functions of one string: asc, strlen, val, strupr, strlwr, file_exists.
Value of_one_string(Parser& p, const Tok& tok) {
  const std::string& word = tok.token.text;
  Args a(p, word);
  std::string s = a.s();
  a.end();
  if (word == "asc") return Value::number(s.empty() ? 0 : static_cast<unsigned char>(s[0]));
  if (word == "strlen") return Value::number(static_cast<double>(s.size()));
  if (word == "val") return Value::number(std::strtod(s.c_str(), nullptr));
  if (word == "file_exists") return boolean(p.resolve_include(s, nullptr, false).has_value());
  for (char& c : s) {
    c = static_cast<char>(word == "strupr" ? std::toupper(static_cast<unsigned char>(c))
                                           : std::tolower(static_cast<unsigned char>(c)));
  }
  return Value::string(s);
}

Value compare_strings(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  std::string s = a.s(), t = a.s();
  a.end();
  int c = s.compare(t);
  return Value::number(c < 0 ? -1 : c > 0 ? 1 : 0);
}

// substr(S, P, L): L characters from the P-th (1-based).
Value substr(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  std::string s = a.s();
  double start = a.f(), length = a.f();
  a.end();
  if (start < 1 || length < 0 || start - 1 + length > static_cast<double>(s.size())) {
    p.fail("substr() range outside the string");
  }
  return Value::string(s.substr(static_cast<size_t>(start) - 1, static_cast<size_t>(length)));
}

// ---- random numbers: seed() opens a stream, rand() draws from it in [0, 1] ----

Value random_stream(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  double s = a.f();
  a.end();
  return Value::number(static_cast<double>(p.new_random_stream(s)));
}

Value random_draw(Parser& p, const Tok& tok) {
  Args a(p, tok.token.text);
  double stream = a.f();
  a.end();
  if (!(stream >= 0 && stream < 1e9)) p.fail("rand() of something that is not a seed()");
  size_t index = static_cast<size_t>(stream);
  try {
    return Value::number(static_cast<double>(p.next_random(index)) / 4294967295.0);
  } catch (const std::out_of_range&) {
    p.fail("rand() of something that is not a seed()");
  }
}

// ---- identifiers and arrays ----

// defined(A) or defined(A[i]...): the name is read raw, since a lookup would fail on it.
Value is_defined(Parser& p, const Tok&) {
  p.expect("(");
  Token name = p.raw_next();
  bool defined = name.kind == TokenKind::kWord && p.find(name.text) != nullptr;
  const Tok& after = p.peek();
  if (after.symbol("[")) {
    // defined(A[i]): is the element set?
    Value* array = p.find(name.text);
    bool inside = array && array->kind == ValueKind::kArray;
    size_t index = 0;
    for (size_t d = 0; inside && d < array->array->sizes.size(); ++d) {
      p.expect("[");
      double i = p.parse_float();
      p.expect("]");
      inside = i >= 0 && i < static_cast<double>(array->array->sizes[d]);
      if (inside) index = index * array->array->sizes[d] + static_cast<size_t>(i);
    }
    defined = inside && array->array->elements[index].has_value();
  }
  p.expect(")");
  return boolean(defined);
}

Value array_dimensions(Parser& p, const Tok& tok) {
  const std::string& word = tok.token.text;
  Args a(p, word);
  Value array = a.any();
  if (array.kind != ValueKind::kArray) p.fail(word + "() expects an array");
  if (word == "dimensions") {
    a.end();
    return Value::number(static_cast<double>(array.array->sizes.size()));
  }
  double d = a.f();
  a.end();
  if (!(d >= 1 && d <= static_cast<double>(array.array->sizes.size()))) {
    p.fail("dimension_size(): no dimension " + number_string(d));
  }
  return Value::number(static_cast<double>(array.array->sizes[static_cast<size_t>(d) - 1]));
}

struct Function {
  std::string_view name;
  Handler call;
};

constexpr Function kFunctions[] = {
    {"max", min_max},
    {"min", min_max},
    {"select", select_by_sign},
    {"vlength", vector_length},
    {"vnormalize", vector_length},
    {"vdot", vector_product},
    {"vcross", vector_product},
    {"vrotate", vrotate},
    {"vaxis_rotate", vaxis_rotate},
    {"vturbulence", vturbulence},
    {"vstr", vstr},
    {"str", str},
    {"concat", concat},
    {"chr", chr},
    {"asc", of_one_string},
    {"strlen", of_one_string},
    {"val", of_one_string},
    {"strupr", of_one_string},
    {"strlwr", of_one_string},
    {"file_exists", of_one_string},
    {"strcmp", compare_strings},
    {"substr", substr},
    {"seed", random_stream},
    {"rand", random_draw},
    {"defined", is_defined},
    {"dimensions", array_dimensions},
    {"dimension_size", array_dimensions},
    {"inside", inside_function},
    {"trace", trace_function},
    {"min_extent", extent_function},
    {"max_extent", extent_function},
};

}  // namespace

std::optional<Value> builtin(Parser& p, const Tok& tok) {
  const std::string& word = tok.token.text;
  if (const Constant* c = find_keyword(kConstants, word)) return c->value(p.options());
  if (const UnaryMath* f = find_keyword(kUnaryMath, word)) return unary_math(p, word, *f);
  if (const BinaryMath* f = find_keyword(kBinaryMath, word)) return binary_math(p, word, *f);
  if (const Function* f = find_keyword(kFunctions, word)) return f->call(p, tok);
  return std::nullopt;
}

}  // namespace fb::pov::sdl
