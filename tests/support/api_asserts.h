// SPDX-License-Identifier: Apache-2.0
/* Assertions on ppm_status results for the C tests of the public API. */
#ifndef PPM_API_ASSERTS_H
#define PPM_API_ASSERTS_H

#include <ppm/ppm.h>

#include "test_support.h"

#include <string.h>

/* The call succeeds and leaves ppm_last_error_message() empty. */
#define assert_ppm_ok(call)                                                                                            \
    do {                                                                                                               \
        const ppm_status status_ = (call);                                                                             \
        if (status_ != PPM_OK)                                                                                         \
            fail_msg("%s returned %s: %s", #call, ppm_status_string(status_), ppm_last_error_message());               \
        assert_string_equal(ppm_last_error_message(), "");                                                             \
    } while (0)

/* The call fails with `expected` and the per-thread message contains `needle`. */
#define assert_ppm_error(call, expected, needle)                                                                       \
    do {                                                                                                               \
        const ppm_status status_ = (call);                                                                             \
        const char *message_ = ppm_last_error_message();                                                               \
        if (status_ != (expected))                                                                                     \
            fail_msg("%s returned %s, expected %s (message: '%s')", #call, ppm_status_string(status_),                 \
                     ppm_status_string(expected), message_);                                                           \
        assert_non_null(message_);                                                                                     \
        if (message_[0] == '\0') fail_msg("%s failed with an empty message", #call);                                   \
        if (!strstr(message_, (needle)))                                                                               \
            fail_msg("%s: message '%s' does not contain '%s'", #call, message_, (needle));                             \
    } while (0)

#endif
