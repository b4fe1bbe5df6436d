// POV-Ray's built-in functions that functions.inc names `internal(N)` (f_sphere is internal(61),
// f_torus internal(70) ...): each takes x, y, z and its own extra parameters. filmback evaluates
// the ones the sample scenes use; the formulas follow POV-Ray 3.7's definitions (source/vm/
// fnintern.cpp, functions.inc's comments) and docs/pov.md lists them.
#pragma once

namespace fb {

// Whether POV-Ray 3.7 has internal(number) (0 to 78).
bool internal_function_exists(int number);
// Whether filmback evaluates internal(number).
bool internal_function_known(int number);
// x, y, z and the extra parameters: what internal(number) takes (0 if it does not exist).
int internal_function_arguments(int number);
// internal(number) at `arguments` (internal_function_arguments(number) values).
double internal_function(int number, const double* arguments);

}  // namespace fb
