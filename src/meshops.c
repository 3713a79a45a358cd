/* meshops.c -- the design file's mesh operations (cut, transpose, reverse, merge, morph) for C
 * callers: plain rg2_mesh in, plain rg2_mesh out. Each wraps its input meshes as design meshes
 * (shallow views; no provenance) and runs the operation of design_ops.c, so a mesh built here
 * equals, bit for bit, the one a design file builds from the same meshes. */
#include "design_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A design mesh viewing m (its points and scalars shared, not copied; never rg2__dmesh_free'd),
 * every point and scalar of no source. */
typedef struct {
    rg2__dmesh d;
} view;

static void view_free(view *v)
{
    free(v->d.pp);
    for (int k = 0; k < 2; k++) {
        free(v->d.leg[k]);
        free(v->d.jun[k]);
    }
    memset(v, 0, sizeof *v);
}

/* A view of m, after rg2_mesh_check (its message prefixed with `what`); the operations' messages
 * call it `label` ("mesh 'in'"). */
static rg2_status view_init(view *v, const rg2_mesh *m, const char *what, const char *label, rg2_error *err)
{
    memset(v, 0, sizeof *v);
    if (!m)
        return rg2__fail(err, RG2_EINVAL, "%s is NULL", what);
    rg2_status st = rg2_mesh_check(m, err);
    if (st)
        return rg2__prefix(err, st, what);
    v->d.name = (char *)label; /* read by the operations' messages only */
    v->d.m = *m;
    size_t np = (size_t)m->nu * (size_t)m->nv;
    v->d.pp = rg2__calloc(1, np * sizeof *v->d.pp);
    int ok = v->d.pp != NULL;
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *s = k ? &m->sv : &m->su;
        v->d.leg[k] = rg2__calloc(1, (size_t)rg2_scalars_num_w(s) * sizeof(int));
        v->d.jun[k] = rg2__calloc(1, (size_t)s->n * sizeof(int));
        ok = ok && v->d.leg[k] && v->d.jun[k];
    }
    if (!ok) {
        view_free(v);
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory for %d x %d control points", what, m->nu, m->nv);
    }
    for (size_t q = 0; q < np; q++)
        v->d.pp[q] = (rg2__pprov){-1, 0, 0};
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *s = k ? &m->sv : &m->su;
        for (int i = 0; i < rg2_scalars_num_w(s); i++)
            v->d.leg[k][i] = -1;
        for (int i = 0; i < s->n; i++)
            v->d.jun[k][i] = -1;
    }
    return RG2_OK;
}

/* Hands the operation's result over to *out (st == RG2_OK) or leaves *out empty. */
static rg2_status finish(rg2_status st, rg2__dmesh *res, rg2_mesh *out)
{
    if (st == RG2_OK) {
        *out = res->m;
        memset(&res->m, 0, sizeof res->m);
        rg2__dmesh_free(res);
    }
    return st;
}

/* The common entry checks: out given and not one of the inputs. */
static rg2_status begin(const char *fn, rg2_mesh *out, const rg2_mesh *const *in, int n, rg2_error *err)
{
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "%s: out is NULL", fn);
    for (int t = 0; t < n; t++)
        if (in[t] == out)
            return rg2__fail(err, RG2_EINVAL, "%s: out is also an input; give a mesh of its own", fn);
    memset(out, 0, sizeof *out);
    return RG2_OK;
}

rg2_status rg2_mesh_cut(const rg2_mesh *in, const int first[2], const int last[2], rg2_mesh *out,
                        rg2_error *err)
{
    rg2_status st = begin("rg2_mesh_cut", out, &in, 1, err);
    if (st)
        return st;
    if (!first || !last)
        return rg2__fail(err, RG2_EINVAL, "rg2_mesh_cut: %s is NULL", first ? "last" : "first");
    for (int k = 0; k < 2; k++)
        if (first[k] < -1)
            return rg2__fail(err, RG2_EINVAL,
                             "rg2_mesh_cut: first[%d] = %d is negative (-1 keeps the %s direction whole)", k,
                             first[k], k ? "v" : "u");
    view v;
    if ((st = view_init(&v, in, "rg2_mesh_cut: in", "in", err)))
        return st;
    const char *what[2] = {"rg2_mesh_cut: u (first[0], last[0])", "rg2_mesh_cut: v (first[1], last[1])"};
    rg2__dmesh res;
    st = finish(rg2__op_cut(&v.d, first, last, &res, what, err), &res, out);
    view_free(&v);
    return st;
}

rg2_status rg2_mesh_transpose(const rg2_mesh *in, rg2_mesh *out, rg2_error *err)
{
    rg2_status st = begin("rg2_mesh_transpose", out, &in, 1, err);
    if (st)
        return st;
    view v;
    if ((st = view_init(&v, in, "rg2_mesh_transpose: in", "in", err)))
        return st;
    rg2__dmesh res;
    st = finish(rg2__op_transpose(&v.d, &res, "rg2_mesh_transpose", err), &res, out);
    view_free(&v);
    return st;
}

/* rg2_mesh_reverse (roll 0) and rg2_mesh_roll (roll 1) of direction dir. */
static rg2_status one_dir_op(const char *who, int roll, const rg2_mesh *in, int dir, int by, rg2_mesh *out,
                             rg2_error *err)
{
    rg2_status st = begin(who, out, &in, 1, err);
    if (st)
        return st;
    if (dir != 0 && dir != 1)
        return rg2__fail(err, RG2_EINVAL, "%s: dir = %d, must be 0 (u) or 1 (v)", who, dir);
    view v;
    char what[64];
    snprintf(what, sizeof what, "%s: in", who);
    if ((st = view_init(&v, in, what, "in", err)))
        return st;
    rg2__dmesh res;
    st = finish(roll ? rg2__op_roll(&v.d, dir, by, &res, who, err) : rg2__op_reverse(&v.d, dir, &res, who, err),
                &res, out);
    view_free(&v);
    return st;
}

rg2_status rg2_mesh_reverse(const rg2_mesh *in, int dir, rg2_mesh *out, rg2_error *err)
{
    return one_dir_op("rg2_mesh_reverse", 0, in, dir, 0, out, err);
}

rg2_status rg2_mesh_roll(const rg2_mesh *in, int dir, int by, rg2_mesh *out, rg2_error *err)
{
    return one_dir_op("rg2_mesh_roll", 1, in, dir, by, out, err);
}

rg2_status rg2_mesh_merge_overlap(const rg2_mesh *const *in, int n, int dir, int closed, double *back,
                                  rg2_error *err)
{
    if (!in || !back || n < 1)
        return rg2__fail(err, RG2_EINVAL, "rg2_mesh_merge_overlap: %s",
                         !in ? "in is NULL" : !back ? "back is NULL" : "no meshes (n < 1)");
    if (dir != 0 && dir != 1)
        return rg2__fail(err, RG2_EINVAL, "rg2_mesh_merge_overlap: dir = %d, must be 0 (u) or 1 (v)", dir);
    for (int t = 0; t < n; t++) {
        if (!in[t])
            return rg2__fail(err, RG2_EINVAL, "rg2_mesh_merge_overlap: in[%d] is NULL", t);
        char what[64];
        snprintf(what, sizeof what, "rg2_mesh_merge_overlap: in[%d]", t);
        rg2_status st = rg2_mesh_check(in[t], err);
        if (st)
            return rg2__prefix(err, st, what);
        int a = dir ? in[0]->nu : in[0]->nv, b = dir ? in[t]->nu : in[t]->nv;
        if (a != b)
            return rg2__fail(err, RG2_EINCOMPATIBLE,
                             "rg2_mesh_merge_overlap: in[0] and in[%d] do not agree in %s: %d vs %d control points", t,
                             dir ? "u" : "v", a, b);
    }
    for (int t = 0; t < n; t++)
        back[t] = t || closed ? rg2__merge_seam_back(in[t ? t - 1 : n - 1], in[t], dir, NULL) : 0.0;
    rg2__ok(err);
    return RG2_OK;
}

rg2_status rg2_mesh_merge(const rg2_mesh *const *in, int n, int dir, int closed, rg2_seam_rule rule,
                          rg2_mesh *out, rg2_error *err)
{
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "rg2_mesh_merge: out is NULL");
    if (!in || n < 1) { /* (no input to alias out) */
        memset(out, 0, sizeof *out);
        return rg2__fail(err, RG2_EINVAL, "rg2_mesh_merge: %s", !in ? "in is NULL" : "no meshes (n < 1)");
    }
    rg2_status st = begin("rg2_mesh_merge", out, in, n, err);
    if (st)
        return st;
    if (n > RG2_MAX_POINTS)
        return rg2__fail(err, RG2_ELIMIT, "rg2_mesh_merge: n = %d meshes, more than the limit of %d points", n,
                         RG2_MAX_POINTS);
    if (dir != 0 && dir != 1)
        return rg2__fail(err, RG2_EINVAL, "rg2_mesh_merge: dir = %d, must be 0 (u) or 1 (v)", dir);
    if (rule != RG2_SEAM_PRESERVE && rule != RG2_SEAM_PLAIN)
        return rg2__fail(err, RG2_EINVAL,
                         "rg2_mesh_merge: rule = %d, must be RG2_SEAM_PRESERVE (0) or RG2_SEAM_PLAIN (1)", (int)rule);
    view *v = rg2__calloc((size_t)n, sizeof *v);
    const rg2__dmesh **d = rg2__calloc((size_t)n, sizeof *d);
    /* the names the messages give: "in[t]" (the operation says "rg2_mesh_merge.merge[t]: mesh 'in[t]'") */
    char (*names)[48] = rg2__calloc((size_t)n, sizeof *names);
    int made = 0;
    if (!v || !d || !names) {
        st = rg2__fail(err, RG2_ENOMEM, "rg2_mesh_merge: out of memory for %d meshes", n);
        goto done;
    }
    for (; made < n; made++) {
        snprintf(names[made], sizeof names[made], "in[%d]", made);
        char what[80];
        snprintf(what, sizeof what, "rg2_mesh_merge: in[%d]", made);
        if ((st = view_init(&v[made], in[made], what, names[made], err)))
            goto done;
        d[made] = &v[made].d;
    }
    rg2__dmesh res;
    st = finish(rg2__op_merge(d, n, dir, closed ? 1 : 0,
                              rule == RG2_SEAM_PLAIN ? RG2__SEAM_PLAIN : RG2__SEAM_PRESERVE, &res,
                              "rg2_mesh_merge", err),
                &res, out);
done:
    for (int t = 0; v && t < made; t++)
        view_free(&v[t]);
    free(v);
    free(d);
    free(names);
    return st;
}

rg2_status rg2_mesh_morph(const rg2_mesh *a, const rg2_mesh *b, double t, rg2_mesh *out, rg2_error *err)
{
    const rg2_mesh *in[2] = {a, b};
    rg2_status st = begin("rg2_mesh_morph", out, in, 2, err);
    if (st)
        return st;
    view va, vb;
    if ((st = view_init(&va, a, "rg2_mesh_morph: a", "a", err)))
        return st;
    if ((st = view_init(&vb, b, "rg2_mesh_morph: b", "b", err))) {
        view_free(&va);
        return st;
    }
    rg2__dmesh res;
    st = finish(rg2__op_morph(&va.d, &vb.d, t, &res, "rg2_mesh_morph", err), &res, out);
    view_free(&va);
    view_free(&vb);
    return st;
}

/* The net normal of rg2_mesh_net_normal, its messages prefixed with what. */
rg2_status rg2__net_normal(const rg2_mesh *m, int i, int j, double n[3], const char *what, rg2_error *err)
{
    if (i < 0 || i >= m->nu || j < 0 || j >= m->nv)
        return rg2__fail(err, RG2_EINVAL,
                         "%s: control point [%d, %d] is outside the %d x %d points "
                         "(indices count from 0: [0..%d, 0..%d])", what, i, j, m->nu, m->nv, m->nu - 1, m->nv - 1);
    double t[2][3];
    for (int dir = 0; dir < 2; dir++) {
        int c = dir ? j : i, N = dir ? m->nv : m->nu, closed = dir ? m->sv.closed : m->su.closed;
        int lo = c - 1, hi = c + 1;
        if (closed) {
            lo = (lo + N) % N;
            hi = hi % N;
        } else {
            lo = lo < 0 ? c : lo;
            hi = hi >= N ? c : hi;
        }
        const double *a = dir ? rg2_mesh_at(m, i, lo) : rg2_mesh_at(m, lo, j);
        const double *b = dir ? rg2_mesh_at(m, i, hi) : rg2_mesh_at(m, hi, j);
        if (!(a[3] > 0.0) || !(b[3] > 0.0)) {
            int bad = !(a[3] > 0.0) ? lo : hi;
            return rg2__fail(err, RG2_EWEIGHT,
                             "%s: control point [%d, %d] has weight W = %g; design "
                             "points need W > 0", what, dir ? i : bad, dir ? bad : j, !(a[3] > 0.0) ? a[3] : b[3]);
        }
        for (int k = 0; k < 3; k++)
            t[dir][k] = b[k] / b[3] - a[k] / a[3];
    }
    double c[3] = {t[0][1] * t[1][2] - t[0][2] * t[1][1], t[0][2] * t[1][0] - t[0][0] * t[1][2],
                   t[0][0] * t[1][1] - t[0][1] * t[1][0]};
    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double lu = sqrt(t[0][0] * t[0][0] + t[0][1] * t[0][1] + t[0][2] * t[0][2]);
    double lv = sqrt(t[1][0] * t[1][0] + t[1][1] * t[1][1] + t[1][2] * t[1][2]);
    if (!(len > 1e-12 * lu * lv) || !rg2__finite(len))
        return rg2__fail(err, RG2_EDOMAIN,
                         "%s: the control net has no normal at [%d, %d]: its differences along u "
                         "(length %g) and v (length %g) are zero or parallel (a polar point's "
                         "collapsed row, or coinciding points)", what, i, j, lu, lv);
    for (int k = 0; k < 3; k++)
        n[k] = c[k] / len;
    return RG2_OK;
}

rg2_status rg2_mesh_net_normal(const rg2_mesh *m, int i, int j, double n[3], rg2_error *err)
{
    if (!m || !n || !m->p)
        return rg2__fail(err, RG2_EINVAL, "rg2_mesh_net_normal: %s is NULL", !m || !m->p ? "the mesh" : "n");
    return rg2__net_normal(m, i, j, n, "rg2_mesh_net_normal", err);
}
