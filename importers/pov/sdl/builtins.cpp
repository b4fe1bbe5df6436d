#include "importers/pov/sdl/builtins.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

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

}  // namespace

std::optional<Value> builtin(Parser& p, const Tok& tok) {
  const std::string& word = tok.token.text;
  const std::string_view w = word;  // compared by length first
  const EvaluateOptions& o = p.options();
  // constants and settings
  if (w == "pi") return Value::number(std::numbers::pi);
  if (w == "tau") return Value::number(2 * std::numbers::pi);
  if (w == "true" || w == "yes" || w == "on") return Value::number(1);
  if (w == "false" || w == "no" || w == "off") return Value::number(0);
  if (w == "x") return Value::vector({1, 0, 0});
  if (w == "y") return Value::vector({0, 1, 0});
  if (w == "z") return Value::vector({0, 0, 1});
  if (w == "t") return Value::vector({0, 0, 0, 1});
  if (w == "u") return Value::vector({1, 0});
  if (w == "v") return Value::vector({0, 1});
  if (w == "clock") return Value::number(o.clock);
  if (w == "clock_delta") return Value::number(0);
  if (w == "clock_on") return Value::number(0);
  if (w == "initial_clock" || w == "final_clock") return Value::number(o.clock);
  if (w == "frame_number" || w == "initial_frame" || w == "final_frame") {
    return Value::number(o.frame_number);
  }
  if (w == "image_width") return Value::number(o.image_width);
  if (w == "image_height") return Value::number(o.image_height);
  if (w == "version") return Value::number(3.7);

  static const char* const kFloat1[] = {"abs",   "acos",  "acosh", "asin", "asinh",   "atan",
                                        "atanh", "ceil",  "cos",   "cosh", "degrees", "radians",
                                        "exp",   "floor", "int",   "ln",   "sin",     "sinh",
                                        "sqrt",  "tan",   "tanh",  "log",  "sqr"};
  for (const char* name : kFloat1) {
    if (w != name) continue;
    Args a(p, word);
    double x = a.f();
    if (w == "atan" && a.more()) {
      double y = a.f();  // POV-Ray 3.7 accepts atan(a, b) as atan2
      a.end();
      return Value::number(std::atan2(x, y));
    }
    a.end();
    double r = 0;
    if (w == "abs") r = std::abs(x);
    if (w == "acos") r = std::acos(std::clamp(x, -1.0, 1.0));
    if (w == "acosh") r = std::acosh(std::max(x, 1.0));
    if (w == "asin") r = std::asin(std::clamp(x, -1.0, 1.0));
    if (w == "asinh") r = std::asinh(x);
    if (w == "atan") r = std::atan(x);
    if (w == "atanh") r = std::atanh(std::clamp(x, -1.0 + 1e-15, 1.0 - 1e-15));
    if (w == "ceil") r = std::ceil(x);
    if (w == "cos") r = std::cos(x);
    if (w == "cosh") r = std::cosh(x);
    if (w == "degrees") r = x * kDegrees;
    if (w == "radians") r = x / kDegrees;
    if (w == "exp") r = std::exp(x);
    if (w == "floor") r = std::floor(x);
    if (w == "int") r = std::trunc(x);
    if (w == "ln") r = x > 0 ? std::log(x) : (p.fail("ln of a number <= 0"), 0.0);
    if (w == "log") r = x > 0 ? std::log10(x) : (p.fail("log of a number <= 0"), 0.0);
    if (w == "sin") r = std::sin(x);
    if (w == "sinh") r = std::sinh(x);
    if (w == "sqrt") r = x >= 0 ? std::sqrt(x) : (p.fail("sqrt of a negative number"), 0.0);
    if (w == "sqr") r = x * x;
    if (w == "tan") r = std::tan(x);
    if (w == "tanh") r = std::tanh(x);
    if (!std::isfinite(r)) p.fail(word + "() overflows");
    return Value::number(r);
  }
  if (w == "atan2" || w == "div" || w == "mod" || w == "pow" || w == "bitwise_and" ||
      w == "bitwise_or" || w == "bitwise_xor") {
    Args a(p, word);
    double x = a.f(), y = a.f();
    a.end();
    double r = 0;
    if (w == "atan2") r = std::atan2(x, y);
    if ((w == "div" || w == "mod") && y == 0) p.fail(word + "() by zero");
    if (w == "div") r = std::trunc(x / y);
    if (w == "mod") r = std::fmod(x, y);
    if (w == "pow") r = std::pow(x, y);
    auto i = [](double d) { return static_cast<int64_t>(std::clamp(d, -9e18, 9e18)); };
    if (w == "bitwise_and") r = static_cast<double>(i(x) & i(y));
    if (w == "bitwise_or") r = static_cast<double>(i(x) | i(y));
    if (w == "bitwise_xor") r = static_cast<double>(i(x) ^ i(y));
    if (!std::isfinite(r)) p.fail(word + "() gives no finite number");
    return Value::number(r);
  }
  if (w == "max" || w == "min") {
    Args a(p, word);
    double r = a.f();
    while (a.more())
      r = w == "max" ? std::max(r, a.f()) : std::min(r, a.f());
    a.end();
    return Value::number(r);
  }
  if (w == "select") {
    Args a(p, word);
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
  if (w == "vlength" || w == "vnormalize") {
    Args a(p, word);
    Vec3d v = a.vec();
    a.end();
    double len = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (w == "vlength") return Value::number(len);
    if (len == 0) return from_vec3({0, 0, 0});  // POV-Ray warns and returns <0,0,0>
    return from_vec3({v.x / len, v.y / len, v.z / len});
  }
  if (w == "vdot" || w == "vcross") {
    Args a(p, word);
    Vec3d u = a.vec(), v = a.vec();
    a.end();
    if (w == "vdot") return Value::number(u.x * v.x + u.y * v.y + u.z * v.z);
    return from_vec3({u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x});
  }
  if (w == "vrotate") {
    Args a(p, word);
    Vec3d v = a.vec(), r = a.vec();
    a.end();
    // about x, then y, then z, as `rotate`
    v = rotate_about(v, {1, 0, 0}, r.x / kDegrees);
    v = rotate_about(v, {0, 1, 0}, r.y / kDegrees);
    v = rotate_about(v, {0, 0, 1}, r.z / kDegrees);
    return from_vec3(v);
  }
  if (w == "vaxis_rotate") {
    Args a(p, word);
    Vec3d v = a.vec(), axis = a.vec();
    double angle = a.f();
    a.end();
    double len = std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
    if (len == 0) p.fail("vaxis_rotate about a zero axis");
    return from_vec3(rotate_about(v, {axis.x / len, axis.y / len, axis.z / len}, angle / kDegrees));
  }
  if (w == "vturbulence") {
    // approximated: no displacement (docs/pov.md)
    Args a(p, word);
    a.f();
    a.f();
    a.f();
    a.vec();
    a.end();
    return from_vec3({0, 0, 0});
  }
  if (w == "vstr") {
    Args a(p, word);
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
  if (w == "str") {
    Args a(p, word);
    double f = a.f(), width = a.f(), precision = a.f();
    a.end();
    return Value::string(format_float(f, width, precision));
  }
  if (w == "concat") {
    Args a(p, word);
    std::string out = a.s();
    while (a.more()) {
      out += a.s();
      p.check_string(out);
    }
    a.end();
    return Value::string(out);
  }
  if (w == "chr") {
    Args a(p, word);
    double c = a.f();
    a.end();
    return Value::string(std::string(1, static_cast<char>(static_cast<int>(c) & 0xff)));
  }
  if (w == "asc" || w == "strlen" || w == "val" || w == "strupr" || w == "strlwr" ||
      w == "file_exists") {
    Args a(p, word);
    std::string s = a.s();
    a.end();
    if (w == "asc") return Value::number(s.empty() ? 0 : static_cast<unsigned char>(s[0]));
    if (w == "strlen") return Value::number(static_cast<double>(s.size()));
    if (w == "val") return Value::number(std::strtod(s.c_str(), nullptr));
    if (w == "file_exists") return boolean(p.resolve_include(s, nullptr, false).has_value());
    for (char& c : s) {
      c = static_cast<char>(w == "strupr" ? std::toupper(static_cast<unsigned char>(c))
                                          : std::tolower(static_cast<unsigned char>(c)));
    }
    return Value::string(s);
  }
  if (w == "strcmp") {
    Args a(p, word);
    std::string s = a.s(), t = a.s();
    a.end();
    int c = s.compare(t);
    return Value::number(c < 0 ? -1 : c > 0 ? 1 : 0);
  }
  if (w == "substr") {
    Args a(p, word);
    std::string s = a.s();
    double start = a.f(), length = a.f();
    a.end();
    if (start < 1 || length < 0 || start - 1 + length > static_cast<double>(s.size())) {
      p.fail("substr() range outside the string");
    }
    return Value::string(s.substr(static_cast<size_t>(start) - 1, static_cast<size_t>(length)));
  }
  if (w == "seed") {
    Args a(p, word);
    double s = a.f();
    a.end();
    return Value::number(static_cast<double>(p.new_random_stream(s)));
  }
  if (w == "rand") {
    Args a(p, word);
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
  if (w == "defined") {
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
  if (w == "dimensions" || w == "dimension_size") {
    Args a(p, word);
    Value array = a.any();
    if (array.kind != ValueKind::kArray) p.fail(word + "() expects an array");
    if (w == "dimensions") {
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
  if (w == "inside" || w == "trace" || w == "min_extent" || w == "max_extent") {
    // need the geometry's intersection code: parsed, reported, answered with zeros
    SourceLocation where = p.location_of(tok);
    p.skip_parenthesised();
    p.unsupported(word, where);
    if (w == "inside") return Value::number(0);
    return from_vec3({0, 0, 0});
  }
  return std::nullopt;
}

}  // namespace fb::pov::sdl
