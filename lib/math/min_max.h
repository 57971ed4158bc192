// SPDX-License-Identifier: Apache-2.0
// Minimum and maximum of 16 doubles, the hot reduction of the patch intersector. GCC does not
// vectorise min/max reductions of doubles without -ffinite-math-only (which would also remove
// our NaN checks), so use SSE2, part of every x86-64 CPU, where it is there.
#pragma once

#include <algorithm>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace ppm {

inline void min_max16(const double *v, double &lo, double &hi) {
#ifdef __SSE2__
    __m128d l = _mm_loadu_pd(v), h = l;
    for (int k = 2; k < 16; k += 2) {
        const __m128d x = _mm_loadu_pd(v + k);
        l = _mm_min_pd(l, x);
        h = _mm_max_pd(h, x);
    }
    double ls[2], hs[2];
    _mm_storeu_pd(ls, l);
    _mm_storeu_pd(hs, h);
    lo = std::min(ls[0], ls[1]);
    hi = std::max(hs[0], hs[1]);
#else
    lo = hi = v[0];
    for (int k = 1; k < 16; ++k) {
        lo = std::min(lo, v[k]);
        hi = std::max(hi, v[k]);
    }
#endif
}

} // namespace ppm
