#include "core/function/user_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "core/function/internal_functions.h"

namespace fb {
namespace {

// (x - 1) * y / 2, written as the SDL reader writes it.
std::shared_ptr<UserFunction> sample_function() {
  auto f = std::make_shared<UserFunction>(std::vector<std::string>{"x", "y", "z"});
  f->push_parameter(0);
  f->push_constant(1);
  f->apply(FunctionOp::kSubtract, 2);
  f->push_parameter(1);
  f->apply(FunctionOp::kMultiply, 2);
  f->push_constant(2);
  f->apply(FunctionOp::kDivide, 2);
  f->finish();
  return f;
}

TEST(UserFunction, EvaluatesTheStackProgramInOrder) {
  const auto f = sample_function();
  EXPECT_DOUBLE_EQ(f->evaluate(3, 5, 0), (3 - 1) * 5 / 2.0);
  EXPECT_DOUBLE_EQ(f->evaluate(-1, 0.5, 7), (-1 - 1) * 0.5 / 2);
}

TEST(UserFunction, SelectPicksByTheSignAsPovRayDoes) {
  auto f = std::make_shared<UserFunction>(std::vector<std::string>{"a"});
  f->push_parameter(0);
  f->push_constant(10);
  f->push_constant(20);
  f->push_constant(30);
  f->apply(FunctionOp::kSelect4, 4);
  f->finish();
  const double negative = -2, zero = 0, positive = 3;
  EXPECT_EQ(f->evaluate({&negative, 1}), 10);
  EXPECT_EQ(f->evaluate({&zero, 1}), 20);
  EXPECT_EQ(f->evaluate({&positive, 1}), 30);
}

TEST(UserFunction, CallsAnotherFunctionWithItsOwnArguments) {
  const auto inner = sample_function();
  // g(a) = inner(a, a + 1, 0) + a
  auto g = std::make_shared<UserFunction>(std::vector<std::string>{"a"});
  g->push_parameter(0);
  g->push_parameter(0);
  g->push_constant(1);
  g->apply(FunctionOp::kAdd, 2);
  g->push_constant(0);
  g->call(inner);
  g->push_parameter(0);
  g->apply(FunctionOp::kAdd, 2);
  g->finish();
  const double a = 4;
  EXPECT_DOUBLE_EQ(g->evaluate({&a, 1}), (4 - 1) * 5 / 2.0 + 4);
  EXPECT_EQ(g->call_depth(), 2);
}

TEST(UserFunction, BoundsTheStackAndTheCallDepth) {
  UserFunction deep({"x"});
  EXPECT_THROW(
      {
        for (int i = 0; i <= UserFunction::kMaxStack; ++i)
          deep.push_constant(i);
      },
      FunctionBoundError);
  std::shared_ptr<const UserFunction> chain = sample_function();
  EXPECT_THROW(
      {
        for (int level = 0; level < UserFunction::kMaxCallDepth; ++level) {
          auto next = std::make_shared<UserFunction>(std::vector<std::string>{"x", "y", "z"});
          for (int i = 0; i < 3; ++i)
            next->push_parameter(i);
          next->call(chain);
          next->finish();
          chain = next;
        }
      },
      FunctionBoundError);
}

TEST(UserFunction, BuiltinsAreNamedWithTheirArgumentCounts) {
  ASSERT_TRUE(function_builtin_named("pow"));
  EXPECT_EQ(function_builtin_named("pow")->arguments, 2);
  EXPECT_EQ(function_builtin_named("sqrt")->op, FunctionOp::kSqrt);
  EXPECT_FALSE(function_builtin_named("vlength"));  // a vector function, not in functions
}

double internal(int number, std::initializer_list<double> arguments) {
  EXPECT_EQ(internal_function_arguments(number), int(arguments.size()));
  return internal_function(number, arguments.begin());
}

// functions.inc's shapes against their closed forms.
TEST(InternalFunctions, ShapesAreDistancesToTheirSurfaces) {
  EXPECT_DOUBLE_EQ(internal(61, {3, 4, 0, 2}), 5 - 2);                                  // f_sphere
  EXPECT_DOUBLE_EQ(internal(70, {3, 0.5, 0, 2, 0.25}), std::hypot(3 - 2, 0.5) - 0.25);  // f_torus
  EXPECT_DOUBLE_EQ(internal(57, {1, 2, 2}), 3);                                         // f_r
  // f_rounded_box: radius 0.1, half sizes 1, 2, 3; outside the +x face by 0.5
  EXPECT_NEAR(internal(60, {1.5, 0, 0, 0.1, 1, 2, 3}), 0.5, 1e-5);
  // inside, the rounded box's value is its rounding radius below zero at most
  EXPECT_NEAR(internal(60, {0, 0, 0, 0.1, 1, 2, 3}), -0.1, 1e-5);
  // f_superellipsoid with e = n = 1 is a sphere: 1 - r
  EXPECT_NEAR(internal(68, {0.6, 0, 0, 1, 1}), 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(internal(69, {1, 5, 1}), std::atan2(1.0, 1.0));  // f_th
  EXPECT_FALSE(internal_function_known(8));                         // f_boy_surface
  EXPECT_EQ(internal_function_arguments(8), 3 + 2);
  EXPECT_EQ(internal_function_arguments(79), 0);
}

TEST(InternalFunctions, HelixIsTubeDistanceAtItsCentreLine) {
  // one helix of frequency 1, minor 0.2, major 1, shape 1, circular cross section: on the
  // helix's centre line the value is minus the minor radius
  const double y = 0.3;
  const double turn = -y;  // where the helix passes for this y: angle * 1 + y * 1 = pi
  const double angle = std::numbers::pi + turn;
  const double on_line = internal(25, {std::cos(angle), y, std::sin(angle), 1, 1, 0.2, 1, 1, 1, 0});
  EXPECT_NEAR(on_line, -0.2, 1e-9);
}

TEST(InternalFunctions, NoiseStaysInItsRange) {
  for (int i = 0; i < 200; ++i) {
    const double n = internal(76, {i * 0.37, i * 0.11, -i * 0.23});
    EXPECT_GE(n, 0);
    EXPECT_LE(n, 1);
  }
}

}  // namespace
}  // namespace fb
