/* status.c -- status codes and error messages. */
#include "internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *rg2_status_str(rg2_status code)
{
    switch (code) {
    case RG2_OK: return "ok";
    case RG2_ENOMEM: return "out of memory";
    case RG2_EINVAL: return "invalid argument";
    case RG2_ENONFINITE: return "non-finite value";
    case RG2_EWEIGHT: return "non-positive weight or scalar";
    case RG2_EDOMAIN: return "value out of range";
    case RG2_EINCOMPATIBLE: return "incompatible meshes";
    case RG2_EPARSE: return "malformed input";
    case RG2_EIO: return "input/output error";
    case RG2_ELIMIT: return "size limit exceeded";
    }
    return "unknown status";
}

const char *rg2_version(void) { return RG2_VERSION_STRING; }

rg2_status rg2__fail(rg2_error *err, rg2_status code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
        err->code = code;
    }
    return code;
}

rg2__numtext rg2__num(double x)
{
    rg2__numtext t;
    if (!isfinite(x)) {
        snprintf(t.s, sizeof t.s, "%g", x);
        return t;
    }
    /* Start at the integer digits (below 1e17, where %.17g would not switch to an exponent
     * either), so 90 reads "90", not "9e+01". */
    snprintf(t.s, sizeof t.s, "%.16e", x);
    const char *e = strchr(t.s, 'e');
    int x10 = e ? atoi(e + 1) : 0;
    for (int p = x10 >= 0 && x10 < 17 ? x10 + 1 : 1; p <= 17; p++) {
        snprintf(t.s, sizeof t.s, "%.*g", p, x);
        if (strtod(t.s, NULL) == x)
            break;
    }
    return t;
}

void rg2__ok(rg2_error *err)
{
    if (err) {
        err->code = RG2_OK;
        err->msg[0] = '\0';
    }
}
