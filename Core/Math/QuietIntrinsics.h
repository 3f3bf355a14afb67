// <immintrin.h>, included first in every source file by GCC before 13 (CMakeLists.txt): GCC 12's
// intrinsic headers make their "undefined" vectors by initialising them from themselves
// (`__m512d __Y = __Y;`), and -Wuninitialized reports each one wherever Eigen's AVX-512 code
// inlines it (GCC bug 105593; GCC 13 puts these pragmas in the headers). Diagnostics are
// suppressed by where they point, so turning the warning off only around this first inclusion
// keeps it on for every other line.
#pragma once

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
