/* design_parse.c -- the JSON design file format (docs/design-format.md), read with cJSON.
 * Every semantic error names the JSON path of the offending item; syntax errors give the
 * line and column; unknown keys and names suggest the closest known one. */
#include "design_internal.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

typedef struct {
    rg2_design *d;
    const char *file;
    rg2_error *err;
} pctx;

#if defined(__GNUC__)
__attribute__((format(printf, 4, 5)))
#endif
static rg2_status fail(pctx *c, rg2_status code, const char *path, const char *fmt, ...)
{
    /* formatted whole: a message longer than a fixed buffer (a long label quoted in it) lost its
     * end, the reason, and could end in half a UTF-8 character, before rg2__fail shortens the
     * whole message keeping its head and its end */
    char small[400], *msg = small;
    void *loc = rg2__c_numeric_begin(); /* (its numbers in the "C" locale, as rg2__fail's) */
    va_list ap, ap2;
    va_start(ap, fmt);
    va_copy(ap2, ap);
    int n = vsnprintf(small, sizeof small, fmt, ap);
    va_end(ap);
    if (n >= (int)sizeof small && (msg = malloc((size_t)n + 1)) != NULL)
        vsnprintf(msg, (size_t)n + 1, fmt, ap2);
    else if (!msg) { /* (out of memory: cut, between characters) */
        msg = small;
        rg2__utf8_cut(small);
    }
    rg2__c_numeric_end(loc);
    va_end(ap2);
    rg2_status st = rg2__fail(c->err, code, "%s: %s: %s", c->file, path, msg);
    if (msg != small)
        free(msg);
    return st;
}

/* ------------------------------------------------------------------------------------- */
/* suggestions */

/* The edit distance of a and b when it is at most EDIT_BAND (the most rg2_closest_name takes),
 * else some number above EDIT_BAND: the table's cells within EDIT_BAND of its diagonal, so
 * strings of any length cost O(length) (it gave 99 past 63 bytes: a 64-byte word never matched,
 * not even the name it equals). */
#define EDIT_BAND 3
#define EDIT_FAR 99
static int edit_distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if ((la > lb ? la - lb : lb - la) > EDIT_BAND)
        return EDIT_FAR;
    int prev[2 * EDIT_BAND + 1], cur[2 * EDIT_BAND + 1]; /* [d + EDIT_BAND]: column j = i + d */
    for (int d = -EDIT_BAND; d <= EDIT_BAND; d++)
        prev[d + EDIT_BAND] = d >= 0 && (size_t)d <= lb ? d : EDIT_FAR;
    for (size_t i = 1; i <= la; i++) {
        for (int d = -EDIT_BAND; d <= EDIT_BAND; d++) {
            long long j = (long long)i + d;
            int v = EDIT_FAR;
            if (j == 0)
                v = i < EDIT_FAR ? (int)i : EDIT_FAR;
            else if (j > 0 && (size_t)j <= lb) {
                int sub = prev[d + EDIT_BAND] + (a[i - 1] != b[j - 1]);
                int del = d < EDIT_BAND ? prev[d + 1 + EDIT_BAND] + 1 : EDIT_FAR;
                int ins = d > -EDIT_BAND ? cur[d - 1 + EDIT_BAND] + 1 : EDIT_FAR;
                v = sub < del ? (sub < ins ? sub : ins) : (del < ins ? del : ins);
                if (v > EDIT_FAR)
                    v = EDIT_FAR;
            }
            cur[d + EDIT_BAND] = v;
        }
        memcpy(prev, cur, sizeof prev);
    }
    return prev[(long long)lb - (long long)la + EDIT_BAND];
}

const char *rg2_closest_name(const char *word, const char *const *names, int n)
{
    int best = -1, bd = 1 << 30;
    for (int k = 0; k < n; k++) {
        int dd = edit_distance(word, names[k]);
        if (dd < bd) {
            bd = dd;
            best = k;
        }
    }
    int lim = (int)strlen(word) / 2 + 1;
    return best >= 0 && bd <= (lim < 3 ? lim : 3) ? names[best] : NULL;
}

/* " (did you mean 'x'?)" for the closest of names, or "" if none is close. A word of 3 letters or
 * more that none is close to but that begins exactly one name is that name cut short ("deg" for
 * "degrees", "seg" for "segments": 4 edits, past the edit-distance rule). */
static void suggest(const char *word, const char *const *names, int n, char *out, size_t cap)
{
    const char *best = rg2_closest_name(word, names, n);
    size_t len = strlen(word);
    for (int k = 0; k < n && !best && len >= 3; k++)
        if (!strncmp(names[k], word, len)) {
            int again = 0;
            for (int q = k + 1; q < n; q++)
                again |= !strncmp(names[q], word, len);
            if (again)
                break;
            best = names[k];
        }
    out[0] = 0;
    static const char more[] = "...'?)";
    if (best && snprintf(out, cap, " (did you mean '%s'?)", best) >= (int)cap && cap > sizeof more + 20) {
        out[cap - sizeof more] = 0; /* a long name: its head, cut between UTF-8 characters */
        rg2__utf8_cut(out);
        strcat(out, more);
    }
}

/* ------------------------------------------------------------------------------------- */
/* typed access */

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void fmtpath(char *buf, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, cap, fmt, ap);
    va_end(ap);
    if (n >= (int)cap) /* a path of long names cut short: between UTF-8 characters */
        rg2__utf8_cut(buf);
}

static void subpath(char *buf, size_t cap, const char *path, const char *key)
{
    fmtpath(buf, cap, "%s.%s", path, key);
}

static void indexpath(char *buf, size_t cap, const char *path, int k)
{
    fmtpath(buf, cap, "%s[%d]", path, k);
}


static rg2_status check_keys(pctx *c, const cJSON *obj, const char *path, const char *const *allowed,
                             int n)
{
    for (const cJSON *it = obj->child; it; it = it->next) {
        int ok = !strcmp(it->string, "comment");
        for (int k = 0; k < n && !ok; k++)
            ok = !strcmp(it->string, allowed[k]);
        if (!ok) {
            char sug[128], list[400] = "";
            suggest(it->string, allowed, n, sug, sizeof sug);
            for (int k = 0; k < n; k++) {
                strncat(list, allowed[k], sizeof list - strlen(list) - 1);
                if (k + 1 < n)
                    strncat(list, ", ", sizeof list - strlen(list) - 1);
            }
            return fail(c, RG2_EPARSE, path, "unknown key '%s'%s; known keys: %s", it->string, sug, list);
        }
        for (const cJSON *o = obj->child; o != it; o = o->next)
            if (!strcmp(o->string, it->string))
                return fail(c, RG2_EPARSE, path, "duplicate key '%s'", it->string);
    }
    return RG2_OK;
}

static const char *type_name(const cJSON *x)
{
    if (cJSON_IsNumber(x)) return "a number";
    if (cJSON_IsString(x)) return "a string";
    if (cJSON_IsBool(x)) return "a boolean";
    if (cJSON_IsNull(x)) return "null";
    if (cJSON_IsArray(x)) return "an array";
    if (cJSON_IsObject(x)) return "an object";
    return "invalid";
}

static rg2_status as_num(pctx *c, const cJSON *x, const char *path, double *out)
{
    *out = 0.0;
    if (!cJSON_IsNumber(x))
        return fail(c, RG2_EPARSE, path, "expected a number, found %s", type_name(x));
    if (!rg2__finite(x->valuedouble))
        return fail(c, RG2_ENONFINITE, path,
                    "number is not finite (it overflows a double; JSON has no NaN or infinity)");
    rg2_error e;
    rg2_status st = rg2_number_check(x->valuedouble, path, &e); /* the range rg2 shape applies too */
    if (st)
        return rg2__fail(c->err, st, "%s: %s", c->file, e.msg);
    *out = x->valuedouble;
    return RG2_OK;
}

static rg2_status as_int(pctx *c, const cJSON *x, const char *path, int *out)
{
    double v = 0.0;
    rg2_status st = as_num(c, x, path, &v);
    if (st)
        return st;
    if (v != floor(v))
        return fail(c, RG2_EPARSE, path, "expected an integer, found %s", rg2__num(v).s);
    if (fabs(v) > 1e9) /* ("expected an integer, found 2147483647" named an integer as none) */
        return fail(c, RG2_EDOMAIN, path, "the integer %s is outside the supported range -1e9 .. 1e9",
                    rg2__num(v).s);
    *out = (int)v;
    return RG2_OK;
}

static rg2_status as_bool(pctx *c, const cJSON *x, const char *path, int *out)
{
    if (!cJSON_IsBool(x))
        return fail(c, RG2_EPARSE, path, "expected true or false, found %s", type_name(x));
    *out = cJSON_IsTrue(x) ? 1 : 0;
    return RG2_OK;
}

static rg2_status as_str(pctx *c, const cJSON *x, const char *path, const char **out)
{
    *out = NULL;
    if (!cJSON_IsString(x))
        return fail(c, RG2_EPARSE, path, "expected a string, found %s", type_name(x));
    *out = x->valuestring;
    return RG2_OK;
}

static rg2_status as_obj(pctx *c, const cJSON *x, const char *path)
{
    if (!cJSON_IsObject(x))
        return fail(c, RG2_EPARSE, path, "expected an object, found %s", type_name(x));
    return RG2_OK;
}

/* A number array of exactly n (n > 0) or of 1..max (n = 0, count into *count). */
static rg2_status as_nums(pctx *c, const cJSON *x, const char *path, double *out, int n, int max,
                          int *count)
{
    if (!cJSON_IsArray(x) && n)
        return fail(c, RG2_EPARSE, path, "expected an array of %d numbers, found %s", n, type_name(x));
    if (!cJSON_IsArray(x))
        return fail(c, RG2_EPARSE, path, "expected an array of numbers, found %s", type_name(x));
    int len = cJSON_GetArraySize(x);
    if (n && len != n)
        return fail(c, RG2_EPARSE, path, "expected %d numbers, found %d", n, len);
    if (!n && len < 1)
        return fail(c, RG2_EPARSE, path, "expected at least one number, found an empty array");
    if (!n && len > max)
        return fail(c, RG2_ELIMIT, path, "expected at most %d numbers, found %d", max, len);
    int k = 0;
    for (const cJSON *it = x->child; it; it = it->next, k++) {
        char p[300];
        indexpath(p, sizeof p, path, k);
        rg2_status st = as_num(c, it, p, &out[k]);
        if (st)
            return st;
    }
    if (count)
        *count = len;
    return RG2_OK;
}

static const cJSON *get(const cJSON *obj, const char *key)
{
    return cJSON_GetObjectItemCaseSensitive(obj, key);
}

static rg2_status need(pctx *c, const cJSON *obj, const char *key, const char *path, const cJSON **out)
{
    *out = get(obj, key);
    if (!*out)
        return fail(c, RG2_EPARSE, path, "missing key '%s'", key);
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* placement: scale, then rotate, then translate, then matrix */

static const char *const placement_keys[] = {"matrix", "translate", "rotate", "scale"};

/* One rotation {"axis": [x, y, z], "degrees": a} at path into T. */
static rg2_status parse_rotation(pctx *c, const cJSON *x, const char *p, double T[16])
{
    rg2_status st;
    if ((st = as_obj(c, x, p)))
        return st;
    static const char *const rk[] = {"axis", "degrees"};
    if ((st = check_keys(c, x, p, rk, 2)))
        return st;
    const cJSON *ax, *dg;
    double a[3], deg;
    char q[340];
    if ((st = need(c, x, "axis", p, &ax)) || (st = need(c, x, "degrees", p, &dg)))
        return st;
    subpath(q, sizeof q, p, "axis");
    if ((st = as_nums(c, ax, q, a, 3, 3, NULL)))
        return st;
    if (a[0] == 0.0 && a[1] == 0.0 && a[2] == 0.0)
        return fail(c, RG2_EDOMAIN, q, "the rotation axis is the zero vector");
    subpath(q, sizeof q, p, "degrees");
    if ((st = as_num(c, dg, q, &deg)))
        return st;
    const char *turn = rg2_angle_total_in_radians(fabs(deg));
    if (turn) { /* 1.5708: radians typed for degrees, most likely; a rotation has no "closed" to say so */
        char msg[1200];
        snprintf(msg, sizeof msg,
                 "%s: %s: %.6g is %s; angles in a design file are in degrees, so this turns by %.6g "
                 "degrees (for the turn of %.6g radians write %.0f)",
                 c->file, q, deg, turn, deg, deg, deg * 180.0 / M_PI);
        if ((st = rg2__design_add_note(c->d, msg, c->err)))
            return st;
    }
    rg2_xform_rotate(T, a[0], a[1], a[2], deg * M_PI / 180.0);
    return RG2_OK;
}

static rg2_status parse_placement(pctx *c, const cJSON *obj, const char *path, double M[16], int *any)
{
    char p[300];
    rg2_status st;
    double T[16];
    rg2_xform_identity(M);
    *any = 0;
    const cJSON *x;
    if ((x = get(obj, "scale"))) {
        double s[3];
        subpath(p, sizeof p, path, "scale");
        if (cJSON_IsNumber(x)) {
            if ((st = as_num(c, x, p, &s[0])))
                return st;
            s[1] = s[2] = s[0];
        } else if ((st = as_nums(c, x, p, s, 3, 3, NULL)))
            return st;
        if (s[0] == 0.0 || s[1] == 0.0 || s[2] == 0.0)
            return fail(c, RG2_EDOMAIN, p, "scale factors must be non-zero");
        rg2_xform_scale(T, s[0], s[1], s[2]);
        rg2_xform_mul(T, M, M);
        *any = 1;
    }
    if ((x = get(obj, "rotate"))) {
        subpath(p, sizeof p, path, "rotate");
        if (cJSON_IsArray(x)) { /* rotations applied in order, the first first */
            int nr = cJSON_GetArraySize(x);
            if (nr < 1)
                return fail(c, RG2_EPARSE, p, "an empty list of rotations (give one {\"axis\": [x, y, z], "
                                              "\"degrees\": a} or a list of them)");
            for (int k = 0; k < nr; k++) {
                char q[320];
                indexpath(q, sizeof q, p, k);
                if ((st = parse_rotation(c, cJSON_GetArrayItem(x, k), q, T)))
                    return st;
                rg2_xform_mul(T, M, M);
            }
        } else {
            if ((st = parse_rotation(c, x, p, T)))
                return st;
            rg2_xform_mul(T, M, M);
        }
        *any = 1;
    }
    if ((x = get(obj, "translate"))) {
        double t[3];
        subpath(p, sizeof p, path, "translate");
        if ((st = as_nums(c, x, p, t, 3, 3, NULL)))
            return st;
        rg2_xform_translate(T, t[0], t[1], t[2]);
        rg2_xform_mul(T, M, M);
        *any = 1;
    }
    if ((x = get(obj, "matrix"))) {
        subpath(p, sizeof p, path, "matrix");
        if ((st = as_nums(c, x, p, T, 16, 16, NULL)))
            return st;
        rg2_xform_mul(T, M, M);
        *any = 1;
    }
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* shapes */

static rg2_status parse_shape(pctx *c, const cJSON *obj, const char *label, const char *path)
{
    rg2_status st = as_obj(c, obj, path);
    if (st)
        return st;
    const cJSON *k;
    const char *kind;
    char p[300];
    if ((st = need(c, obj, "kind", path, &k)))
        return st;
    subpath(p, sizeof p, path, "kind");
    if ((st = as_str(c, k, p, &kind)))
        return st;
    const char *names[RG2_SHAPE_COUNT];
    int kk = -1;
    for (int q = 0; q < RG2_SHAPE_COUNT; q++) {
        names[q] = rg2_shape_name((rg2_shape_kind)q);
        if (!strcmp(kind, names[q]))
            kk = q;
    }
    if (kk < 0) {
        char sug[128], list[400] = "";
        suggest(kind, names, RG2_SHAPE_COUNT, sug, sizeof sug);
        for (int q = 0; q < RG2_SHAPE_COUNT; q++) {
            strncat(list, names[q], sizeof list - strlen(list) - 1);
            if (q + 1 < RG2_SHAPE_COUNT)
                strncat(list, ", ", sizeof list - strlen(list) - 1);
        }
        return fail(c, RG2_EPARSE, p, "unknown shape kind '%s'%s; known kinds: %s", kind, sug, list);
    }
    const rg2_shape_desc *desc = rg2_shape_describe((rg2_shape_kind)kk);
    const char *allowed[12];
    int na = 0;
    allowed[na++] = "kind";
    for (int q = 0; q < 4; q++)
        allowed[na++] = placement_keys[q];
    for (int q = 0; q < desc->n_params; q++)
        allowed[na++] = desc->param_names[q];
    if (desc->dir_kind[1] == RG2_PART_KNOTS && strcmp(kind, "hypar")) /* a size along the axis */
        for (const cJSON *it = obj->child; it; it = it->next) {
            static const char *const along[] = {"height", "length", "h", "radius"};
            int hit = 0;
            for (size_t q = 0; q < sizeof along / sizeof along[0]; q++)
                hit |= !strcmp(it->string, along[q]);
            for (int q = 0; q < na && hit; q++)
                hit = strcmp(it->string, allowed[q]) != 0;
            if (!hit)
                continue;
            char list[400] = "";
            for (int q = 0; q < na; q++) {
                strncat(list, allowed[q], sizeof list - strlen(list) - 1);
                if (q + 1 < na)
                    strncat(list, ", ", sizeof list - strlen(list) - 1);
            }
            return fail(c, RG2_EPARSE, path,
                        "unknown key '%s'; known keys: %s: a %s's extent is not a parameter but comes from "
                        "its mesh's v partition, whose knots place the rings (%s; in the mesh: "
                        "\"v\": {\"from\": A, \"to\": B}; docs/shapes.md, \"Where a knot puts the ring\")",
                        it->string, list, kind,
                        !strcmp(kind, "cylinder")             ? "the cylinder's knots are heights z"
                        : !strcmp(kind, "cone")               ? "the cone's knot v is the ring's radius, at height k v"
                        : !strcmp(kind, "sphere") || !strcmp(kind, "ellipsoid")
                            ? "knots in (0, 1), 0 the south pole, 1 the north pole"
                        : !strcmp(kind, "paraboloid")         ? "the ring at knot v has height v^2"
                                                              : "see the table there for the ring of a knot");
        }
    if ((st = check_keys(c, obj, path, allowed, na)))
        return st;
    rg2_shape s;
    rg2_shape_init(&s, (rg2_shape_kind)kk);
    for (int q = 0; q < desc->n_params; q++) {
        const cJSON *x = get(obj, desc->param_names[q]);
        if (!x)
            continue;
        subpath(p, sizeof p, path, desc->param_names[q]);
        if ((st = as_num(c, x, p, &s.param[q])))
            return st;
    }
    int any;
    if ((st = parse_placement(c, obj, path, s.xform, &any)))
        return st;
    /* let the shape module validate the parameters and the placement */
    double coef[4][4][4], inv[16];
    rg2_error e;
    if ((st = rg2_shape_coeffs(&s, coef, &e)))
        return fail(c, st, path, "%s", e.msg);
    if (any && (st = rg2_xform_invert(s.xform, inv, &e))) { /* (a zero scale is refused above: the matrix) */
        subpath(p, sizeof p, path, "matrix");
        return fail(c, st, get(obj, "matrix") ? p : path, "%s", e.msg);
    }
    if (rg2__design_add_shape(c->d, &s, label, c->err) < 0)
        return fail(c, RG2_ENOMEM, path, "out of memory");
    return RG2_OK;
}

static int find_shape(const rg2_design *d, const char *label)
{
    return rg2__design_find_shape(d, label);
}

/* ------------------------------------------------------------------------------------- */
/* partitions */

#define MAX_PART 100000

/* The message for an angle total that looks like radians (what names the total: "the 4 arcs sum
 * to", "'from' 0 to 'to' 1.5708 spans"). */
static rg2_status radian_fail(pctx *c, const char *path, const char *what, double deg, const char *turn)
{
    return fail(c, RG2_EDOMAIN, path,
                "%s %.6g degrees, which is %s; angles in a design file are in degrees (a full circle is "
                "360): convert them (times 180 / pi), or say \"closed\": false if an open ring of %.6g degrees "
                "is meant", what, deg, turn, deg);
}

typedef struct {
    rg2_partition p;
    double *values;
} part_buf;

static rg2_status parse_partition(pctx *c, const cJSON *obj, const char *path, const rg2_shape_desc *desc,
                                  int dir, part_buf *pb)
{
    rg2_status st;
    char p[300];
    int angles = desc->dir_kind[dir] == RG2_PART_ANGLES;
    double lo = desc->default_range[dir][0], hi = desc->default_range[dir][1];
    int closed = desc->default_closed[dir], nseg = desc->default_segments[dir];
    if (angles) {
        lo *= 180.0 / M_PI;
        hi *= 180.0 / M_PI;
    }
    const cJSON *list = NULL;
    int have_to = 0, have_closed = 0, have_count = 0;
    if (obj) {
        if ((st = as_obj(c, obj, path)))
            return st;
        static const char *const ka[] = {"arcs", "from", "to", "closed"};
        static const char *const kk[] = {"knots", "segments", "from", "to"};
        /* a key of the other kind of direction: say which kind this one is (the closest-name
         * suggestion would point at an unrelated key) */
        static const char *const other[2][2] = {{"knots", "segments"}, {"arcs", "closed"}};
        for (int k = 0; k < 2; k++)
            if (get(obj, other[!angles][k]))
                return fail(c, RG2_EPARSE, path,
                            angles ? "'%s' is for polynomial (knot) directions; %s of a %s is a circle: give "
                                     "'arcs' (a number, or opening angles in degrees) with 'from', 'to', 'closed'"
                                   : "'%s' is for circle directions; %s of a %s is a polynomial (knot) direction: "
                                     "give 'knots', or 'segments' with 'from' and 'to'",
                            other[!angles][k], dir ? "v" : "u", desc->name);
        if ((st = check_keys(c, obj, path, angles ? ka : kk, 4)))
            return st;
        const cJSON *x;
        if ((x = get(obj, "from"))) {
            subpath(p, sizeof p, path, "from");
            if ((st = as_num(c, x, p, &lo)))
                return st;
        }
        if ((x = get(obj, "to"))) {
            subpath(p, sizeof p, path, "to");
            if ((st = as_num(c, x, p, &hi)))
                return st;
            have_to = 1;
        }
        if ((x = get(obj, "closed"))) {
            subpath(p, sizeof p, path, "closed");
            if ((st = as_bool(c, x, p, &closed)))
                return st;
            have_closed = 1;
        }
        if (angles && have_to && have_closed && closed) /* as rg2 shape refuses --D-closed with --D-sweep */
            return fail(c, RG2_EPARSE, path,
                        "'to' ends an open ring; a closed circle goes all the way round (drop 'to', or "
                        "say \"closed\": false)");
        const char *ck = angles ? "arcs" : "segments";
        x = get(obj, ck);
        if (!angles && get(obj, "knots")) {
            if (x || get(obj, "from") || have_to)
                return fail(c, RG2_EPARSE, path, "give either 'knots' or 'segments' with 'from'/'to'");
            list = get(obj, "knots");
        } else if (x) {
            subpath(p, sizeof p, path, ck);
            if (angles && !cJSON_IsArray(x) && !cJSON_IsNumber(x))
                return fail(c, RG2_EPARSE, p,
                            "expected a number of arcs or an array of opening angles (degrees), "
                            "found %s", type_name(x));
            if (angles && cJSON_IsArray(x)) {
                if (have_to)
                    return fail(c, RG2_EPARSE, path,
                                "'to' goes with a number of arcs; a list of arcs starts at 'from' "
                                "and ends where its angles add up");
                list = x;
            }
            else if ((st = as_int(c, x, p, &nseg)))
                return st;
            else if (nseg < 1 || nseg > MAX_PART) /* past the count: a size limit, as for a list */
                return fail(c, nseg < 1 ? RG2_EDOMAIN : RG2_ELIMIT, p, "%d %s; need 1 to %d", nseg, ck, MAX_PART);
            have_count = 1;
        }
    }
    int n;
    if (list) {
        subpath(p, sizeof p, path, angles ? "arcs" : "knots");
        int len = cJSON_IsArray(list) ? cJSON_GetArraySize(list) : 0;
        pb->values = rg2__calloc((size_t)(len > 0 ? len : 1), sizeof(double));
        if (!pb->values)
            return fail(c, RG2_ENOMEM, p, "out of memory");
        if ((st = as_nums(c, list, p, pb->values, 0, MAX_PART, &n)))
            return st;
        if (angles) {
            double sum = 0;
            for (int k = 0; k < n; k++) {
                sum += pb->values[k];
                pb->values[k] *= M_PI / 180.0;
            }
            double gap = fabs(sum - 360.0);
            const char *turn = have_closed ? NULL : rg2_angle_total_in_radians(sum);
            if (turn) {
                char what[64];
                snprintf(what, sizeof what, "the %d arc%s sum%s to", n, n == 1 ? "" : "s", n == 1 ? "s" : "");
                return radian_fail(c, p, what, sum, turn);
            }
            if (!have_closed && gap > RG2_CLOSED_SUM_TOL * 360.0 && gap <= RG2_NEAR_FULL_DEG)
                return fail(c, RG2_EDOMAIN, p,
                            "the %d arcs sum to %.10g degrees, %.3g from a full circle: for a closed circle "
                            "give the angles to 12 digits (or \"arcs\": %d for equal arcs); for an open ring "
                            "say \"closed\": false",
                            n, sum, gap, n);
            if (!have_closed)
                closed = gap <= RG2_CLOSED_SUM_TOL * 360.0;
        }
    } else {
        if (angles && !have_closed)
            closed = !have_to;
        if (!angles)
            closed = 0;
        if (angles && have_to && !have_closed && fabs(hi - lo - 360.0) <= RG2_NEAR_FULL_DEG)
            /* (a full range was an open ring whose two ends met: a slit, 20 free edges in a STEP file) */
            return fail(c, RG2_EDOMAIN, path,
                        "'from' %s to 'to' %s degrees goes all the way round, which 'to' leaves open (the two "
                        "ends meet in a slit): drop 'to' for a closed circle starting at 'from', or say "
                        "\"closed\": false for an open ring",
                        rg2__num(lo).s, rg2__num(hi).s);
        const char *turn = angles && have_to && !have_closed ? rg2_angle_total_in_radians(hi - lo) : NULL;
        if (turn) {
            char what[160];
            snprintf(what, sizeof what, "'from' %s to 'to' %s spans", rg2__num(lo).s, rg2__num(hi).s);
            return radian_fail(c, path, what, hi - lo, turn);
        }
        if (angles && !closed && !have_count && hi - lo > 0.0) {
            /* an open range without a count: arcs about as fine as the default full circle's, as
             * rg2 shape's --D-sweep (the default count over 90 degrees gave the torus 8 arcs of
             * 11.25 degrees in a design, 2 of 45 from rg2 shape) */
            double k = ceil((hi - lo) / (360.0 / nseg) - 1e-9);
            nseg = k < 1.0 ? 1 : k > MAX_PART ? MAX_PART : (int)k;
        }
        pb->values = rg2__calloc((size_t)nseg + 1, sizeof(double));
        if (!pb->values)
            return fail(c, RG2_ENOMEM, path, "out of memory");
        if (angles) {
            double span = closed ? 360.0 : hi - lo;
            if (!(span > 0.0))
                return fail(c, RG2_EDOMAIN, path, "arc range from %s to %s degrees is empty", rg2__num(lo).s,
                            rg2__num(hi).s);
            /* (arcs of 180 degrees or more: the opening angle's own message named arc 0 and its angle,
             * not the count or the range that made it) */
            if (closed && nseg < 3)
                return fail(c, RG2_EDOMAIN, path,
                            "a full circle in %d arc%s gives arcs of %g degrees; every arc must be under 180: "
                            "give at least 3 arcs", nseg, nseg == 1 ? "" : "s", 360.0 / nseg);
            if (!closed && span > 360.0)
                return fail(c, RG2_EDOMAIN, path,
                            "'from' %s to 'to' %s spans %s degrees, more than a full circle", rg2__num(lo).s,
                            rg2__num(hi).s, rg2__num(span).s);
            if (!closed && span / nseg >= 180.0)
                return fail(c, RG2_EDOMAIN, path,
                            "%s degrees in %d arc%s gives arcs of %s degrees; every arc must be under 180: give "
                            "at least %d arcs", rg2__num(span).s, nseg, nseg == 1 ? "" : "s",
                            rg2__num(span / nseg).s, (int)floor(span / 180.0) + 1);

            for (int k = 0; k < nseg; k++)
                pb->values[k] = closed ? 2.0 * M_PI / nseg : span * (M_PI / 180.0) / nseg;
            n = nseg;
        } else {
            if (!(hi > lo))
                return fail(c, RG2_EDOMAIN, path,
                            hi < lo ? "knot range from %s to %s is empty: 'from' must be below 'to' (to run the "
                                      "other way, give 'from' %s, 'to' %s and reverse the mesh: {\"reverse\": "
                                      "\"<mesh>\", \"dir\": \"%c\"})"
                                    : "knot range from %s to %s is empty",
                            rg2__num(lo).s, rg2__num(hi).s, rg2__num(hi).s, rg2__num(lo).s, dir ? 'v' : 'u');
            for (int k = 0; k <= nseg; k++)
                pb->values[k] = k == nseg ? hi : lo + (hi - lo) * k / nseg;
            n = nseg + 1;
        }
    }
    pb->p.kind = angles ? RG2_PART_ANGLES : RG2_PART_KNOTS;
    pb->p.closed = angles ? closed : 0;
    pb->p.n = n;
    pb->p.values = pb->values;
    /* (the start within one turn, exactly: "from": 1e20 degrees rounded every junction angle onto
     * the start in radians, and the shape's corners left its arcs) */
    pb->p.start = angles ? (fabs(lo) < 360.0 ? lo : fmod(lo, 360.0)) * M_PI / 180.0 : 0.0;
    rg2_error e;
    if ((st = rg2_partition_check(&pb->p, dir ? "v" : "u", &e))) /* "u partition: ...": the path says it */
        return fail(c, st, path, "%s", rg2__after(e.msg, dir ? "v partition: " : "u partition: "));
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* meshes */

/* a mesh's operations: the enum indexes the table of their keys */
enum {
    OP_SHAPE,
    OP_CUT,
    OP_MERGE,
    OP_TRANSPOSE,
    OP_REVERSE,
    OP_EDIT,
    OP_TRANSFORM,
    OP_MORPH,
    OP_POLAR,
    OP_MOBIUS,
    OP_CAP,
    OP_NURBS,
    OP_ROLL,
    N_OPS
};
static const char *const ops[] = {"shape", "cut", "merge", "transpose", "reverse", "edit", "transform", "morph",
                                  "polar", "mobius", "cap", "nurbs", "roll"};
_Static_assert(sizeof ops / sizeof ops[0] == N_OPS, "one key per operation");

/* Whether operation `op` makes its mesh from no other mesh (shape, polar, nurbs: no mesh inputs). */
static int op_makes_mesh_from_nothing(int op)
{
    return op == OP_SHAPE || op == OP_POLAR || op == OP_NURBS;
}

static rg2_status mesh_ref(pctx *c, const cJSON *x, const char *path, int *idx)
{
    const char *name = NULL;
    rg2_status st = as_str(c, x, path, &name);
    if (st)
        return st;
    *idx = rg2__design_find_mesh(c->d, name);
    if (*idx < 0) {
        const char **names = rg2__calloc((size_t)c->d->n_mesh + 1, sizeof *names);
        char sug[128] = "";
        if (names) {
            for (int k = 0; k < c->d->n_mesh; k++)
                names[k] = c->d->mesh[k].name;
            suggest(name, names, c->d->n_mesh, sug, sizeof sug);
            free(names);
        }
        if (find_shape(c->d, name) >= 0) /* a shape label where a mesh belongs */
            return fail(c, RG2_EPARSE, path,
                        "'%s' is a shape label, not a mesh%s; make its control mesh first, e.g. "
                        "\"%s_mesh\": {\"shape\": \"%s\"}, and use that mesh here",
                        name, sug, name, name);
        /* the output list comes after every mesh: "before this one" would point at nothing */
        return fail(c, RG2_EPARSE, path, "no mesh named '%s' %s%s", name,
                    strncmp(path, "output", 6) ? "defined before this one" : "in \"meshes\"", sug);
    }
    return RG2_OK;
}

/* Common start of the single-source operations: check the keys (keys[0] is the operation,
 * whose value names the input mesh) and resolve the input. */
static rg2_status op_begin(pctx *c, const cJSON *obj, const char *path, const char *const *keys,
                           int nk, int *src)
{
    rg2_status st = check_keys(c, obj, path, keys, nk);
    if (st)
        return st;
    char p[300];
    subpath(p, sizeof p, path, keys[0]);
    return mesh_ref(c, get(obj, keys[0]), p, src);
}

static rg2_status op_shape(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"shape", "u", "v"};
    rg2_status st = check_keys(c, obj, path, keys, 3);
    if (st)
        return st;
    char p[300];
    const char *label;
    subpath(p, sizeof p, path, "shape");
    if ((st = as_str(c, get(obj, "shape"), p, &label)))
        return st;
    int sh = find_shape(c->d, label);
    if (sh < 0 && rg2__design_find_mesh(c->d, label) >= 0)
        return fail(c, RG2_EPARSE, p,
                    "'%s' is a mesh, not a shape label; \"shape\" takes a label of \"shapes\" (to work on "
                    "the mesh, use it in cut, edit, transform, ...)", label);
    if (sh < 0) {
        char sug[128];
        suggest(label, (const char *const *)c->d->labels, c->d->n_shapes, sug, sizeof sug);
        return fail(c, RG2_EPARSE, p, "no shape labelled '%s' in \"shapes\"%s", label, sug);
    }
    const rg2_shape_desc *desc = rg2_shape_describe(c->d->shapes[sh].kind);
    part_buf pb[2] = {{{0}, NULL}, {{0}, NULL}};
    for (int k = 0; k < 2 && !st; k++) {
        subpath(p, sizeof p, path, k ? "v" : "u");
        st = parse_partition(c, get(obj, k ? "v" : "u"), p, desc, k, &pb[k]);
    }
    if (!st) /* (p: the v partition's path) */
        st = rg2__op_shape(c->d, sh, &pb[0].p, &pb[1].p, out, path, p, c->err);
    free(pb[0].values);
    free(pb[1].values);
    return st;
}

static rg2_status op_cut(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"cut", "u", "v"};
    int src;
    char p[300];
    rg2_status st = op_begin(c, obj, path, keys, 3, &src);
    if (st)
        return st;
    const rg2__dmesh *in = &c->d->mesh[src];
    int first[2] = {-1, -1}, last[2] = {-1, -1};
    char dp[2][320];
    const char *const dpath[2] = {dp[0], dp[1]};
    if (!get(obj, "u") && !get(obj, "v"))
        return fail(c, RG2_EPARSE, path, "a cut needs a range in 'u' or 'v'");
    for (int k = 0; k < 2; k++) {
        const cJSON *x = get(obj, k ? "v" : "u");
        subpath(p, sizeof p, path, k ? "v" : "u");
        fmtpath(dp[k], sizeof dp[k], "%s", p);
        if (!x)
            continue;
        const rg2_scalars *s = k ? &in->m.sv : &in->m.su;
        if (cJSON_IsObject(x)) {
            static const char *const ok[] = {"open_at"};
            if ((st = check_keys(c, x, p, ok, 1)))
                return st;
            const cJSON *y;
            if ((st = need(c, x, "open_at", p, &y)))
                return st;
            char q[320];
            subpath(q, sizeof q, p, "open_at");
            int j = 0;
            if ((st = as_int(c, y, q, &j)))
                return st;
            if (!s->closed)
                return fail(c, RG2_EINVAL, q, "mesh '%s' is already open in %s", in->name, k ? "v" : "u");
            if (j < 0 || j >= s->n)
                return fail(c, RG2_EINVAL, q, "junction %d is outside 0..%d of mesh '%s'", j, s->n - 1, in->name);
            if (s->n < 4)
                return fail(c, RG2_EINVAL, q,
                            "mesh '%s' has %d control points in %s; opened, it needs at least 4 (an open "
                            "direction's minimum)", in->name, s->n, k ? "v" : "u");
            fmtpath(dp[k], sizeof dp[k], "%s", q);
            first[k] = j;
            last[k] = j + s->n - 1;
        } else {
            double r[2];
            if ((st = as_nums(c, x, p, r, 2, 2, NULL)))
                return st;
            for (int q = 0; q < 2; q++)
                if (r[q] != floor(r[q]) || fabs(r[q]) > 1e9)
                    return fail(c, RG2_EPARSE, p, "expected integer indices [first, last], found %s",
                                rg2__num(r[q]).s);
            first[k] = (int)r[0];
            last[k] = (int)r[1];
            if (first[k] < 0)
                return fail(c, RG2_EINVAL, p, "first index %d is negative", first[k]);
        }
    }
    return rg2__op_cut(in, first, last, out, dpath, c->err);
}

static rg2_status parse_dir(pctx *c, const cJSON *x, const char *path, int *dir)
{
    const char *s = NULL;
    rg2_status st = as_str(c, x, path, &s);
    if (st)
        return st;
    if (!strcmp(s, "u") || !strcmp(s, "v")) {
        *dir = s[0] == 'v';
        return RG2_OK;
    }
    return fail(c, RG2_EPARSE, path, "expected \"u\" or \"v\", found \"%s\"", s);
}

static rg2_status op_merge(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"merge", "along", "closed", "seam"};
    rg2_status st = check_keys(c, obj, path, keys, 4);
    if (st)
        return st;
    char p[300];
    const cJSON *x = get(obj, "merge"), *y;
    subpath(p, sizeof p, path, "merge");
    if (!cJSON_IsArray(x) || cJSON_GetArraySize(x) < 2)
        return fail(c, RG2_EPARSE, p, "expected an array of at least 2 mesh names, found %s",
                    cJSON_IsArray(x) ? "a shorter array" : type_name(x));
    int n = cJSON_GetArraySize(x);
    const rg2__dmesh **in = rg2__calloc((size_t)n, sizeof *in);
    if (!in)
        return fail(c, RG2_ENOMEM, p, "out of memory");
    int k = 0;
    for (const cJSON *it = x->child; it; it = it->next, k++) {
        char q[320];
        indexpath(q, sizeof q, p, k);
        int idx;
        if ((st = mesh_ref(c, it, q, &idx))) {
            free(in);
            return st;
        }
        in[k] = &c->d->mesh[idx];
    }
    int dir = 0, closed = 0;
    rg2__seam_rule rule = RG2__SEAM_PRESERVE;
    subpath(p, sizeof p, path, "along");
    if ((st = need(c, obj, "along", path, &y)) || (st = parse_dir(c, y, p, &dir)))
        goto done;
    if ((y = get(obj, "closed"))) {
        subpath(p, sizeof p, path, "closed");
        if ((st = as_bool(c, y, p, &closed)))
            goto done;
    }
    if ((y = get(obj, "seam"))) {
        const char *s;
        subpath(p, sizeof p, path, "seam");
        if ((st = as_str(c, y, p, &s)))
            goto done;
        if (!strcmp(s, "plain"))
            rule = RG2__SEAM_PLAIN;
        else if (strcmp(s, "preserve")) {
            st = fail(c, RG2_EPARSE, p, "unknown seam rule '%s'; known: preserve, plain", s);
            goto done;
        }
    }
    st = rg2__op_merge(in, n, dir, closed, rule, out, path, c->err);
    if (!st && ((st = rg2__merge_twist_notes(c->d, in, n, dir, closed, path, c->err)) ||
                (st = rg2__merge_overlap_notes(c->d, in, n, dir, closed, path, &out->weight_noted, c->err))))
        rg2__dmesh_free(out);
done:
    free(in);
    return st;
}

static rg2_status op_transpose(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"transpose"};
    int src;
    rg2_status st = op_begin(c, obj, path, keys, 1, &src);
    if (st)
        return st;
    return rg2__op_transpose(&c->d->mesh[src], out, path, c->err);
}

/* The source mesh and the required "dir" of a one-direction operation (reverse, roll). */
static rg2_status op_begin_dir(pctx *c, const cJSON *obj, const char *path, const char *const *keys, int nk,
                               int *src, int *dir)
{
    rg2_status st = op_begin(c, obj, path, keys, nk, src);
    if (st)
        return st;
    const cJSON *x;
    char p[300];
    subpath(p, sizeof p, path, "dir");
    if ((st = need(c, obj, "dir", path, &x)) || (st = parse_dir(c, x, p, dir)))
        return st;
    return RG2_OK;
}

static rg2_status op_reverse(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"reverse", "dir"};
    int src, dir;
    rg2_status st = op_begin_dir(c, obj, path, keys, 2, &src, &dir);
    if (st)
        return st;
    return rg2__op_reverse(&c->d->mesh[src], dir, out, path, c->err);
}

static rg2_status op_roll(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"roll", "dir", "by"};
    int src, dir, by = 0; /* (set by as_int; GCC -O2 cannot see it) */
    rg2_status st = op_begin_dir(c, obj, path, keys, 3, &src, &dir);
    if (st)
        return st;
    const cJSON *x;
    char p[300];
    subpath(p, sizeof p, path, "by");
    if ((st = need(c, obj, "by", path, &x)) || (st = as_int(c, x, p, &by)))
        return st;
    return rg2__op_roll(&c->d->mesh[src], dir, by, out, path, c->err);
}

static rg2_status op_transform(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"transform", "matrix", "translate", "rotate", "scale"};
    int src, any;
    double M[16];
    rg2_status st = op_begin(c, obj, path, keys, 5, &src);
    if (st)
        return st;
    if ((st = parse_placement(c, obj, path, M, &any)))
        return st;
    if (!any)
        return fail(c, RG2_EPARSE, path, "a transform needs 'matrix', 'translate', 'rotate' or 'scale'");
    double inv[16]; /* refused as a shape's placement is: the transformed shapes' equations need it */
    rg2_error e;
    if ((st = rg2_xform_invert(M, inv, &e))) {
        char p[300];
        subpath(p, sizeof p, path, "matrix");
        return fail(c, st, get(obj, "matrix") ? p : path, "%s", e.msg);
    }
    return rg2__op_transform(c->d, &c->d->mesh[src], M, out, path, c->err);
}

static rg2_status op_morph(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"morph", "t"};
    rg2_status st = check_keys(c, obj, path, keys, 2);
    if (st)
        return st;
    char p[300];
    const cJSON *x = get(obj, "morph"), *y;
    subpath(p, sizeof p, path, "morph");
    if (!cJSON_IsArray(x) || cJSON_GetArraySize(x) != 2) {
        char n[32];
        snprintf(n, sizeof n, "%d", cJSON_GetArraySize(x));
        return fail(c, RG2_EPARSE, p, "expected an array of 2 mesh names, found %s%s", cJSON_IsArray(x) ? "an array of " : "",
                    cJSON_IsArray(x) ? n : type_name(x));
    }
    int a, b;
    char q[320];
    fmtpath(q, sizeof q, "%s[0]", p);
    if ((st = mesh_ref(c, x->child, q, &a)))
        return st;
    fmtpath(q, sizeof q, "%s[1]", p);
    if ((st = mesh_ref(c, x->child->next, q, &b)))
        return st;
    double t;
    subpath(p, sizeof p, path, "t");
    if ((st = need(c, obj, "t", path, &y)) || (st = as_num(c, y, p, &t)))
        return st;
    if (t < 0.0 || t > 1.0) /* 1.000001, not 1 (%g) or 1.0000009999999999 */
        return fail(c, RG2_EDOMAIN, p, "t = %s, must lie in [0, 1]", rg2__num(t).s);
    return rg2__op_morph(&c->d->mesh[a], &c->d->mesh[b], t, out, path, c->err);
}

/* The state edit_points keeps across the entries of one edit (allocated on first need, freed at
 * the end): `first`, for a list of points, the entry + 1 that first named each point (a point
 * listed twice is refused), cleared again after each list at the points it set; `net`, for
 * 'normal', the control points as they were before the current entry, copied at the first
 * 'normal' entry and then kept equal to the mesh by copying the points each entry changed. Each
 * entry used to allocate both for the whole mesh (and copy it for 'normal'): an edit of E
 * entries on a mesh of N points cost E x N (4000 entries of 'normal' on 1000 x 1003 points
 * copied 128 GB: 32.5 s, now 0.97 s; test_scaling counts the bytes). */
typedef struct {
    int *first;
    double *net;
    size_t *listed, n_listed, cap_listed; /* the mesh indices the current entry named */
} edit_state;

static void edit_state_free(edit_state *es)
{
    free(es->first);
    free(es->net);
    free(es->listed);
}

static rg2_status edit_points(pctx *c, const cJSON *arr, const char *path, rg2__dmesh *m)
{
    if (!cJSON_IsArray(arr))
        return fail(c, RG2_EPARSE, path, "expected an array of point edits, found %s", type_name(arr));
    int k = 0;
    rg2_status st = RG2_OK;
    edit_state es = {NULL, NULL, NULL, 0, 0};
    const size_t np = (size_t)m->m.nu * (size_t)m->m.nv;
    for (const cJSON *e = arr->child; e; e = e->next, k++) {
        char p[300], q[320];
        indexpath(p, sizeof p, path, k);
        static const char *const keys[] = {"at", "move", "to", "normal", "W", "pole"};
        if ((st = as_obj(c, e, p)) || (st = check_keys(c, e, p, keys, 6)))
            break;
        const cJSON *at = NULL, *mv = get(e, "move"), *to = get(e, "to"), *W = get(e, "W"), *pole = get(e, "pole");
        const cJSON *nrm = get(e, "normal");
        if (pole && get(e, "at")) {
            st = fail(c, RG2_EPARSE, p, "give 'at' (points) or 'pole' (a polar point), not both");
            break;
        }
        if (!pole && (st = need(c, e, "at", p, &at)))
            break;
        if (!!mv + !!to + !!nrm > 1) {
            st = fail(c, RG2_EPARSE, p, "give one of 'move' (offset), 'to' (position) and 'normal' (offset along "
                                        "the net's normal)");
            break;
        }
        if (!mv && !to && !nrm && !W) {
            st = fail(c, RG2_EPARSE, p, "a point edit needs 'move', 'to', 'normal' or 'W'");
            break;
        }
        if (nrm && pole) {
            st = fail(c, RG2_EPARSE, p, "a polar point has no net normal: move it with 'move' or 'to'");
            break;
        }
        double v[3], w = 0, dist = 0;
        if (mv || to) {
            subpath(q, sizeof q, p, mv ? "move" : "to");
            if ((st = as_nums(c, mv ? mv : to, q, v, 3, 3, NULL)))
                break;
        }
        if (nrm) {
            subpath(q, sizeof q, p, "normal");
            if ((st = as_num(c, nrm, q, &dist)))
                break;
        }
        if (W) {
            subpath(q, sizeof q, p, "W");
            if ((st = as_num(c, W, q, &w)))
                break;
            if (!(w > 0.0)) {
                st = fail(c, RG2_EWEIGHT, q, "weight W = %g, must be > 0", w);
                break;
            }
        }
        if (pole) { /* a polar point: the whole collapsed row moves (docs/poles.md) */
            const char *pn = NULL;
            subpath(q, sizeof q, p, "pole");
            if ((st = as_str(c, pole, q, &pn)))
                break;
            if (strcmp(pn, "south") && strcmp(pn, "north")) {
                st = fail(c, RG2_EPARSE, q, "expected \"south\" or \"north\", found '%s'", pn);
                break;
            }
            int end = !strcmp(pn, "north");
            if ((mv || to) && (st = rg2__edit_pole(m, end, mv ? RG2__EDIT_MOVE : RG2__EDIT_TO, v, q, c->err)))
                break;
            if (W && (st = rg2__edit_pole(m, end, RG2__EDIT_WEIGHT, &w, q, c->err)))
                break;
            if (es.net) /* (the row it moved) */
                for (int i = 0, j = end ? m->m.nv - 1 : 0; i < m->m.nu; i++)
                    memcpy(es.net + 4 * ((size_t)i * (size_t)m->m.nv + (size_t)j), rg2_mesh_at(&m->m, i, j),
                           4 * sizeof *es.net);
            continue;
        }
        /* "at": [i, j] or [[i, j], ...] */
        subpath(q, sizeof q, p, "at");
        if (!cJSON_IsArray(at) || cJSON_GetArraySize(at) < 1) {
            st = fail(c, RG2_EPARSE, q, "expected [i, j] or a list of [i, j], found %s",
                      cJSON_IsArray(at) ? "an empty array" : type_name(at));
            break;
        }
        int multi = cJSON_IsArray(at->child);
        /* a point listed twice in one list (a move would apply twice): the entry that first
         * named each point, + 1 */
        if (multi && !es.first && !(es.first = rg2__calloc(np, sizeof *es.first))) {
            st = rg2__fail(c->err, RG2_ENOMEM, "%s: out of memory", q);
            break;
        }
        /* 'normal': every listed point's normal from the net as it was before this entry */
        if (nrm && !es.net) {
            if (!(es.net = rg2__calloc(np * 4, sizeof *es.net))) {
                st = rg2__fail(c->err, RG2_ENOMEM, "%s: out of memory", q);
                break;
            }
            memcpy(es.net, m->m.p, np * 4 * sizeof *es.net);
        }
        rg2_mesh net = m->m;
        net.p = es.net;
        es.n_listed = 0;
        int idx = 0;
        for (const cJSON *it = multi ? at->child : at; !st && it; it = multi ? it->next : NULL, idx++) {
            char r[340];
            if (multi)
                indexpath(r, sizeof r, q, idx);
            else
                fmtpath(r, sizeof r, "%s", q);
            double ij[2];
            if ((st = as_nums(c, it, r, ij, 2, 2, NULL)))
                break;
            if (ij[0] != floor(ij[0]) || ij[1] != floor(ij[1]) || fabs(ij[0]) > 1e9 || fabs(ij[1]) > 1e9) {
                st = fail(c, RG2_EPARSE, r, "expected integer indices [i, j], found [%s, %s]",
                          rg2__num(ij[0]).s, rg2__num(ij[1]).s);
                break;
            }
            int i = (int)ij[0], j = (int)ij[1];
            if (nrm && !(st = rg2__net_normal(&net, i, j, v, r, c->err)))
                for (int k2 = 0; k2 < 3; k2++)
                    v[k2] *= dist;
            if (!st && (mv || to || nrm))
                st = rg2__edit_point(m, i, j, to ? RG2__EDIT_TO : RG2__EDIT_MOVE, v, r, c->err);
            if (!st && W)
                st = rg2__edit_point(m, i, j, RG2__EDIT_WEIGHT, &w, r, c->err);
            if (st)
                break;
            size_t at_k = (size_t)i * (size_t)m->m.nv + (size_t)j; /* (in range) */
            int *f = multi ? &es.first[at_k] : NULL;
            if (f && *f) {
                st = fail(c, RG2_EPARSE, r, "control point [%d, %d] is listed twice (at[%d] and at[%d])%s", i, j,
                          *f - 1, idx, mv || nrm ? ": the move would apply twice" : "");
                break;
            }
            if (f)
                *f = idx + 1;
            if (es.n_listed == es.cap_listed) {
                size_t nc = es.cap_listed ? 2 * es.cap_listed : 16;
                size_t *g = realloc(es.listed, nc * sizeof *g);
                if (!g) {
                    st = rg2__fail(c->err, RG2_ENOMEM, "%s: out of memory", q);
                    break;
                }
                es.listed = g;
                es.cap_listed = nc;
            }
            es.listed[es.n_listed++] = at_k;
        }
        if (st)
            break;
        for (size_t t = 0; t < es.n_listed; t++) { /* the next entry starts from the mesh as it is now */
            if (multi)
                es.first[es.listed[t]] = 0;
            if (es.net)
                memcpy(es.net + 4 * es.listed[t], m->m.p + 4 * es.listed[t], 4 * sizeof *es.net);
        }
    }
    edit_state_free(&es);
    return st;
}

static rg2_status edit_scalars(pctx *c, const cJSON *arr, const char *path, rg2__dmesh *m)
{
    if (!cJSON_IsArray(arr))
        return fail(c, RG2_EPARSE, path, "expected an array of scalar edits, found %s", type_name(arr));
    int k = 0;
    rg2_status st;
    for (const cJSON *e = arr->child; e; e = e->next, k++) {
        char p[300], q[320];
        indexpath(p, sizeof p, path, k);
        static const char *const keys[] = {"dir", "leg", "junction", "w", "b", "g"};
        if ((st = as_obj(c, e, p)) || (st = check_keys(c, e, p, keys, 6)))
            return st;
        const cJSON *d, *leg = get(e, "leg"), *jun = get(e, "junction");
        int dir, idx = 0;
        subpath(q, sizeof q, p, "dir");
        if ((st = need(c, e, "dir", p, &d)) || (st = parse_dir(c, d, q, &dir)))
            return st;
        if (!leg == !jun)
            return fail(c, RG2_EPARSE, p, "give exactly one of 'leg' (for w) or 'junction' (for b, g)");
        subpath(q, sizeof q, p, leg ? "leg" : "junction");
        if ((st = as_int(c, leg ? leg : jun, q, &idx)))
            return st;
        const rg2_scalars *sc = dir ? &m->m.sv : &m->m.su;
        int lo = leg && !sc->closed ? -1 : 0, hi = sc->n - 1; /* (open: legs -1 and n - 1 are data-only) */
        if (idx < lo || idx > hi)
            return fail(c, RG2_EINVAL, q, "%s %s %d is outside %d..%d of mesh '%s'", dir ? "v" : "u",
                        leg ? "leg" : "junction", idx, lo, hi, m->name);
        static const char which[3] = {'w', 'b', 'g'};
        int any = 0;
        for (int s = 0; s < 3; s++) {
            char key[2] = {which[s], 0};
            const cJSON *x = get(e, key);
            if (!x)
                continue;
            subpath(q, sizeof q, p, key);
            if ((s == 0) != (leg != NULL))
                return fail(c, RG2_EPARSE, q, "'%s' goes with a '%s', not a '%s' ('w' belongs to a leg, 'b' and "
                            "'g' to a junction)", key, s ? "junction" : "leg", leg ? "leg" : "junction");
            double v;
            if ((st = as_num(c, x, q, &v)) || (st = rg2__edit_scalar(m, dir, which[s], idx, v, q, c->err)))
                return st;
            any = 1;
        }
        if (!any)
            return fail(c, RG2_EPARSE, p, "a scalar edit needs 'w' (leg) or 'b'/'g' (junction)");
    }
    return RG2_OK;
}

static rg2_status op_edit(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"edit", "points", "scalars"};
    int src;
    char p[300];
    rg2_status st = op_begin(c, obj, path, keys, 3, &src);
    if (st)
        return st;
    const cJSON *pts = get(obj, "points"), *scs = get(obj, "scalars");
    if (!pts && !scs)
        return fail(c, RG2_EPARSE, path, "an edit needs 'points' or 'scalars'");
    /* [] edits nothing: as good as no key (a list left empty while writing the file) */
    if ((!pts || (cJSON_IsArray(pts) && !pts->child)) && (!scs || (cJSON_IsArray(scs) && !scs->child)))
        return fail(c, RG2_EPARSE, path, "an edit needs 'points' or 'scalars'; %s empty (it would copy the mesh "
                    "unchanged)", pts && scs ? "both lists are" : pts ? "'points' is" : "'scalars' is");
    if ((st = rg2__dmesh_copy(&c->d->mesh[src], out, c->err)))
        return st;
    out->name = c->d->mesh[src].name; /* borrowed for messages; replaced by the caller */
    if (pts) {
        subpath(p, sizeof p, path, "points");
        st = edit_points(c, pts, p, out);
    }
    if (!st && scs) {
        subpath(p, sizeof p, path, "scalars");
        st = edit_scalars(c, scs, p, out);
    }
    for (int k = 0; k < 2 && !st; k++) { /* K > 0 after all the edits: name the last edit of the junction */
        const rg2_scalars *sc = k ? &out->m.sv : &out->m.su;
        int i = rg2__bad_junction(sc), blame = -1, e = 0;
        for (const cJSON *it = cJSON_GetArrayItem(scs, 0); i >= 0 && it; it = it->next, e++) {
            const cJSON *leg = get(it, "leg"), *jun = get(it, "junction");
            int id = (int)(leg ? leg : jun)->valuedouble; /* (checked above) */
            int l0 = sc->closed ? rg2__wrap(i - 1, sc->n, 1) : i - 1; /* junction i joins legs i - 1, i */
            if (!strcmp(get(it, "dir")->valuestring, k ? "v" : "u") && (leg ? id == l0 || id == i : id == i))
                blame = e;
        }
        char w[340];
        if (blame >= 0)
            fmtpath(w, sizeof w, "%s: %s.scalars[%d]", c->file, path, blame);
        else
            fmtpath(w, sizeof w, "%s: %s", c->file, path);
        st = rg2__dir_check(sc, k, w, "", c->err);
    }
    out->name = NULL;
    if (st)
        rg2__dmesh_free(out);
    else /* a NURBS pole side the edits leave alone (none of the values its patches read) */
        rg2__poles_keep_same(out, &c->d->mesh[src]);
    return st;
}

static rg2_status op_polar(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out);
static rg2_status op_nurbs(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out);
static rg2_status nurbs_spec(pctx *c, const cJSON *spec, const char *p, rg2_mesh *mout, unsigned *poles,
                             double pole[4][3]);
static rg2_status op_mobius(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out);
static rg2_status op_cap(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out);

/* A transform's matrix must keep the weights W = p_4 of the control points positive, like a
 * shape's placement (rg2_shape_mesh): the design points are p_{1..3} / W, and a weight the
 * matrix turns <= 0 puts the surface through infinity (the exports then write garbage).
 * Weights that were <= 0 already are the shape's (docs/shapes.md "Homogeneous weights"). The
 * other operations cannot turn a positive weight non-positive: cut, merge, transpose, reverse
 * and morph (t in [0, 1]) keep or blend weights, edits check their W, mobius checks its own. */
static rg2_status transform_weights(pctx *c, const cJSON *obj, const char *path, const rg2__dmesh *m)
{
    const cJSON *x = get(obj, "transform");
    int k = cJSON_IsString(x) ? rg2__design_find_mesh(c->d, x->valuestring) : -1;
    if (k < 0 || c->d->mesh[k].m.nu != m->m.nu || c->d->mesh[k].m.nv != m->m.nv)
        return RG2_OK;
    const rg2_mesh *in = &c->d->mesh[k].m;
    for (int i = 0; i < m->m.nu; i++)
        for (int j = 0; j < m->m.nv; j++) {
            double W = rg2_mesh_at(&m->m, i, j)[3], before = rg2_mesh_at(in, i, j)[3];
            if (W > 0.0 || !(before > 0.0))
                continue;
            char p[300];
            subpath(p, sizeof p, path, "matrix");
            return fail(c, rg2__finite(W) ? RG2_EWEIGHT : RG2_ENONFINITE, get(obj, "matrix") ? p : path,
                        "the transform gives control point [%d, %d] of mesh '%s' the weight W = %.6g (%.6g "
                        "before); weights must stay > 0 (the matrix's last row must be positive on the "
                        "whole mesh, or the surface passes through infinity)",
                        i, j, c->d->mesh[k].name, W, before);
        }
    return RG2_OK;
}

/* 1 + the capped mesh that operation `op` of obj takes as an input (or that one of its inputs was
 * made from uncapped), 0 none: the operation uses it uncapped, as a cap belongs to an output. */
static int capped_input(pctx *c, const cJSON *obj, int op)
{
    if (op_makes_mesh_from_nothing(op))
        return 0;
    const cJSON *x = get(obj, ops[op]);
    const cJSON *it = cJSON_IsArray(x) ? x->child : x;
    for (; it; it = cJSON_IsArray(x) ? it->next : NULL) {
        int k = cJSON_IsString(it) ? rg2__design_find_mesh(c->d, it->valuestring) : -1;
        if (k >= 0 && c->d->mesh[k].capped)
            return k + 1;
        if (k >= 0 && c->d->mesh[k].uncapped_of)
            return c->d->mesh[k].uncapped_of;
    }
    return 0;
}

static rg2_status parse_mesh(pctx *c, const cJSON *obj, const char *name, const char *path)
{
    rg2_status st = as_obj(c, obj, path);
    if (st)
        return st;
    int op = -1;
    for (int k = 0; k < N_OPS; k++)
        if (get(obj, ops[k])) {
            if (op >= 0)
                return fail(c, RG2_EPARSE, path, "both '%s' and '%s': a mesh has exactly one operation",
                            ops[op], ops[k]);
            op = k;
        }
    if (op < 0) {
        char list[160] = ""; /* the operations, from their table: "shape, cut, ..., roll" */
        for (int k = 0; k < N_OPS; k++)
            snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", k ? ", " : "", ops[k]);
        /* a misspelt operation ("merg"): name it and the operation it is closest to */
        for (const cJSON *it = obj->child; it; it = it->next) {
            char sug[128] = "";
            if (strcmp(it->string, "comment"))
                suggest(it->string, ops, N_OPS, sug, sizeof sug);
            if (sug[0])
                return fail(c, RG2_EPARSE, path, "unknown key '%s'%s; a mesh needs one operation: %s", it->string,
                            sug, list);
        }
        return fail(c, RG2_EPARSE, path, "no operation: give one of %s", list);
    }
    if (rg2__design_find_mesh(c->d, name) >= 0)
        return fail(c, RG2_EPARSE, path, "a mesh named '%s' already exists", name);
    rg2__dmesh tmp;
    memset(&tmp, 0, sizeof tmp);
    switch (op) {
    case OP_SHAPE: st = op_shape(c, obj, path, &tmp); break;
    case OP_CUT: st = op_cut(c, obj, path, &tmp); break;
    case OP_MERGE: st = op_merge(c, obj, path, &tmp); break;
    case OP_TRANSPOSE: st = op_transpose(c, obj, path, &tmp); break;
    case OP_REVERSE: st = op_reverse(c, obj, path, &tmp); break;
    case OP_EDIT: st = op_edit(c, obj, path, &tmp); break;
    case OP_TRANSFORM: st = op_transform(c, obj, path, &tmp); break;
    case OP_MORPH: st = op_morph(c, obj, path, &tmp); break;
    case OP_POLAR: st = op_polar(c, obj, path, &tmp); break;
    case OP_MOBIUS: st = op_mobius(c, obj, path, &tmp); break;
    case OP_CAP: st = op_cap(c, obj, path, &tmp); break;
    case OP_NURBS: st = op_nurbs(c, obj, path, &tmp); break;
    default: st = op_roll(c, obj, path, &tmp); break; /* OP_ROLL */
    }
    if (st) {
        rg2__dmesh_free(&tmp); /* whatever the operation had allocated */
        /* the ops module's messages start with a JSON path but lack the file name; a message of the
         * layers below that an operation passed on as it is (out of memory) lacks the path too */
        if (strncmp(c->err->msg, c->file, strlen(c->file))) {
            rg2_error e = *c->err;
            if (!strncmp(e.msg, "meshes.", 7) || !strncmp(e.msg, "shapes.", 7))
                rg2__fail(c->err, st, "%s: %s", c->file, e.msg);
            else
                rg2__fail(c->err, st, "%s: %s: %s", c->file, path, e.msg);
        }
        return st;
    }
    tmp.uncapped_of = op == OP_CAP ? 0 : capped_input(c, obj, op);
    if (op == OP_TRANSFORM && (st = transform_weights(c, obj, path, &tmp))) {
        rg2__dmesh_free(&tmp);
        return st;
    }
    size_t total = (size_t)tmp.m.nu * (size_t)tmp.m.nv + c->d->mesh_points;
    if (total > RG2_DESIGN_MAX_POINTS) {
        rg2__dmesh_free(&tmp);
        return fail(c, RG2_ELIMIT, path, "the design's meshes reach %zu control points, more than the "
                    "limit of %d", total, RG2_DESIGN_MAX_POINTS);
    }
    rg2__dmesh *slot = rg2__design_new_mesh(c->d, c->err);
    if (!slot) {
        rg2__dmesh_free(&tmp);
        return c->err->code;
    }
    *slot = tmp;
    slot->name = rg2__calloc(strlen(name) + 1, 1);
    if (!slot->name) {
        rg2__dmesh_free(slot);
        return fail(c, RG2_ENOMEM, path, "out of memory");
    }
    strcpy(slot->name, name);
    if (rg2__design_commit_mesh(c->d, c->err)) {
        rg2__dmesh_free(slot);
        return fail(c, RG2_ENOMEM, path, "out of memory");
    }
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */

static void line_col(const char *text, size_t off, int *line, int *col)
{
    *line = 1;
    *col = 1;
    for (size_t k = 0; k < off && text[k]; k++) {
        if (text[k] == '\n') {
            (*line)++;
            *col = 1;
        } else
            (*col)++;
    }
}

/* Whether text[*k] belongs to a string (its quotes included), tracking *in_string; past an escape
 * *k moves onto the escaped character. */
static int string_char(const char *text, size_t *k, int *in_string)
{
    char ch = text[*k];
    if (*in_string) {
        if (ch == '\\')
            ++*k;
        else if (ch == '"')
            *in_string = 0;
        return 1;
    }
    if (ch == '"')
        *in_string = 1;
    return *in_string;
}

/* How deep in arrays and objects the text is at offset off (brackets in strings not counted). */
static int nesting(const char *text, size_t off)
{
    int depth = 0, in_string = 0;
    for (size_t k = 0; k < off && text[k]; k++) {
        char ch = text[k];
        if (string_char(text, &k, &in_string))
            continue;
        if (ch == '[' || ch == '{')
            depth++;
        else if (ch == ']' || ch == '}')
            depth--;
    }
    return depth;
}

/* Number literals cJSON takes that a JSON reader must not (RFC 8259 grammar:
 * -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?): a leading zero (01, -00.5), a '.' with no
 * digit after it (1., 1.e3) or no digit before it (-.5). cJSON reads them through strtod, so
 * rg2 took such a design while other JSON tools refuse it. */
enum { LIT_OK, LIT_TINY, LIT_LEADING_ZERO, LIT_BARE_POINT };

/* The first number literal of the text that is not JSON (LIT_LEADING_ZERO, LIT_BARE_POINT) or
 * that has a non-zero digit but so small an order (below 1e-323) that cJSON reads it as 0 or a
 * subnormal (LIT_TINY): 1e-400 would pass as the number 0, which the numeric range allows, while
 * 1e-320 is refused by value. Gives the offset of the literal and its length, or returns LIT_OK
 * when none (the text has parsed as JSON: numbers stand outside strings). The order comes from
 * the digits and the exponent, not from strtod (no locale). */
static int bad_literal(const char *t, size_t len, size_t *at, size_t *n)
{
    int in_string = 0;
    for (size_t k = 0; k < len; k++) {
        char ch = t[k];
        if (string_char(t, &k, &in_string))
            continue;
        if (ch != '-' && !(ch >= '0' && ch <= '9'))
            continue;
        size_t b = k;
        if (t[k] == '-')
            k++;
        long digits_before = 0, first_int = -1, first_frac = 0, f = 0;
        int frac = 0, kind = LIT_OK;
        for (; k < len && ((t[k] >= '0' && t[k] <= '9') || t[k] == '.'); k++) {
            if (t[k] == '.') {
                frac = 1;
                continue;
            }
            int nz = t[k] != '0';
            if (!frac) {
                if (digits_before == 1 && t[k - 1] == '0')
                    kind = LIT_LEADING_ZERO;
                if (nz && first_int < 0)
                    first_int = digits_before;
                digits_before++;
            } else {
                f++;
                if (nz && first_int < 0 && !first_frac)
                    first_frac = f;
            }
        }
        if (digits_before == 0 || (frac && f == 0))
            kind = LIT_BARE_POINT;
        int nonzero = first_int >= 0 || first_frac > 0;
        /* the order of the first non-zero digit: 10^order */
        long order = first_int >= 0 ? digits_before - 1 - first_int : -first_frac;
        long ex = 0;
        if (k < len && (t[k] == 'e' || t[k] == 'E')) {
            k++;
            int sign = 1;
            if (k < len && (t[k] == '+' || t[k] == '-'))
                sign = t[k++] == '-' ? -1 : 1;
            for (; k < len && t[k] >= '0' && t[k] <= '9'; k++)
                if (ex < 100000)
                    ex = ex * 10 + (t[k] - '0');
            ex *= sign;
        }
        if (kind == LIT_OK && nonzero && order + ex < -323)
            kind = LIT_TINY;
        if (kind != LIT_OK) {
            *at = b;
            *n = k - b;
            return kind;
        }
        k--; /* (the loop's k++ moves past the literal) */
    }
    return LIT_OK;
}

/* Parse a JSON text (a whole design file or a NURBS spec) into *root; the errors name name:line:col. */
static rg2_status parse_text(const char *json, size_t len, const char *name, cJSON **root, rg2_error *err)
{
    char *buf = malloc(len + 1);
    if (!buf)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory", name);
    memcpy(buf, json, len);
    buf[len] = 0;
    if (strlen(buf) != len) {
        size_t off = strlen(buf);
        int line, col;
        line_col(buf, off, &line, &col);
        /* a UTF-16 (or UTF-32) file, from Windows most often: a byte-order mark FF FE / FE FF, or
         * a NUL in the first two bytes, where JSON text has '{' or blanks */
        const unsigned char *u = (const unsigned char *)buf;
        int wide = off < 2 || (len >= 2 && ((u[0] == 0xff && u[1] == 0xfe) || (u[0] == 0xfe && u[1] == 0xff)));
        free(buf);
        return rg2__fail(err, RG2_EPARSE, "%s:%d:%d: NUL byte in the design text%s", name, line, col,
                         wide ? " (the file looks like UTF-16 or UTF-32: save it as UTF-8)" : "");
    }
    /* "\u0000" in a string: cJSON's strings are C strings and would end there silently */
    for (size_t i = 0; i + 1 < len; i++)
        if (buf[i] == '\\') {
            if (buf[i + 1] == 'u' && i + 5 < len && !strncmp(buf + i + 2, "0000", 4)) {
                int line, col;
                line_col(buf, i, &line, &col);
                free(buf);
                return rg2__fail(err, RG2_EPARSE, "%s:%d:%d: \\u0000 (a NUL character) in a string", name, line,
                                 col);
            }
            i++; /* skip the escaped character: \\ then u0000 is a backslash and text */
        }
    /* JSON text is UTF-8 (RFC 8259): other bytes would reach the labels, the messages and the
     * mesh file (rg2 mesh wrote them as they were: JSON no reader takes) */
    for (size_t i = 0; i < len;) {
        size_t n = rg2__utf8_len((const unsigned char *)buf + i, len - i);
        if (!n) {
            int line, col;
            line_col(buf, i, &line, &col);
            unsigned byte = (unsigned char)buf[i];
            free(buf);
            return rg2__fail(err, RG2_EPARSE, "%s:%d:%d: byte 0x%02x is not UTF-8 text (save the file as UTF-8)",
                             name, line, col, byte);
        }
        i += n;
    }
    size_t blank = 0; /* an empty file (or only white space) is not a syntax error to hunt for */
    while (blank < len && strchr(" \t\r\n", buf[blank]))
        blank++;
    if (blank == len) {
        free(buf);
        return rg2__fail(err, RG2_EPARSE, "%s is empty%s: there is no JSON object in it", name,
                         len ? " (only white space)" : "");
    }
    const char *end = NULL;
    *root = rg2__json_parse(buf, len + 1, &end);
    if (!*root) {
        size_t off = end ? (size_t)(end - buf) : 0;
        if (off > len)
            off = len;
        int line, col;
        line_col(buf, off, &line, &col);
        char near[24];
        size_t k = 0;
        for (; k < sizeof near - 1 && buf[off + k] && buf[off + k] != '\n'; k++)
            near[k] = buf[off + k];
        near[k] = 0;
        /* well formed, perhaps, but past the parser's depth: cJSON stops at the bracket one level too
         * deep (a syntax error at depth 1000, which it accepts, is not a nesting error) */
        if ((buf[off] == '[' || buf[off] == '{') && nesting(buf, off) >= CJSON_NESTING_LIMIT) {
            free(buf);
            return rg2__fail(err, RG2_ELIMIT, "%s:%d:%d: arrays and objects nested more than %d deep", name, line,
                             col, CJSON_NESTING_LIMIT);
        }
        size_t ws = 0; /* (only blanks or a CR before the line's end: a CRLF file, trailing spaces) */
        while (ws < k && (near[ws] == ' ' || near[ws] == '\t' || near[ws] == '\r'))
            ws++;
        if (ws == k && off + k < len && buf[off + k] == '\n') { /* at the end of a line (it said "at the end of the text"): what precedes */
            size_t b = off;
            while (b > 0 && off - b < sizeof near - 1 && buf[b - 1] != '\n')
                b--;
            memcpy(near, buf + b, off - b);
            near[off - b] = 0;
            free(buf);
            return rg2__fail(err, RG2_EPARSE, "%s:%d:%d: malformed JSON at the end of line %d, after '%s'", name, line,
                             col, line, near);
        }
        free(buf);
        return rg2__fail(err, RG2_EPARSE, "%s:%d:%d: malformed JSON %s%s%s", name, line, col,
                         k ? "near '" : "at the end of the text", near, k ? "'" : "");
    }
    size_t at, n;
    int lit = bad_literal(buf, len, &at, &n);
    if (lit != LIT_OK) {
        int line, col;
        line_col(buf, at, &line, &col);
        cJSON_Delete(*root);
        *root = NULL;
        int shown = (int)(n < 40 ? n : 40);
        const char *more = n <= 40 ? "" : "..."; /* (40 characters are shown whole) */
        rg2_status st =
            lit == LIT_TINY
                ? rg2__fail(err, RG2_EDOMAIN,
                            "%s:%d:%d: number %.*s%s is too small for a double (below 1e-323): it would read as 0 or "
                            "a subnormal; numbers must be 0 or have a magnitude from 1e-100 to 1e+100 (write 0 for "
                            "zero)",
                            name, line, col, shown, buf + at, more)
                : rg2__fail(err, RG2_EPARSE, "%s:%d:%d: malformed JSON: number %.*s%s %s", name, line, col, shown,
                            buf + at, more,
                            lit == LIT_LEADING_ZERO
                                ? "has a leading zero (JSON numbers do not: write 1, not 01; 0.5, not 00.5)"
                                : "has no digit on one side of its '.' (JSON numbers need both: write 1 or 1.0, not "
                                  "1.; 0.5, not .5)");
        free(buf);
        return st;
    }
    free(buf);
    return RG2_OK;
}

rg2_status rg2_nurbs_parse(const char *json, size_t len, const char *name, rg2_mesh *out, rg2_error *err)
{
    if (out) /* (first: a caller frees it whatever the outcome) */
        memset(out, 0, sizeof *out);
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "nurbs: NULL output mesh");
    if (!name) /* (as rg2_design_parse: a NULL name is the default) */
        name = "nurbs";
    if (!json)
        return rg2__fail(err, RG2_EINVAL, "%s: no text (NULL text)", name);
    if (len > RG2_TEXT_MAX_BYTES)
        return rg2__fail(err, RG2_ELIMIT, "%s: %zu bytes, more than the limit of %u", name, len, RG2_TEXT_MAX_BYTES);
    cJSON *root;
    rg2_status st = parse_text(json, len, name, &root, err);
    if (st)
        return st;
    pctx c = {NULL, name, err};
    st = nurbs_spec(&c, root, "nurbs", out, NULL, NULL); /* a mesh has no place for the poles */
    cJSON_Delete(root);
    if (!st)
        rg2__ok(err);
    return st;
}

rg2_status rg2__design_parse_json(rg2_design *d, const char *json, size_t len, const char *name,
                                  rg2_error *err)
{
    pctx c = {d, name, err};
    cJSON *root;
    rg2_status st = parse_text(json, len, name, &root, err);
    if (st)
        return st;
    static const char *const top[] = {"format", "description", "shapes", "meshes", "output", "expect"};
    if ((st = as_obj(&c, root, "(top level)")) || (st = check_keys(&c, root, "(top level)", top, 6)))
        goto done;
    const cJSON *x;
    if ((x = get(root, "format"))) {
        const char *f = NULL;
        if ((st = as_str(&c, x, "format", &f)))
            goto done;
        if (strcmp(f, "rg2 design 1")) {
            st = fail(&c, RG2_EPARSE, "format", "unsupported format '%s' (this is \"rg2 design 1\")", f);
            goto done;
        }
    }
    if ((x = get(root, "description")) && (st = as_str(&c, x, "description", &(const char *){0})))
        goto done;
    const cJSON *shapes, *meshes;
    if ((st = need(&c, root, "shapes", "(top level)", &shapes)) || (st = as_obj(&c, shapes, "shapes")))
        goto done;
    int comments = 0; /* a "comment" text before: a later "comment" shape is a duplicate too */
    for (const cJSON *it = shapes->child; it; it = it->next) {
        int is_comment = !strcmp(it->string, "comment");
        if (is_comment && cJSON_IsString(it)) {
            comments++;
            continue;
        }
        char p[300];
        fmtpath(p, sizeof p, "shapes.%s", it->string);
        /* every label before this one is a shape already (or failed the parse) */
        if (find_shape(d, it->string) >= 0 || (is_comment && comments)) {
            st = fail(&c, RG2_EPARSE, p, "duplicate shape label '%s'", it->string);
            goto done;
        }
        if ((st = parse_shape(&c, it, it->string, p)))
            goto done;
    }
    if ((st = need(&c, root, "meshes", "(top level)", &meshes)) || (st = as_obj(&c, meshes, "meshes")))
        goto done;
    for (const cJSON *it = meshes->child; it; it = it->next) {
        if (!strcmp(it->string, "comment") && cJSON_IsString(it))
            continue;
        char p[300];
        fmtpath(p, sizeof p, "meshes.%s", it->string);
        if ((st = parse_mesh(&c, it, it->string, p)))
            goto done;
    }
    if (!d->n_mesh) {
        st = fail(&c, RG2_EPARSE, "meshes", "no meshes");
        goto done;
    }
    /* outputs: a name, a list of names, or (default) the last mesh */
    x = get(root, "output");
    int n_out = !x ? 1 : cJSON_IsArray(x) ? cJSON_GetArraySize(x) : 1;
    if (n_out < 1) {
        st = fail(&c, RG2_EPARSE, "output", "empty output list");
        goto done;
    }
    d->out = rg2__calloc((size_t)n_out, sizeof(int));
    if (!d->out) {
        st = fail(&c, RG2_ENOMEM, "output", "out of memory");
        goto done;
    }
    d->n_out = n_out;
    d->out_key = x != NULL;
    if (!x)
        d->out[0] = d->n_mesh - 1;
    else if (cJSON_IsArray(x)) {
        int k = 0;
        int *listed = rg2__calloc((size_t)d->n_mesh, sizeof *listed); /* output index + 1 of each mesh */
        if (!listed) {
            st = fail(&c, RG2_ENOMEM, "output", "out of memory");
            goto done;
        }
        for (const cJSON *it = x->child; it; it = it->next, k++) {
            char p[40];
            fmtpath(p, sizeof p, "output[%d]", k);
            if ((st = mesh_ref(&c, it, p, &d->out[k])))
                break;
            if (listed[d->out[k]]) { /* the same surface twice in every export */
                st = fail(&c, RG2_EPARSE, p, "mesh '%s' is listed twice (also output[%d])",
                          d->mesh[d->out[k]].name, listed[d->out[k]] - 1);
                break;
            }
            listed[d->out[k]] = k + 1;
        }
        free(listed);
        if (st)
            goto done;
    } else if ((st = mesh_ref(&c, x, "output", &d->out[0])))
        goto done;
    if (!x) { /* no "output": the last mesh alone; a mesh no operation uses is built into nothing */
        char *used = rg2__calloc((size_t)d->n_mesh, 1);
        if (!used) {
            st = fail(&c, RG2_ENOMEM, "output", "out of memory");
            goto done;
        }
        for (const cJSON *it = meshes->child; it; it = it->next)
            for (int op = 0; op < N_OPS; op++) {
                const cJSON *v = op_makes_mesh_from_nothing(op) ? NULL : get(it, ops[op]);
                for (const cJSON *e = cJSON_IsArray(v) ? v->child : v; e; e = cJSON_IsArray(v) ? e->next : NULL) {
                    int m = cJSON_IsString(e) ? rg2__design_find_mesh(d, e->valuestring) : -1;
                    if (m >= 0)
                        used[m] = 1;
                }
            }
        int n_unused = 0;
        char list[300] = "";
        for (int k = 0; k + 1 < d->n_mesh; k++)
            if (!used[k] && n_unused++ < 4)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s'%s'", n_unused > 1 ? ", " : "",
                         d->mesh[k].name);
        free(used);
        if (n_unused) {
            char msg[900];
            snprintf(msg, sizeof msg,
                     "%s: meshes: %s%s %s and no operation uses %s, so %s built into nothing: without "
                     "\"output\" only the last mesh, '%s', is built; to build more, list them: \"output\": "
                     "[...]",
                     c.file, list, n_unused > 4 ? ", ..." : "", n_unused > 1 ? "are not outputs" : "is not an output",
                     n_unused > 1 ? "them" : "it", n_unused > 1 ? "they are" : "it is", d->mesh[d->n_mesh - 1].name);
            if ((st = rg2__design_add_note(d, msg, c.err)))
                goto done;
        }
    }
    for (int k = 0; k < d->n_out; k++) { /* an output made from a capped mesh, itself uncapped */
        const rg2__dmesh *o = &d->mesh[d->out[k]];
        if (o->capped || !o->uncapped_of)
            continue;
        const rg2__dmesh *cm = &d->mesh[o->uncapped_of - 1];
        int e = cm->cap.ends;
        char msg[900];
        snprintf(msg, sizeof msg,
                 "%s: meshes.%s: the output '%s' is made from '%s', which is capped, and has no caps: a cap "
                 "belongs to an output surface, so an operation uses a capped mesh uncapped; to close the "
                 "ends of '%s', cap it as '%s' is capped ({\"cap\": \"%s\", \"ends\": \"%s\"}, the same options)",
                 c.file, o->name, o->name, cm->name, o->name, cm->name, o->name,
                 e == (RG2_CAP_SOUTH | RG2_CAP_NORTH) ? "both" : e == RG2_CAP_SOUTH ? "south" : "north");
        if ((st = rg2__design_add_note(d, msg, c.err)))
            goto done;
    }
done:
    cJSON_Delete(root);
#ifdef __GLIBC__
    if (len > ((size_t)1 << 20))
        malloc_trim(0);
#endif
    return st;
}

/* ------------------------------------------------------------------------------------- */
/* poles operations (docs/poles.md): polar, mobius, cap */

/* {"nurbs": {"nu": .., "nv": .., "points": [[x, y, z], ...], "weights": [...], "knots_u": [...],
 * "knots_v": [...]}}: the control mesh of a bi-cubic NURBS (rg2_nurbs_mesh; the JSON of
 * `rg2 shape nurbs`). Its points carry no shape (provenance -1): there is no implicit equation to
 * measure them against, so its patches count as transitions, although every patch away from a
 * seam or an edit is the NURBS itself. */
/* "3" for an array of 3 items, else the JSON type ("a string"). */
static const char *len_or_type(const cJSON *x, char *buf, size_t cap)
{
    if (!cJSON_IsArray(x))
        return type_name(x);
    snprintf(buf, cap, "%d", cJSON_GetArraySize(x));
    return buf;
}

/* A bi-cubic NURBS spec {nu, nv, points, weights?, knots_u, knots_v} at JSON path p into m; with
 * poles, its pole ends too (rg2__nurbs_pole_ends). */
static rg2_status nurbs_spec(pctx *c, const cJSON *spec, const char *p, rg2_mesh *mout, unsigned *poles,
                             double pole[4][3])
{
    static const char *const nk[] = {"nu", "nv", "points", "weights", "knots_u", "knots_v"};
    char q[340], got[32];
    const cJSON *x;
    rg2_status st;
    if ((st = as_obj(c, spec, p)) || (st = check_keys(c, spec, p, nk, 6)))
        return st;
    int n[2];
    for (int k = 0; k < 2; k++) {
        subpath(q, sizeof q, p, k ? "nv" : "nu");
        if ((st = need(c, spec, k ? "nv" : "nu", p, &x)) || (st = as_int(c, x, q, &n[k])))
            return st;
        if (n[k] < 4 || n[k] > RG2_MAX_POINTS)
            return fail(c, n[k] < 4 ? RG2_EINVAL : RG2_ELIMIT, q,
                        "%d control points; a bi-cubic NURBS needs 4 to %d in each direction", n[k], RG2_MAX_POINTS);
    }
    size_t np = (size_t)n[0] * (size_t)n[1];
    if (np > RG2_DESIGN_MAX_POINTS)
        return fail(c, RG2_ELIMIT, p, "%d x %d control points, more than the limit of %d", n[0], n[1],
                    RG2_DESIGN_MAX_POINTS);
    const cJSON *pts, *wts = get(spec, "weights"), *kn[2];
    if ((st = need(c, spec, "points", p, &pts)) || (st = need(c, spec, "knots_u", p, &kn[0])) ||
        (st = need(c, spec, "knots_v", p, &kn[1])))
        return st;
    subpath(q, sizeof q, p, "points");
    if (!cJSON_IsArray(pts) || (size_t)cJSON_GetArraySize(pts) != np)
        return fail(c, RG2_EPARSE, q, "expected nu * nv = %zu points [x, y, z] (u-major: point (i, j) at i * nv + j), "
                    "found %s", np, len_or_type(pts, got, sizeof got));
    if (wts) {
        subpath(q, sizeof q, p, "weights");
        if (!cJSON_IsArray(wts) || (size_t)cJSON_GetArraySize(wts) != np)
            return fail(c, RG2_EPARSE, q, "expected nu * nv = %zu weights, found %s", np,
                        len_or_type(wts, got, sizeof got));
    }
    for (int k = 0; k < 2; k++) {
        subpath(q, sizeof q, p, k ? "knots_v" : "knots_u");
        if (!cJSON_IsArray(kn[k]) || cJSON_GetArraySize(kn[k]) != n[k] + 4)
            return fail(c, RG2_EPARSE, q, "expected %s + 4 = %d knots, found %s", k ? "nv" : "nu", n[k] + 4,
                        len_or_type(kn[k], got, sizeof got));
    }
    double *buf = rg2__calloc(np * 4 + (size_t)n[0] + (size_t)n[1] + 8, sizeof *buf);
    if (!buf)
        return fail(c, RG2_ENOMEM, p, "out of memory for %zu control points", np);
    double *P = buf, *W = buf + 3 * np, *U = W + np, *V = U + n[0] + 4;
    size_t k = 0;
    for (const cJSON *it = pts->child; it && !st; it = it->next, k++) {
        char r[360];
        subpath(q, sizeof q, p, "points");
        indexpath(r, sizeof r, q, (int)k);
        st = as_nums(c, it, r, P + 3 * k, 3, 3, NULL);
    }
    if (!st && wts) {
        subpath(q, sizeof q, p, "weights");
        st = as_nums(c, wts, q, W, 0, (int)np, NULL);
    }
    for (int d = 0; d < 2 && !st; d++) {
        subpath(q, sizeof q, p, d ? "knots_v" : "knots_u");
        st = as_nums(c, kn[d], q, d ? V : U, 0, n[d] + 4, NULL);
    }
    rg2_mesh m = {0};
    if (!st) {
        rg2_nurbs nb = {n[0], n[1], P, wts ? W : NULL, U, V};
        rg2_error e;
        if ((st = rg2_nurbs_mesh(&nb, &m, &e))) { /* its message names knots_u[k], weight (i, j), ... */
            const char *msg = strncmp(e.msg, "nurbs: ", 7) ? e.msg : e.msg + 7; /* p ends in nurbs */
            st = fail(c, st, p, "%s", msg);
        } else if (poles)
            *poles = rg2__nurbs_pole_ends(&nb, pole);
    }
    free(buf);
    if (!st)
        *mout = m;
    return st;
}

static rg2_status op_nurbs(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"nurbs"};
    rg2_status st = check_keys(c, obj, path, keys, 1);
    if (st)
        return st;
    char p[300];
    subpath(p, sizeof p, path, "nurbs");
    rg2_mesh m = {0};
    unsigned poles = 0;
    double pole[4][3] = {{0.0}};
    if ((st = nurbs_spec(c, get(obj, "nurbs"), p, &m, &poles, pole)))
        return st;
    if ((st = rg2__dmesh_alloc(out, NULL, m.nu, m.nv, 0, 0, c->err))) {
        rg2_mesh_free(&m);
        return st;
    }
    rg2_mesh_free(&out->m);
    out->m = m;
    out->poles = poles;
    memcpy(out->pole, pole, sizeof pole);
    for (int i = 0; i < m.nu; i++)
        for (int j = 0; j < m.nv; j++)
            *rg2__dmesh_pp(out, i, j) = (rg2__pprov){-1, i, j};
    for (int d = 0; d < 2; d++) {
        const rg2_scalars *sc = d ? &m.sv : &m.su;
        for (int i = 0; i < rg2_scalars_num_w(sc); i++)
            out->leg[d][i] = -1;
        for (int i = 0; i < sc->n; i++)
            out->jun[d][i] = -1;
    }
    return RG2_OK;
}

static rg2_status op_polar(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"polar", "u", "v"};
    rg2_status st = check_keys(c, obj, path, keys, 3);
    if (st)
        return st;
    char p[300], q[320];
    const char *label = NULL;
    subpath(p, sizeof p, path, "polar");
    if ((st = as_str(c, get(obj, "polar"), p, &label)))
        return st;
    int sh = find_shape(c->d, label);
    if (sh < 0) {
        char sug[128];
        suggest(label, (const char *const *)c->d->labels, c->d->n_shapes, sug, sizeof sug);
        return fail(c, RG2_EPARSE, p, "no shape labelled '%s' in \"shapes\"%s", label, sug);
    }
    const rg2_shape_desc *desc = rg2_shape_describe(c->d->shapes[sh].kind);
    if ((st = rg2__polar_kind(c->d, sh, path, c->err))) /* (before its partitions: a hypar's u is knots) */
        return st;
    const cJSON *vo, *kn;
    subpath(p, sizeof p, path, "v");
    static const char *const vkeys[] = {"knots"};
    /* (no default v: say what to give; the example knots suit all four kinds with poles) */
    static const char *const give = "a polar configuration has no default v: give its interior knots, at least 2, "
                                    "e.g. \"v\": {\"knots\": [0.2, 0.4, 0.6, 0.8]}";
    if (!(vo = get(obj, "v")))
        return fail(c, RG2_EPARSE, path, "missing key 'v': %s", give);
    if ((st = as_obj(c, vo, p)) || (st = check_keys(c, vo, p, vkeys, 1)))
        return st;
    if (!(kn = get(vo, "knots")))
        return fail(c, RG2_EPARSE, p, "missing key 'knots': %s", give);
    subpath(q, sizeof q, p, "knots");
    int len = cJSON_IsArray(kn) ? cJSON_GetArraySize(kn) : 0, m = 0;
    double *v = rg2__calloc((size_t)(len > 0 ? len : 1), sizeof(double));
    if (!v)
        return fail(c, RG2_ENOMEM, q, "out of memory");
    part_buf pb = {{0}, NULL};
    if (!(st = as_nums(c, kn, q, v, 0, MAX_PART, &m))) {
        subpath(p, sizeof p, path, "u");
        st = parse_partition(c, get(obj, "u"), p, desc, 0, &pb);
    }
    if (!st && !pb.p.closed) /* (the u of the shapes with poles is a circle) */
        st = fail(c, RG2_EPARSE, p, "a polar configuration needs a closed u-direction (full circle)");
    if (!st)
        st = rg2__op_polar(c->d, sh, &pb.p, v, m, out, path, q, c->err);
    free(v);
    free(pb.values);
    return st;
}

static rg2_status op_mobius(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"mobius", "sphere", "b", "poles"};
    int src, sh = -1;
    char p[300], q[320];
    rg2_status st = op_begin(c, obj, path, keys, 4, &src);
    if (st)
        return st;
    const cJSON *x;
    if ((x = get(obj, "sphere"))) {
        const char *label = NULL;
        subpath(p, sizeof p, path, "sphere");
        if ((st = as_str(c, x, p, &label)))
            return st;
        if ((sh = find_shape(c->d, label)) < 0) {
            char sug[128];
            suggest(label, (const char *const *)c->d->labels, c->d->n_shapes, sug, sizeof sug);
            return fail(c, RG2_EPARSE, p, "no shape labelled '%s' in \"shapes\"%s", label, sug);
        }
    }
    const cJSON *bj = get(obj, "b"), *pj = get(obj, "poles");
    if (!bj == !pj)
        return fail(c, RG2_EPARSE, path, "give exactly one of 'b' (eq. 16) or 'poles' ({\"south\": [x, y, z], "
                                         "\"north\": [x, y, z]})");
    double b = 0, poles[2][3];
    if (bj) {
        subpath(p, sizeof p, path, "b");
        if ((st = as_num(c, bj, p, &b)))
            return st;
    } else {
        static const char *const pk[] = {"south", "north"};
        subpath(p, sizeof p, path, "poles");
        if ((st = as_obj(c, pj, p)) || (st = check_keys(c, pj, p, pk, 2)))
            return st;
        for (int e = 0; e < 2; e++) {
            const cJSON *y;
            subpath(q, sizeof q, p, pk[e]);
            if ((st = need(c, pj, pk[e], p, &y)) || (st = as_nums(c, y, q, poles[e], 3, 3, NULL)))
                return st;
        }
    }
    return rg2__op_mobius(c->d, &c->d->mesh[src], sh, bj ? &b : NULL, poles, out, path, c->err);
}

static rg2_status op_cap(pctx *c, const cJSON *obj, const char *path, rg2__dmesh *out)
{
    static const char *const keys[] = {"cap", "ends", "length", "vc", "samples", "jet_weights", "quadratic"};
    int src;
    char p[300];
    rg2_status st = op_begin(c, obj, path, keys, 7, &src);
    if (st)
        return st;
    rg2_cap_opts o;
    rg2_cap_opts_default(&o);
    const cJSON *x;
    if ((x = get(obj, "ends"))) {
        const char *e = NULL;
        subpath(p, sizeof p, path, "ends");
        if ((st = as_str(c, x, p, &e)))
            return st;
        if (!strcmp(e, "both"))
            o.ends = RG2_CAP_SOUTH | RG2_CAP_NORTH;
        else if (!strcmp(e, "south"))
            o.ends = RG2_CAP_SOUTH;
        else if (!strcmp(e, "north"))
            o.ends = RG2_CAP_NORTH;
        else
            return fail(c, RG2_EPARSE, p, "expected \"both\", \"south\" or \"north\", found '%s'", e);
    }
    /* the options' ranges (rg2_cap_build checks them too, when the output is built) */
    char q[320];
    if ((x = get(obj, "length"))) {
        subpath(p, sizeof p, path, "length");
        if ((st = as_nums(c, x, p, o.length, 2, 2, NULL)))
            return st;
        for (int e = 0; e < 2; e++) {
            indexpath(q, sizeof q, p, e);
            if (!(o.length[e] >= 0.0))
                return fail(c, RG2_EDOMAIN, q, "%s cap length %g, must be > 0 (or 0: automatic)",
                            e ? "north" : "south", o.length[e]);
        }
        for (int e = 0; e < 2; e++) { /* a length for an end this cap leaves open: nothing uses it */
            if (!(o.length[e] > 0.0) || (o.ends & (e ? RG2_CAP_NORTH : RG2_CAP_SOUTH)))
                continue;
            char msg[700], hint[200] = "";
            indexpath(q, sizeof q, p, e);
            if (!(o.length[1 - e] > 0.0))
                snprintf(hint, sizeof hint, "; the %s cap's length 0 is automatic (for a %s cap of length %g "
                         "write [%g, %g])", e ? "south" : "north", e ? "south" : "north", o.length[e],
                         e ? o.length[e] : 0.0, e ? 0.0 : o.length[e]);
            snprintf(msg, sizeof msg,
                     "%s: %s: %g is the length of a %s cap, but this cap closes only the %s end (\"ends\": "
                     "\"%s\"), so it has no effect: the list is [south, north]%s",
                     c->file, q, o.length[e], e ? "north" : "south", e ? "south" : "north", e ? "south" : "north",
                     hint);
            if ((st = rg2__design_add_note(c->d, msg, c->err)))
                return st;
        }
        o.vc[0] = o.vc[1] = 0.5;
    }
    if ((x = get(obj, "vc"))) {
        subpath(p, sizeof p, path, "vc");
        if (!get(obj, "length"))
            return fail(c, RG2_EPARSE, p, "'vc' needs 'length' (both are automatic otherwise)");
        if ((st = as_nums(c, x, p, o.vc, 2, 2, NULL)))
            return st;
        for (int e = 0; e < 2; e++) {
            indexpath(q, sizeof q, p, e);
            if (!(o.vc[e] >= 0.0 && o.vc[e] < 1.0)) /* checked for both ends (used where length > 0) */
                return fail(c, RG2_EDOMAIN, q, "%s seam position v_c = %s, must lie in [0, 1)",
                            e ? "north" : "south", rg2__num(o.vc[e]).s);
        }
    }
    if ((x = get(obj, "samples"))) {
        subpath(p, sizeof p, path, "samples");
        if ((st = as_int(c, x, p, &o.samples)))
            return st;
        if (o.samples < 2 || o.samples > 256)
            return fail(c, RG2_EDOMAIN, p, "%d boundary samples per patch column, must be in 2..256", o.samples);
    }
    if ((x = get(obj, "jet_weights"))) {
        subpath(p, sizeof p, path, "jet_weights");
        if ((st = as_nums(c, x, p, o.jet_weight, 3, 3, NULL)))
            return st;
        for (int e = 0; e < 3; e++) {
            indexpath(q, sizeof q, p, e);
            if (!(o.jet_weight[e] > 0.0))
                return fail(c, RG2_EDOMAIN, q,
                            "weight %g (order %d of the boundary 2-jet), must be > 0 (a zero weight leaves the "
                            "cap's least-squares fit rank-deficient)",
                            o.jet_weight[e], e);
        }
    }
    if ((x = get(obj, "quadratic"))) {
        const char *qs = NULL;
        subpath(p, sizeof p, path, "quadratic");
        if ((st = as_str(c, x, p, &qs)))
            return st;
        if (!strcmp(qs, "rotational"))
            o.quadratic = RG2_CAP_ROTATIONAL;
        else if (!strcmp(qs, "general"))
            o.quadratic = RG2_CAP_GENERAL;
        else
            return fail(c, RG2_EPARSE, p, "expected \"rotational\" (bi-3 caps) or \"general\" (degree 4/5 in u), found '%s'", qs);
    }
    if ((st = rg2__dmesh_copy(&c->d->mesh[src], out, c->err)))
        return st;
    out->capped = 1;
    out->cap = o;
    out->cap_src = src;
    rg2__poles_keep_same(out, &c->d->mesh[src]); /* (for the operations that use it uncapped) */
    return RG2_OK;
}
