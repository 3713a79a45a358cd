/* outfile.c -- output files written whole or not at all: the data goes to a temporary file
 * next to path, "<path>.<pid>.tmp", which is renamed to path only when every byte is written
 * (and, for several files written as one, only when every file is; rg2_export_files). Used by
 * every writer: the exports, the design's control mesh and the pictures.
 *
 * The temporary file is created new (O_EXCL, never through a symbolic link, closed on exec):
 * a symlink planted at the name cannot redirect the write to another file, and two writers of
 * the same path (threads or processes) each get a file of their own, so the path ends up with
 * one writer's whole file, never a mix. The process id keeps processes apart; within one
 * process a name in use gets a counter ("<path>.<pid>.1.tmp", ...). A regular file replaced
 * keeps its permission bits (the temporary file gets them before the rename); a new file has
 * 0666 & ~umask. A file name near its directory's file-name limit (255 bytes on most file
 * systems, 143 on eCryptfs) has its temporary name cut to fit, with a hash of the whole name.
 * An output into memory (rg2_export_memory) is written to an anonymous temporary file (tmpfile:
 * the IGES writer seeks back for its directory section) and read back when complete. */
#define _POSIX_C_SOURCE 200809L /* O_NOFOLLOW, O_CLOEXEC */
#include "internal.h"

#include <errno.h>
#include <limits.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define OUT_TRIES 1000   /* names tried within one process before giving up */
#define OUT_NAME_MAX 255 /* the longest file name where the directory does not say (NAME_MAX of Linux) */
#define OUT_TAG_LEN 9    /* ".%08x", the hash of a cut name */

static long dir_name_max(const char *dir)
{
    return pathconf(dir, _PC_NAME_MAX);
}

/* Test hook: the longest file name in directory dir, or -1 for none known (pathconf). */
long (*rg2__dir_name_max)(const char *dir) = dir_name_max;

/* The longest file name in path's directory (the file systems' 255 bytes, eCryptfs' 143, ...):
 * the directory's own answer, OUT_NAME_MAX when it has none or a larger one. Larger answers are
 * not byte counts: vfat and exfat report 255 UTF-16 units times 6 bytes (1530) yet refuse an
 * ASCII name of 256 bytes, so a name they take, within the suffix's length of 255, went uncut
 * and its temporary name failed with "File name too long". */
static size_t name_max(const char *path)
{
    const char *slash = strrchr(path, '/');
    long m;
    if (!slash)
        m = rg2__dir_name_max(".");
    else if (slash == path)
        m = rg2__dir_name_max("/");
    else {
        size_t n = (size_t)(slash - path);
        char *dir = malloc(n + 1);
        if (!dir)
            return OUT_NAME_MAX;
        memcpy(dir, path, n);
        dir[n] = '\0';
        m = rg2__dir_name_max(dir);
        free(dir);
    }
    return m > 0 && m < OUT_NAME_MAX ? (size_t)m : OUT_NAME_MAX;
}

/* The k-th temporary name of path (k = 0: "<path>.<pid>.tmp", else "<path>.<pid>.<k>.tmp"). A last
 * component within the suffix's length of the file-name limit lim is cut, at a UTF-8 character
 * boundary, so that the temporary name fits too: any name path itself may have can be written
 * (unless the limit leaves no room for the suffix and the hash). */
static int temp_name(const char *path, int k, size_t lim, char *buf, size_t cap)
{
    char suffix[48];
    long pid = (long)getpid();
    int ns = k ? snprintf(suffix, sizeof suffix, ".%ld.%d.tmp", pid, k) : snprintf(suffix, sizeof suffix, ".%ld.tmp", pid);
    const char *slash = strrchr(path, '/');
    size_t dir = slash ? (size_t)(slash + 1 - path) : 0, base = strlen(path + dir);
    if (ns < 0 || dir + base > INT_MAX)
        return -1;
    char tag[16] = "";
    if (base <= lim && base + (size_t)ns > lim && lim >= (size_t)ns + OUT_TAG_LEN) {
        /* the cut name carries a hash of the whole one: names that differ only past the cut
         * (x...x.step and x...x.igs) get different temporary names, each of which
         * rg2_temp_name predicts (the rg2 command removes them on a signal) */
        uint32_t h = 2166136261u; /* FNV-1a */
        for (size_t i = 0; i < base; i++)
            h = (h ^ (unsigned char)path[dir + i]) * 16777619u;
        int nt = snprintf(tag, sizeof tag, ".%08x", (unsigned)h);
        base = lim - (size_t)ns - (size_t)nt;
        while (base > 0 && ((unsigned char)path[dir + base] & 0xC0) == 0x80) /* a continuation byte */
            base--;
    }
    int n = snprintf(buf, cap, "%.*s%s%s", (int)(dir + base), path, tag, suffix);
    return n >= 0 && (size_t)n < cap ? 0 : -1;
}

int rg2_temp_name(const char *path, char *buf, size_t cap)
{
    struct stat sb;
    size_t lim = path && buf ? name_max(path) : 0;
    for (int k = 0; path && buf && k < OUT_TRIES; k++) {
        if (temp_name(path, k, lim, buf, cap))
            return -1;
        if (lstat(buf, &sb) != 0) /* free: the name rg2__out_open takes next */
            return errno == ENOENT ? 0 : -1;
    }
    return -1;
}

rg2_status rg2__out_open(rg2__out *o, const char *path, rg2_error *err)
{
    memset(o, 0, sizeof *o);
    /* refused before anything is written: the rename would fail only after the whole write, and
     * after the other files of an rg2_export_files call had replaced theirs. lstat: a symbolic
     * link to a directory is replaced by the rename, as a link to a file is */
    struct stat sb;
    int have = lstat(path, &sb) == 0;
    if (have && S_ISDIR(sb.st_mode))
        return rg2__fail(err, RG2_EIO, "%s: cannot write: it is a directory", path);
    size_t cap = strlen(path) + 48;
    o->tmp = malloc(cap);
    if (!o->tmp)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory", path);
    o->path = path;
    int fd = -1;
    size_t lim = name_max(path);
    for (int k = 0; k < OUT_TRIES && fd < 0; k++) {
        temp_name(path, k, lim, o->tmp, cap);
        fd = open(o->tmp, O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST)
            break;
    }
    /* a regular file at path keeps its permission bits (mode & 0777) and, where the writer may
     * give them (root; a group of its own), its owner and group, as sed -i keeps them: the
     * renamed file used to have the new file's 0666 & ~umask (a 0600 file became 0644), and
     * with the bits alone a 0660 file of group 'project' became 0660 of the writer's group.
     * Under another group the group bits grant no more than the others' do. Not the setuid,
     * setgid and sticky bits: root writing over another user's setuid file would make a
     * root-owned setuid file. A failed fchmod (a file system without modes) leaves
     * 0666 & ~umask and is not an error */
    if (fd >= 0 && have && S_ISREG(sb.st_mode)) {
        mode_t m = sb.st_mode & 0777;
        if (fchown(fd, sb.st_uid, sb.st_gid) != 0 && fchown(fd, (uid_t)-1, sb.st_gid) != 0)
            m = (m & 0707) | (m & (m << 3) & 0070);
        (void)fchmod(fd, m);
    }
    if (fd >= 0 && !(o->f = fdopen(fd, "wb"))) {
        int saved = errno;
        close(fd);
        remove(o->tmp);
        errno = saved;
    }
    if (!o->f) {
        rg2_status st = rg2__fail(err, RG2_EIO, "%s: cannot write: %s", path,
                                  errno == EEXIST ? "too many temporary files of this name in use" : strerror(errno));
        free(o->tmp);
        o->tmp = NULL;
        return st;
    }
    return RG2_OK;
}

rg2_status rg2__out_open_memory(rg2__out *o, const char *name, rg2_error *err)
{
    memset(o, 0, sizeof *o);
    o->path = name;
    o->mem = 1;
    if (!(o->f = tmpfile()))
        return rg2__fail(err, RG2_EIO, "%s: cannot open a temporary file to write into memory: %s", name,
                         strerror(errno));
    return RG2_OK;
}

/* An output into memory, written: its bytes into o->data (and a 0 after them). Returns 0, or -1
 * with errno (ENOMEM for the buffer, EFBIG past the address space). */
static int read_back(rg2__out *o)
{
    long n;
    if (fflush(o->f) != 0 || ferror(o->f) || fseek(o->f, 0, SEEK_END) != 0 || (n = ftell(o->f)) < 0 ||
        fseek(o->f, 0, SEEK_SET) != 0)
        return -1;
    if ((unsigned long)n >= SIZE_MAX) {
        errno = EFBIG;
        return -1;
    }
    o->data = malloc((size_t)n + 1);
    if (!o->data) {
        errno = ENOMEM;
        return -1;
    }
    if (fread(o->data, 1, (size_t)n, o->f) != (size_t)n) {
        if (!ferror(o->f))
            errno = EIO;
        free(o->data);
        o->data = NULL;
        return -1;
    }
    o->data[n] = '\0';
    o->size = (size_t)n;
    return 0;
}

rg2_status rg2__out_finish(rg2__out *o, rg2_status st, rg2_error *err)
{
    if (!o->f)
        return st;
    if (st == RG2_OK && o->mem) {
        if (read_back(o) != 0)
            st = rg2__fail(err, errno == ENOMEM ? RG2_ENOMEM : RG2_EIO, "%s: writing into memory failed: %s",
                           o->path, strerror(errno));
        fclose(o->f); /* (a tmpfile: nothing to keep, so no error to report) */
    } else if (st == RG2_OK) {
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
    free(o->data);
    o->data = NULL;
    o->size = 0;
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
