/* textfile.c -- reading a whole text file (design files, NURBS files of the command line) with
 * a size limit and messages that name the file; UTF-8 text. */
#include "internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

rg2_status rg2_read_text(const char *path, char **out, size_t *len, rg2_error *err)
{
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "read_text: no output");
    *out = NULL;
    if (len)
        *len = 0;
    if (!path)
        return rg2__fail(err, RG2_EINVAL, "read_text: no file name");
    if (!*path) /* (not fopen's "No such file or directory" after an empty name) */
        return rg2__fail(err, RG2_EIO, "'': cannot open: the file name is empty");
    struct stat sb;
    if (stat(path, &sb) == 0 && S_ISDIR(sb.st_mode))
        return rg2__fail(err, RG2_EIO, "%s: is a directory, not a file", path);
    FILE *f = fopen(path, "rb");
    if (!f)
        return rg2__fail(err, RG2_EIO, "%s: cannot open: %s", path, strerror(errno));
    /* the buffer grows to at most RG2_TEXT_MAX_BYTES + 2: room for one byte past the limit
     * (a file of exactly the limit is read whole, one byte more is refused) and the NUL */
    size_t cap = 1 << 16, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n - 1, f);
        if (n < cap - 1)
            break;
        if (n > RG2_TEXT_MAX_BYTES) {
            free(buf);
            fclose(f);
            return rg2__fail(err, RG2_ELIMIT, "%s: larger than %u bytes", path, RG2_TEXT_MAX_BYTES);
        }
        size_t nc = cap * 2 < (size_t)RG2_TEXT_MAX_BYTES + 2 ? cap * 2 : (size_t)RG2_TEXT_MAX_BYTES + 2;
        char *nb = realloc(buf, nc);
        if (!nb) {
            free(buf);
            buf = NULL;
            break;
        }
        buf = nb;
        cap = nc;
    }
    int bad = ferror(f);
    fclose(f);
    if (!buf)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory", path);
    if (bad) {
        free(buf);
        return rg2__fail(err, RG2_EIO, "%s: read error", path);
    }
    buf[n] = 0;
    *out = buf;
    if (len)
        *len = n;
    rg2__ok(err);
    return RG2_OK;
}

/* No overlong form, no surrogate, nothing past U+10FFFF. */
size_t rg2__utf8_len(const unsigned char *p, size_t n)
{
    if (p[0] < 0x80)
        return 1;
    size_t k = p[0] >= 0xC2 && p[0] <= 0xDF ? 2 : p[0] >= 0xE0 && p[0] <= 0xEF ? 3 : p[0] >= 0xF0 && p[0] <= 0xF4 ? 4 : 0;
    if (!k || k > n)
        return 0;
    for (size_t i = 1; i < k; i++)
        if ((p[i] & 0xC0) != 0x80)
            return 0;
    if ((p[0] == 0xE0 && p[1] < 0xA0) || (p[0] == 0xED && p[1] > 0x9F) || (p[0] == 0xF0 && p[1] < 0x90) ||
        (p[0] == 0xF4 && p[1] > 0x8F))
        return 0;
    return k;
}

char *rg2__text_clean(const char *s, char control)
{
    size_t n = strlen(s);
    char *c = malloc(n + 1);
    if (!c)
        return NULL;
    for (size_t k = 0, l; k <= n; k += l) {
        unsigned char ch = (unsigned char)s[k];
        l = k < n ? rg2__utf8_len((const unsigned char *)s + k, n - k) : 1;
        if (!l)
            c[k] = '?', l = 1;
        else if (control && k < n && (ch < 32 || ch == 127))
            c[k] = control;
        else
            memcpy(c + k, s + k, l);
    }
    return c;
}
