/* textfile.c -- reading a whole text file (design files, NURBS files of the command line) with
 * a size limit and messages that name the file. */
#include "internal.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

rg2_status rg2_read_text(const char *path, char **out, size_t *len, rg2_error *err)
{
    *out = NULL;
    if (len)
        *len = 0;
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
