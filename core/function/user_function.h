// A POV-Ray user function (POV-Ray 3.7 manual, "User-Defined Functions": `function(x, y, z) {
// expr }`) compiled once into a flat stack program, so that the renderer can evaluate it at every
// ray step of an isosurface or every hit of a function pigment: no allocation, no mutable state
// (any number of threads may evaluate one function), bounded stack and call depth. The SDL reader
// (importers/pov/sdl/function_compiler.cpp) writes the programs; docs/pov.md, "User functions".
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene/solid_texture.h"

namespace fb {

enum class FunctionOp : uint8_t {
  kConstant,   // pushes `constant`
  kParameter,  // pushes argument `index`
  // one operand
  kNegate,
  kAbs,
  kAcos,
  kAcosh,
  kAsin,
  kAsinh,
  kAtan,
  kAtanh,
  kCeil,
  kCos,
  kCosh,
  kDegrees,
  kRadians,
  kExp,
  kFloor,
  kInt,
  kLn,
  kLog,
  kSin,
  kSinh,
  kSqrt,
  kSqr,
  kTan,
  kTanh,
  // two operands (a below b on the stack)
  kAdd,
  kSubtract,
  kMultiply,
  kDivide,
  kLess,
  kLessEqual,
  kEqual,
  kNotEqual,
  kGreaterEqual,
  kGreater,
  kAnd,
  kOr,
  kMin,
  kMax,
  kAtan2,
  kPow,
  kMod,
  kDiv,  // integer division, truncated
  // three or four operands
  kSelect3,  // select(a, b, c): b if a < 0, else c
  kSelect4,  // select(a, b, c, d): b if a < 0, c if a = 0, d if a > 0
  // calls: their arguments on the stack, replaced by the result
  kCall,      // callees[index], with its parameter count of arguments
  kInternal,  // POV-Ray's internal(index) (core/function/internal_functions.h)
  kPigment,   // patterns[index]'s colour at (x, y, z), channel `constant` (a PigmentChannel)
};

// The float a pigment function's call gives with .red, .green ... (POV-Ray's .gray: 0.297 R +
// 0.589 G + 0.114 B).
enum class PigmentChannel { kRed, kGreen, kBlue, kFilter, kTransmit, kGrey };

// A program past one of UserFunction's bounds.
struct FunctionBoundError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct FunctionInstruction {
  FunctionOp op = FunctionOp::kConstant;
  uint32_t index = 0;
  double constant = 0;
};

// The built-in float functions a user function may call (POV-Ray 3.7 manual, "Functions"), with
// the operation and the argument count (min and max take two or more; select three or four).
struct FunctionBuiltin {
  std::string_view name;
  FunctionOp op;
  int arguments;
};
std::optional<FunctionBuiltin> function_builtin_named(std::string_view name);

class UserFunction {
 public:
  // Bounds that keep evaluation on a fixed stack: the operand stack of one program and the depth
  // of calls into other functions (checked as the program is written), and the program's size.
  static constexpr int kMaxStack = 64;
  static constexpr int kMaxCallDepth = 24;
  static constexpr size_t kMaxInstructions = 1 << 16;

  explicit UserFunction(std::vector<std::string> parameters);

  // ---- writing the program (each throws FunctionBoundError past a bound) ----
  void push_constant(double value);
  void push_parameter(int index);
  // An operation on the values on the stack; `operands` is what it takes (calls: their arguments).
  void apply(FunctionOp op, int operands);
  void call(std::shared_ptr<const UserFunction> callee);
  void call_internal(int number);  // its argument count from internal_function_arguments()
  void sample_pigment(SolidPattern pigment, PigmentChannel channel);
  // The program complete: exactly one value on the stack.
  void finish();

  // ---- evaluating ----
  const std::vector<std::string>& parameters() const { return parameters_; }
  int parameter_count() const { return int(parameters_.size()); }
  // `arguments` holds parameter_count() values. The result follows IEEE arithmetic as POV-Ray's
  // does: sqrt of a negative number is NaN, a division by zero infinite; callers decide.
  double evaluate(std::span<const double> arguments) const;
  double evaluate(double x, double y, double z) const;  // a function of three parameters or more
  size_t size() const { return code_.size(); }
  int call_depth() const { return call_depth_; }

 private:
  void append(FunctionInstruction instruction, int pops);
  double run(const double* arguments) const;

  std::vector<std::string> parameters_;
  std::vector<FunctionInstruction> code_;
  std::vector<std::shared_ptr<const UserFunction>> callees_;
  std::vector<SolidPattern> patterns_;
  int depth_ = 0, max_depth_ = 0;  // the operand stack while writing
  int call_depth_ = 1;
};

}  // namespace fb
