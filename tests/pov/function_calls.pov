// The calls importers/pov/sdl/function_test.cpp checks, printed by POV-Ray 3.7 itself:
//   povray +Itests/pov/function_calls.pov -D +W8 +H8 -GA
#version 3.7;
global_settings { assumed_gamma 1 }
#include "functions.inc"
#declare A = 2;
#declare B = 2;
#declare F = function(a, b) { a * b + A - B }
#declare G = function { F(x, y) * select(z, -1, 0, 1) + min(x, y, z) + max(x, 1) }
#declare H = function(a) { sqrt(abs(a)) + pow(a, 2) + mod(a, 3) + floor(a / 2) + 10 * (a > 1) + (a < 2 & a > -5) + select(a, 7, 8) }
#declare T = function { f_torus(x, y, z, 2, 0.5) + f_sphere(x, y, z, 1) + 10 * f_rounded_box(x, y, z, 0.2, 1, 2, 3) }
#declare S = function { f_superellipsoid(x, y, z, 0.5, 2) + f_ellipsoid(x, y, z, 1, 2, 3) + f_r(x, y, z) + f_th(x, y, z) + f_ph(x, y, z) }
#declare W = function { f_sine_wave(x, y, z) + f_scallop_wave(x, y, z) + f_helix1(x, y, z, 2, 3, 0.2, 1, 1, 0.5, 30) }
#debug concat("G ", str(G(1.5, -2, 0.5), 0, 9), " ", str(G(-1, 3, 0), 0, 9), " ", str(G(2, 2, -1), 0, 9), "\n")
#debug concat("H ", str(H(3.5), 0, 9), " ", str(H(-4.25), 0, 9), " ", str(H(0), 0, 9), "\n")
#debug concat("T ", str(T(0.3, 1.2, -0.4), 0, 9), " ", str(T(2.5, 0.1, 1.7), 0, 9), "\n")
#debug concat("S ", str(S(0.3, 0.2, -0.4), 0, 9), " ", str(S(0.5, -0.1, 0.7), 0, 9), "\n")
#debug concat("W ", str(W(0.3, 1.2, -0.4), 0, 9), " ", str(W(1.1, 0.4, 0.25), 0, 9), "\n")
camera { location -5*z look_at 0 }
