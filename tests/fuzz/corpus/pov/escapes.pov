#include "../outside.inc"
#include "link.inc"
#include "/etc/passwd"
