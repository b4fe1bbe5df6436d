#include "local.inc"
#include "sub/near.inc"
#include "lib.inc"
object { Local } object { Lib(FromSub) pigment { LibColor } }
