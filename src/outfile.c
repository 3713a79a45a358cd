/* outfile.c -- output files written whole or not at all: the data goes to "<path>.tmp", which
 * is renamed to path only when every byte is written (and, for several files written as one,
 * only when every file is; rg2_export_files). Used by every writer: the exports, the design's
 * control mesh and the pictures. */
#include "internal.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

rg2_status rg2__out_open(rg2__out *o, const char *path, rg2_error *err)
{
    memset(o, 0, sizeof *o);
    size_t n = strlen(path);
    o->tmp = malloc(n + 5);
    if (!o->tmp)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory", path);
    memcpy(o->tmp, path, n);
    memcpy(o->tmp + n, ".tmp", 5);
    o->path = path;
    o->f = fopen(o->tmp, "wb");
    if (!o->f) {
        rg2_status st = rg2__fail(err, RG2_EIO, "%s: cannot write: %s", path, strerror(errno));
        free(o->tmp);
        o->tmp = NULL;
        return st;
    }
    return RG2_OK;
}

rg2_status rg2__out_finish(rg2__out *o, rg2_status st, rg2_error *err)
{
    if (!o->f)
        return st;
    if (st == RG2_OK) {
        int bad = fflush(o->f) != 0 || ferror(o->f);
        int saved = errno;
        if (fclose(o->f) != 0 && !bad) {
            bad = 1;
            saved = errno;
        }
        if (bad)
            st = rg2__fail(err, RG2_EIO, "%s: write failed: %s", o->path, strerror(saved));
    } else
        fclose(o->f);
    o->f = NULL;
    if (st != RG2_OK)
        rg2__out_discard(o);
    return st;
}

rg2_status rg2__out_commit(rg2__out *o, rg2_error *err)
{
    rg2_status st = RG2_OK;
    if (o->tmp && rename(o->tmp, o->path) != 0) {
        st = rg2__fail(err, RG2_EIO, "%s: cannot rename from %s: %s", o->path, o->tmp, strerror(errno));
        remove(o->tmp);
    }
    free(o->tmp);
    o->tmp = NULL;
    return st;
}

void rg2__out_discard(rg2__out *o)
{
    if (o->f)
        fclose(o->f);
    o->f = NULL;
    if (o->tmp)
        remove(o->tmp);
    free(o->tmp);
    o->tmp = NULL;
}

rg2_status rg2__out_close(rg2__out *o, rg2_status st, rg2_error *err)
{
    st = rg2__out_finish(o, st, err);
    return st == RG2_OK ? rg2__out_commit(o, err) : st;
}
