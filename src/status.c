/* status.c -- status codes and error messages. */
#include "internal.h"

#include <math.h>
#include <stdarg.h>
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
int rg2_version_number(void) { return RG2_VERSION_NUMBER; }

/* Head of a message too long for rg2_error.msg that is kept (the rest is its tail). */
#define MSG_HEAD 160

rg2_status rg2__fail(rg2_error *err, rg2_status code, const char *fmt, ...)
{
    if (err) {
        /* numbers in the "C" locale, as in the files: under a host's de_DE the messages read
         * "colour range 1,5,0,5" and "interval 2 [1,25, 1,25]" */
        void *loc = rg2__c_numeric_begin();
        va_list ap, ap2;
        va_start(ap, fmt);
        va_copy(ap2, ap);
        int n = vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
        /* too long (a path of 830 bytes first): its head and its tail, which says what went wrong
         * ("No such file or directory" was cut off); as cut when out of memory */
        char *full = n >= (int)sizeof err->msg ? malloc((size_t)n + 1) : NULL;
        if (full) {
            vsnprintf(full, (size_t)n + 1, fmt, ap2);
            static const char mid[] = " [...] ";
            size_t h = MSG_HEAD, t = (size_t)n - (sizeof err->msg - 1 - MSG_HEAD - (sizeof mid - 1));
            while (h > 0 && ((unsigned char)full[h] & 0xC0) == 0x80) /* cut between UTF-8 characters */
                h--;
            while (t < (size_t)n && ((unsigned char)full[t] & 0xC0) == 0x80)
                t++;
            memcpy(err->msg, full, h);
            memcpy(err->msg + h, mid, sizeof mid - 1);
            memcpy(err->msg + h + sizeof mid - 1, full + t, (size_t)n - t + 1);
            free(full);
        } else if (n >= (int)sizeof err->msg) /* (out of memory: cut, between characters) */
            rg2__utf8_cut(err->msg);
        va_end(ap2);
        rg2__c_numeric_end(loc);
        err->code = code;
    }
    return code;
}

rg2_status rg2__prefix(rg2_error *err, rg2_status st, const char *what)
{
    if (err && st) { /* (shifting the message right cut its end, the reason, and could split a
                      * UTF-8 character, for a message near the buffer's size) */
        rg2_error e = *err;
        rg2__fail(err, st, "%s: %s", what, e.msg);
    }
    return st;
}

rg2__numtext rg2__num(double x)
{
    rg2__numtext t;
    void *loc = rg2__c_numeric_begin(); /* (formatted and read back in the "C" locale, as rg2__fail) */
    if (!isfinite(x)) {
        snprintf(t.s, sizeof t.s, "%g", x);
        rg2__c_numeric_end(loc);
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
    rg2__c_numeric_end(loc);
    return t;
}

void rg2__ok(rg2_error *err)
{
    if (err) {
        err->code = RG2_OK;
        err->msg[0] = '\0';
    }
}

void rg2__utf8_cut(char *s)
{
    size_t n = strlen(s), i = n;
    while (i > 0 && n - i < 3 && ((unsigned char)s[i - 1] & 0xC0) == 0x80) /* continuation bytes */
        i--;
    if (i == 0)
        return;
    unsigned char c = (unsigned char)s[i - 1];
    size_t want = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 1;
    if (c >= 0xC0 && n - (i - 1) < want) /* a lead byte whose character was cut */
        s[i - 1] = '\0';
}
