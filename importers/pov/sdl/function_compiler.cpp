// User functions (POV-Ray 3.7 manual, "User-Defined Functions"): `function [(a, b ...)] { expr }`
// read once into a UserFunction program (core/function/user_function.h). Inside a function the
// parameters are variables (x, y, z by default, u and v naming x and y); a declared float is a
// constant; other declared functions are called; the float built-ins and the operators are those
// of expressions but for `!` and `? :`, which POV-Ray 3.7 does not read in functions (checked
// with its parser), and without vectors or strings.
#include <cmath>

#include "core/function/internal_functions.h"
#include "core/texture/solid_pattern.h"
#include "importers/pov/sdl/builtins.h"
#include "importers/pov/sdl/parser.h"
#include "importers/pov/sdl/solid_pigment.h"

namespace fb::pov::sdl {
namespace {

class FunctionCompiler {
 public:
  FunctionCompiler(Parser& parser, UserFunction& program, bool default_parameters)
      : p_(parser), out_(program), default_parameters_(default_parameters) {}

  void expression() {
    Nesting guard(p_);
    logic();
  }

  // The first feature met that filmback does not evaluate, if any.
  std::string unsupported;

 private:
  void logic() {
    relation();
    for (;;) {
      const Tok& tok = p_.peek();
      const bool is_and = tok.symbol("&");
      if (!is_and && !tok.symbol("|")) return;
      p_.next();
      relation();
      out_.apply(is_and ? FunctionOp::kAnd : FunctionOp::kOr, 2);
    }
  }

  void relation() {
    static constexpr std::pair<std::string_view, FunctionOp> kRelations[] = {
        {"<", FunctionOp::kLess},          {"<=", FunctionOp::kLessEqual},
        {"=", FunctionOp::kEqual},         {"!=", FunctionOp::kNotEqual},
        {">=", FunctionOp::kGreaterEqual}, {">", FunctionOp::kGreater}};
    additive();
    for (;;) {
      const Tok& tok = p_.peek();
      if (tok.token.kind != TokenKind::kSymbol) return;
      const FunctionOp* op = nullptr;
      for (const auto& [text, relation_op] : kRelations)
        if (tok.token.text == text) op = &relation_op;
      if (!op) return;
      const FunctionOp chosen = *op;
      p_.next();
      additive();
      out_.apply(chosen, 2);
    }
  }

  void additive() {
    multiplicative();
    for (;;) {
      const Tok& tok = p_.peek();
      const bool plus = tok.symbol("+");
      if (!plus && !tok.symbol("-")) return;
      p_.next();
      multiplicative();
      out_.apply(plus ? FunctionOp::kAdd : FunctionOp::kSubtract, 2);
    }
  }

  void multiplicative() {
    unary();
    for (;;) {
      const Tok& tok = p_.peek();
      const bool times = tok.symbol("*");
      if (!times && !tok.symbol("/")) return;
      p_.next();
      unary();
      out_.apply(times ? FunctionOp::kMultiply : FunctionOp::kDivide, 2);
    }
  }

  void unary() {
    Nesting guard(p_);
    if (p_.accept("-")) {
      unary();
      out_.apply(FunctionOp::kNegate, 1);
    } else if (p_.accept("+")) {
      unary();
    } else {
      primary();
    }
  }

  // (a, b ...): the arguments, each an expression; their count.
  int arguments() {
    p_.expect("(");
    int count = 0;
    if (p_.accept(")")) return 0;
    do {
      expression();
      ++count;
    } while (p_.accept(","));
    p_.expect(")");
    return count;
  }

  int parameter_index(const std::string& name) const {
    const std::vector<std::string>& names = out_.parameters();
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return int(i);
    if (default_parameters_ && name == "u") return 0;
    if (default_parameters_ && name == "v") return 1;
    return -1;
  }

  void builtin_call(const Tok& tok, FunctionBuiltin builtin) {
    const std::string& name = tok.token.text;
    const int count = arguments();
    if (builtin.op == FunctionOp::kMin || builtin.op == FunctionOp::kMax) {
      if (count < 2) p_.fail(name + "() needs at least two arguments");
      for (int i = 1; i < count; ++i)
        out_.apply(builtin.op, 2);  // min(a, b, c) = min(min(a, b), c)
      return;
    }
    if (builtin.op == FunctionOp::kSelect3) {
      if (count != 3 && count != 4) p_.fail("select() needs three or four arguments");
      out_.apply(count == 3 ? FunctionOp::kSelect3 : FunctionOp::kSelect4, count);
      return;
    }
    if (builtin.op == FunctionOp::kAtan && count == 2) {  // atan(a, b) is atan2, as in expressions
      out_.apply(FunctionOp::kAtan2, 2);
      return;
    }
    if (count != builtin.arguments)
      p_.fail(name + "() takes " + std::to_string(builtin.arguments) + " argument" +
              (builtin.arguments == 1 ? "" : "s") + ", not " + std::to_string(count));
    out_.apply(builtin.op, count);
  }

  // fn(x, y, z).red ...: a channel of a pigment function's colour.
  void pigment_call(const Tok& tok, const SolidPattern& pigment) {
    if (arguments() != 3) p_.fail("pigment function '" + tok.token.text + "' takes 3 arguments");
    if (!p_.accept("."))
      p_.fail("pigment function '" + tok.token.text +
              "' gives a colour: expected .red, .green, .blue, .filter, .transmit or .gray");
    const Tok member = p_.next();
    static constexpr std::pair<std::string_view, PigmentChannel> kChannels[] = {
        {"red", PigmentChannel::kRed},           {"x", PigmentChannel::kRed},
        {"green", PigmentChannel::kGreen},       {"y", PigmentChannel::kGreen},
        {"blue", PigmentChannel::kBlue},         {"z", PigmentChannel::kBlue},
        {"filter", PigmentChannel::kFilter},     {"t", PigmentChannel::kFilter},
        {"transmit", PigmentChannel::kTransmit}, {"gray", PigmentChannel::kGrey},
        {"grey", PigmentChannel::kGrey}};
    for (const auto& [name, channel] : kChannels)
      if (member.token.text == name) return out_.sample_pigment(pigment, channel);
    p_.fail("unknown colour component '." + member.token.text + "'");
  }

  void function_call(const Tok& tok) {
    const FunctionValue& callee = *tok.value.function;
    if (callee.pigment) return pigment_call(tok, *callee.pigment);
    const int count = arguments();
    if (count != callee.program->parameter_count())
      p_.fail("function '" + tok.token.text + "' takes " +
              std::to_string(callee.program->parameter_count()) + " arguments, not " +
              std::to_string(count));
    if (!callee.unsupported.empty() && unsupported.empty()) unsupported = callee.unsupported;
    try {
      out_.call(callee.program);
    } catch (const FunctionBoundError& e) {
      p_.fail(e.what());
    }
    // a vector function's component (unsupported: its value is 0 whichever it is)
    if (p_.peek().symbol(".")) {
      p_.next();
      p_.next();
    }
  }

  void constant(double value) {
    if (!std::isfinite(value)) p_.fail("a function's constant is not a finite number");
    out_.push_constant(value);
  }

  void primary() {
    Tok tok = p_.next();
    if (tok.token.kind == TokenKind::kNumber) return constant(tok.token.number);
    if (tok.symbol("(")) {
      expression();
      p_.expect(")");
      return;
    }
    if (tok.token.kind != TokenKind::kWord)
      p_.fail("unexpected '" + tok.token.text + "' in a function");
    if (const int index = parameter_index(tok.token.text); index >= 0)
      return out_.push_parameter(index);
    if (tok.identifier) return identifier(tok);
    if (auto builtin = function_builtin_named(tok.token.text)) return builtin_call(tok, *builtin);
    // the constants of expressions (pi, true, clock ...), read as expressions read them
    p_.unget(tok);
    Value value = builtin(p_, p_.next());
    if (value.kind != ValueKind::kFloat)
      p_.fail("'" + tok.token.text + "' is not a float or a parameter of this function");
    constant(value.v[0]);
  }

  void identifier(const Tok& tok) {
    const Value& value = tok.value;
    if (value.kind == ValueKind::kFunction) return function_call(tok);
    if (value.kind == ValueKind::kFloat) return constant(value.v[0]);
    p_.fail("'" + tok.token.text + "' is not a float or a function, in a function");
  }

  Value builtin(Parser& p, const Tok& tok) {
    auto value = ::fb::pov::sdl::builtin(p, tok);
    if (!value) p.fail("unknown identifier '" + tok.token.text + "' in a function");
    return *value;
  }

  Parser& p_;
  UserFunction& out_;
  bool default_parameters_;
};

// `internal(N)` as a function's whole body: POV-Ray's built-in function N, whose parameters are
// x, y, z and its own.
FunctionValue internal_function_value(Parser& p) {
  p.expect("(");
  const double number = p.parse_float();
  p.expect(")");
  p.expect("}");
  const int n = int(number);
  if (number != n || !internal_function_exists(n))
    p.fail("internal(" + number_string(number) + ") is not one of POV-Ray's internal functions");
  std::vector<std::string> names = {"x", "y", "z"};
  for (int i = 3; i < internal_function_arguments(n); ++i)
    names.push_back("p" + std::to_string(i - 3));
  auto program = std::make_shared<UserFunction>(names);
  for (int i = 0; i < internal_function_arguments(n); ++i)
    program->push_parameter(i);
  program->call_internal(n);
  program->finish();
  FunctionValue value;
  value.program = std::move(program);
  if (!internal_function_known(n)) value.unsupported = "internal(" + std::to_string(n) + ")";
  return value;
}

// A function filmback does not evaluate: "function `what`" is reported where it is used. A spline
// function takes the spline's parameter, the others x, y, z.
FunctionValue unsupported_function(std::string what) {
  std::vector<std::string> names = {"x", "y", "z"};
  if (what == "spline") names.resize(1);
  auto program = std::make_shared<UserFunction>(std::move(names));
  program->push_constant(0);
  program->finish();
  FunctionValue value;
  value.program = std::move(program);
  value.unsupported = std::move(what);
  return value;
}

// function { pigment { ... } }, after the pigment: a function of x, y, z whose value is a colour.
FunctionValue pigment_function(Parser& p, const Pigment& pigment) {
  p.expect("}");
  if (pigment.averaged) return unsupported_function("pigment");
  auto pattern = std::make_shared<const SolidPattern>(to_solid(pigment, 1.0, Transform()));
  auto program = std::make_shared<UserFunction>(std::vector<std::string>{"x", "y", "z"});
  for (int i = 0; i < 3; ++i)
    program->push_parameter(i);
  program->sample_pigment(*pattern, PigmentChannel::kGrey);
  program->finish();
  FunctionValue value;
  value.program = std::move(program);
  value.pigment = std::move(pattern);
  return value;
}

}  // namespace

FunctionValue Parser::parse_function() {
  std::vector<std::string> names;
  const bool default_parameters = !peek().symbol("(");
  if (default_parameters) {
    names = {"x", "y", "z"};
  } else {
    next();
    while (!accept(")")) {
      if (!names.empty()) expect(",");
      Tok name = next();
      if (name.token.kind != TokenKind::kWord) fail("expected a parameter name");
      names.push_back(name.token.text);
      if (names.size() > size_t(UserFunction::kMaxStack))
        fail("a function has at most " + std::to_string(UserFunction::kMaxStack) + " parameters");
    }
  }
  return parse_function_body(std::move(names), default_parameters);
}

FunctionValue Parser::parse_function_body(std::vector<std::string> names, bool default_parameters) {
  expect("{");
  const Tok& first = peek();
  if (first.word("internal")) {
    next();
    return internal_function_value(*this);
  }
  if (first.word("pigment")) {
    next();
    return pigment_function(*this, parse_pigment());
  }
  if (first.word("pattern") || first.word("spline") || first.word("transform")) {
    // vector and pattern functions: their block read and left unevaluated
    Tok kind = next();
    skip_block();
    expect("}");
    return unsupported_function(kind.token.text);
  }
  auto program = std::make_shared<UserFunction>(names);
  FunctionCompiler compiler(*this, *program, default_parameters);
  try {
    compiler.expression();
    program->finish();
  } catch (const FunctionBoundError& e) {
    fail(e.what());
  }
  expect("}");
  FunctionValue value;
  value.program = std::move(program);
  value.unsupported = std::move(compiler.unsupported);
  return value;
}

Value Parser::call_function(const FunctionValue& function, const Tok& name) {
  const UserFunction& program = *function.program;
  std::vector<double> arguments;
  expect("(");
  while (!accept(")")) {
    if (!arguments.empty()) expect(",");
    if (arguments.size() >= size_t(UserFunction::kMaxStack)) fail("too many arguments");
    arguments.push_back(parse_float());
  }
  if (int(arguments.size()) != program.parameter_count())
    fail("function '" + name.token.text + "' takes " + std::to_string(program.parameter_count()) +
         " arguments, not " + std::to_string(arguments.size()));
  if (!function.unsupported.empty()) {
    unsupported("function " + function.unsupported, location_of(name));
    return Value::number(0);
  }
  if (function.pigment) {
    const SolidColour c =
        evaluate_solid(*function.pigment, {arguments[0], arguments[1], arguments[2]});
    return Value::colour({c.rgb.x, c.rgb.y, c.rgb.z, c.filter, c.transmit});
  }
  const double result = program.evaluate(arguments);
  if (!std::isfinite(result))
    fail("function '" + name.token.text + "' gives no finite number here");
  return Value::number(result);
}

}  // namespace fb::pov::sdl
