#include "scene.pov"
