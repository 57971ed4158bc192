#include "test_support.h"

#include <math.h>
#include <stdio.h>

double test_rng_uniform(test_rng *rng) {
    uint64_t z = (rng->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

void _assert_close(double a, double b, double tolerance, const char *a_text, const char *b_text,
                   const char *file, int line) {
    if (fabs(a - b) <= tolerance) return;
    print_error("%s = %.17g and %s = %.17g differ by %.3g > %.3g\n", a_text, a, b_text, b,
                fabs(a - b), tolerance);
    _fail(file, line);
}
