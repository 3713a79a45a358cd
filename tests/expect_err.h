/* expect_err.h -- the error-case check shared by the shape and NURBS tests: a call must
 * return the wanted status with a message containing the offending item. */
#ifndef RG2_EXPECT_ERR_H
#define RG2_EXPECT_ERR_H

#include "harness.h"

#include <string.h>

static inline void expect_err(rg2_status got, rg2_status want, const rg2_error *err,
                              const char *needle, const char *what)
{
    CHECK(got == want && strstr(err->msg, needle), "%s: got %s '%s', want %s containing '%s'", what,
          rg2_status_str(got), err->msg, rg2_status_str(want), needle);
}

#endif
