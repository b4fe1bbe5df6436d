#include "core/function/user_function.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/function/internal_functions.h"
#include "core/texture/solid_pattern.h"

namespace fb {
namespace {

constexpr FunctionBuiltin kFunctionBuiltins[] = {
    {"abs", FunctionOp::kAbs, 1},         {"acos", FunctionOp::kAcos, 1},
    {"acosh", FunctionOp::kAcosh, 1},     {"asin", FunctionOp::kAsin, 1},
    {"asinh", FunctionOp::kAsinh, 1},     {"atan", FunctionOp::kAtan, 1},
    {"atanh", FunctionOp::kAtanh, 1},     {"ceil", FunctionOp::kCeil, 1},
    {"cos", FunctionOp::kCos, 1},         {"cosh", FunctionOp::kCosh, 1},
    {"degrees", FunctionOp::kDegrees, 1}, {"radians", FunctionOp::kRadians, 1},
    {"exp", FunctionOp::kExp, 1},         {"floor", FunctionOp::kFloor, 1},
    {"int", FunctionOp::kInt, 1},         {"ln", FunctionOp::kLn, 1},
    {"log", FunctionOp::kLog, 1},         {"sin", FunctionOp::kSin, 1},
    {"sinh", FunctionOp::kSinh, 1},       {"sqrt", FunctionOp::kSqrt, 1},
    {"sqr", FunctionOp::kSqr, 1},         {"tan", FunctionOp::kTan, 1},
    {"tanh", FunctionOp::kTanh, 1},       {"atan2", FunctionOp::kAtan2, 2},
    {"pow", FunctionOp::kPow, 2},         {"mod", FunctionOp::kMod, 2},
    {"div", FunctionOp::kDiv, 2},         {"min", FunctionOp::kMin, 2},
    {"max", FunctionOp::kMax, 2},         {"select", FunctionOp::kSelect3, 3},
};

// POV-Ray's truth: a value within 1e-10 of zero is false.
double truth_of(bool b) {
  return b ? 1.0 : 0.0;
}
bool is_true(double a) {
  return std::abs(a) > 1e-10;
}

double unary(FunctionOp op, double a) {
  constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;
  switch (op) {
    case FunctionOp::kNegate:
      return -a;
    case FunctionOp::kAbs:
      return std::abs(a);
    case FunctionOp::kAcos:
      return std::acos(a);
    case FunctionOp::kAcosh:
      return std::acosh(a);
    case FunctionOp::kAsin:
      return std::asin(a);
    case FunctionOp::kAsinh:
      return std::asinh(a);
    case FunctionOp::kAtan:
      return std::atan(a);
    case FunctionOp::kAtanh:
      return std::atanh(a);
    case FunctionOp::kCeil:
      return std::ceil(a);
    case FunctionOp::kCos:
      return std::cos(a);
    case FunctionOp::kCosh:
      return std::cosh(a);
    case FunctionOp::kDegrees:
      return a * kDegreesPerRadian;
    case FunctionOp::kRadians:
      return a / kDegreesPerRadian;
    case FunctionOp::kExp:
      return std::exp(a);
    case FunctionOp::kFloor:
      return std::floor(a);
    case FunctionOp::kInt:
      return std::trunc(a);
    case FunctionOp::kLn:
      return std::log(a);
    case FunctionOp::kLog:
      return std::log10(a);
    case FunctionOp::kSin:
      return std::sin(a);
    case FunctionOp::kSinh:
      return std::sinh(a);
    case FunctionOp::kSqrt:
      return std::sqrt(a);
    case FunctionOp::kSqr:
      return a * a;
    case FunctionOp::kTan:
      return std::tan(a);
    case FunctionOp::kTanh:
      return std::tanh(a);
    default:
      return 0;
  }
}

double binary(FunctionOp op, double a, double b) {
  switch (op) {
    case FunctionOp::kAdd:
      return a + b;
    case FunctionOp::kSubtract:
      return a - b;
    case FunctionOp::kMultiply:
      return a * b;
    case FunctionOp::kDivide:
      return a / b;
    case FunctionOp::kLess:
      return truth_of(a < b);
    case FunctionOp::kLessEqual:
      return truth_of(a <= b);
    case FunctionOp::kEqual:
      return truth_of(a == b);
    case FunctionOp::kNotEqual:
      return truth_of(a != b);
    case FunctionOp::kGreaterEqual:
      return truth_of(a >= b);
    case FunctionOp::kGreater:
      return truth_of(a > b);
    case FunctionOp::kAnd:
      return truth_of(is_true(a) && is_true(b));
    case FunctionOp::kOr:
      return truth_of(is_true(a) || is_true(b));
    case FunctionOp::kMin:
      return std::min(a, b);
    case FunctionOp::kMax:
      return std::max(a, b);
    case FunctionOp::kAtan2:
      return std::atan2(a, b);
    case FunctionOp::kPow:
      return std::pow(a, b);
    case FunctionOp::kMod:
      return std::fmod(a, b);
    case FunctionOp::kDiv:
      return std::trunc(a / b);
    default:
      return 0;
  }
}

bool is_unary(FunctionOp op) {
  return op >= FunctionOp::kNegate && op <= FunctionOp::kTanh;
}
bool is_binary(FunctionOp op) {
  return op >= FunctionOp::kAdd && op <= FunctionOp::kDiv;
}

double pigment_channel(const SolidColour& c, PigmentChannel channel) {
  switch (channel) {
    case PigmentChannel::kRed:
      return c.rgb.x;
    case PigmentChannel::kGreen:
      return c.rgb.y;
    case PigmentChannel::kBlue:
      return c.rgb.z;
    case PigmentChannel::kFilter:
      return c.filter;
    case PigmentChannel::kTransmit:
      return c.transmit;
    case PigmentChannel::kGrey:
      return 0.297 * c.rgb.x + 0.589 * c.rgb.y + 0.114 * c.rgb.z;
  }
  return 0;
}

}  // namespace

std::optional<FunctionBuiltin> function_builtin_named(std::string_view name) {
  for (const FunctionBuiltin& b : kFunctionBuiltins)
    if (b.name == name) return b;
  return std::nullopt;
}

UserFunction::UserFunction(std::vector<std::string> parameters)
    : parameters_(std::move(parameters)) {}

void UserFunction::append(FunctionInstruction instruction, int pops) {
  if (code_.size() >= kMaxInstructions)
    throw FunctionBoundError("function longer than " + std::to_string(kMaxInstructions) +
                             " operations");
  if (pops > depth_) throw std::logic_error("function operation without its operands");
  depth_ += 1 - pops;
  if (depth_ > kMaxStack)
    throw FunctionBoundError("function nested deeper than " + std::to_string(kMaxStack) +
                             " operands");
  max_depth_ = std::max(max_depth_, depth_);
  code_.push_back(instruction);
}

void UserFunction::push_constant(double value) {
  append({FunctionOp::kConstant, 0, value}, 0);
}

void UserFunction::push_parameter(int index) {
  append({FunctionOp::kParameter, uint32_t(index), 0}, 0);
}

void UserFunction::apply(FunctionOp op, int operands) {
  append({op, 0, 0}, operands);
}

void UserFunction::call(std::shared_ptr<const UserFunction> callee) {
  if (callee->call_depth() + 1 > kMaxCallDepth)
    throw FunctionBoundError("functions call each other deeper than " +
                             std::to_string(kMaxCallDepth) + " levels");
  call_depth_ = std::max(call_depth_, callee->call_depth() + 1);
  append({FunctionOp::kCall, uint32_t(callees_.size()), 0}, callee->parameter_count());
  callees_.push_back(std::move(callee));
}

void UserFunction::call_internal(int number) {
  append({FunctionOp::kInternal, uint32_t(number), 0}, internal_function_arguments(number));
}

void UserFunction::sample_pigment(SolidPattern pigment, PigmentChannel channel) {
  append({FunctionOp::kPigment, uint32_t(patterns_.size()), double(channel)}, 3);
  patterns_.push_back(std::move(pigment));
}

void UserFunction::finish() {
  if (depth_ != 1)
    throw std::logic_error("function program leaves " + std::to_string(depth_) + " values");
}

double UserFunction::evaluate(std::span<const double> arguments) const {
  return run(arguments.data());
}

double UserFunction::evaluate(double x, double y, double z) const {
  // parameters past the third are zero, as in POV-Ray's isosurface calls
  double arguments[kMaxStack] = {x, y, z};
  return run(arguments);
}

double UserFunction::run(const double* arguments) const {
  double stack[kMaxStack];
  int top = 0;  // the number of values on the stack
  for (const FunctionInstruction& in : code_) {
    const FunctionOp op = in.op;
    if (op == FunctionOp::kConstant) {
      stack[top++] = in.constant;
    } else if (op == FunctionOp::kParameter) {
      stack[top++] = arguments[in.index];
    } else if (is_unary(op)) {
      stack[top - 1] = unary(op, stack[top - 1]);
    } else if (is_binary(op)) {
      --top;
      stack[top - 1] = binary(op, stack[top - 1], stack[top]);
    } else if (op == FunctionOp::kSelect3) {
      top -= 2;
      stack[top - 1] = stack[top - 1] < 0 ? stack[top] : stack[top + 1];
    } else if (op == FunctionOp::kSelect4) {
      top -= 3;
      const double s = stack[top - 1];
      stack[top - 1] = s < 0 ? stack[top] : s == 0 ? stack[top + 1] : stack[top + 2];
    } else if (op == FunctionOp::kCall) {
      const UserFunction& callee = *callees_[in.index];
      top -= callee.parameter_count();
      stack[top] = callee.run(stack + top);
      ++top;
    } else if (op == FunctionOp::kInternal) {
      top -= internal_function_arguments(int(in.index));
      stack[top] = internal_function(int(in.index), stack + top);
      ++top;
    } else if (op == FunctionOp::kPigment) {
      top -= 3;
      const SolidColour c =
          evaluate_solid(patterns_[in.index], {stack[top], stack[top + 1], stack[top + 2]});
      stack[top] = pigment_channel(c, PigmentChannel(int(in.constant)));
      ++top;
    }
  }
  return stack[0];
}

}  // namespace fb
