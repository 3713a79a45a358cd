/* design_ops.c -- operations on design meshes (paper section 4, MATH.md section 6): shape
 * meshes, cut, transpose, merge, transform, morph, edits; every operation carries the
 * provenance of control points and scalars along. */
#include "design_internal.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *dir_name(int dir) { return dir ? "v" : "u"; }

rg2_status rg2__dmesh_alloc(rg2__dmesh *d, const char *name, int nu, int nv, int cu, int cv,
                            rg2_error *err)
{
    memset(d, 0, sizeof *d);
    rg2_status st = rg2_mesh_init(&d->m, nu, nv, cu, cv, err);
    if (st)
        return st;
    d->pp = rg2__calloc((size_t)nu * (size_t)nv, sizeof *d->pp);
    int ok = d->pp != NULL;
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *s = k ? &d->m.sv : &d->m.su;
        d->leg[k] = rg2__calloc((size_t)rg2_scalars_num_w(s), sizeof(int));
        d->jun[k] = rg2__calloc((size_t)s->n, sizeof(int));
        ok = ok && d->leg[k] && d->jun[k];
    }
    if (name) {
        d->name = rg2__calloc(strlen(name) + 1, 1);
        ok = ok && d->name;
        if (d->name)
            strcpy(d->name, name);
    }
    if (!ok) {
        rg2__dmesh_free(d);
        return rg2__fail(err, RG2_ENOMEM, "out of memory for %d x %d control points", nu, nv);
    }
    return RG2_OK;
}

void rg2__dmesh_free(rg2__dmesh *d)
{
    if (!d)
        return;
    rg2_mesh_free(&d->m);
    free(d->name);
    free(d->pp);
    for (int k = 0; k < 2; k++) {
        free(d->leg[k]);
        free(d->jun[k]);
    }
    memset(d, 0, sizeof *d);
}

static const rg2_scalars *dir_scalars(const rg2_mesh *m, int dir) { return dir ? &m->sv : &m->su; }
static rg2_scalars *dir_scalars_mut(rg2_mesh *m, int dir) { return dir ? &m->sv : &m->su; }

/* A NURBS pole side of an operation's output: side `to` is the point p (rg2__dmesh.poles) */
static void pole_keep(rg2__dmesh *out, int to, const double p[3])
{
    out->poles |= 1u << to;
    memcpy(out->pole[to], p, sizeof out->pole[to]);
}

/* Whether the n doubles at x and y are the same bits. */
static int same_bits(const double *x, const double *y, size_t n) { return !memcmp(x, y, n * sizeof *x); }

/* Whether the scalars a and b of a direction are the same: count, closedness, and every w, b and g
 * the same bits. */
static int scalars_same(const rg2_scalars *a, const rg2_scalars *b)
{
    size_t n = (size_t)a->n;
    return a->n == b->n && a->closed == b->closed && same_bits(a->w, b->w, (size_t)rg2_scalars_num_w(a)) &&
           same_bits(a->b, b->b, n) && same_bits(a->g, b->g, n);
}

/*
 * Whether a pole side at end `hi` (0: index 0, 1: the last) of direction dir of mesh b (whose
 * patches' side there is one point) is that point in mesh a too (whose length along dir may
 * differ). The construction (surface.c: rows_at, columns_at, normalize_weights per patch; curve.c's
 * stencil) makes the first segment of an open direction from points 0..3, legs -1..3 and junctions
 * 0..3 (b, g; K_j reads w_{j-1}, w_j) and the last from the same counted from the far end, and the
 * patches along that end from all the points of those 4 lines and all the scalars of the other
 * direction, the one along the pole line (their side itself from lines 0..2, legs -1..2 and
 * junctions 0..2; line, leg and junction 3 reach it through the patch's power-of-two weight
 * normalization, a factor the same on all of the patch's 4-tuples). Equal values there, bit for
 * bit, give the same end points E_a of the curves along dir, one per index a along the pole line
 * (curve.c: b0 of the end segment): (w_a p, w_a) but for the rounding of b's mesh (a NURBS's
 * extrapolated end lines, nurbs.c), w_a of either sign where the other direction's end lines are
 * extrapolated. The side of a patch is sum_a c_a E_a, c_a a stencil row of the scalars along the
 * pole line (in [0, 1] for every w, b > 0 and K > 0 that rg2_scalars_check accepts), times the
 * power of two: (W p, W), the point p in exact arithmetic wherever W != 0, whatever those scalars
 * are (other scalars than b's can make W <= 0 next to extrapolated end lines: a patch weight <= 0,
 * which the output notes). So those scalars need only the same count and closedness (the same
 * lines to compare); where they are b's too, the patches are b's bit for bit.
 */
static int end_same(const rg2_mesh *a, const rg2_mesh *b, int dir, int hi)
{
    const rg2_scalars *sa = dir_scalars(a, dir), *sb = dir_scalars(b, dir);
    const rg2_scalars *oa = dir_scalars(a, 1 - dir), *ob = dir_scalars(b, 1 - dir);
    if (sa->closed || sb->closed || sa->n < 4 || sb->n < 4 || oa->n != ob->n || oa->closed != ob->closed)
        return 0;
    int fa = hi ? sa->n - 4 : 0, fb = hi ? sb->n - 4 : 0; /* the end's first line (stored leg fa: leg fa - 1) */
    if (!same_bits(sa->w + fa, sb->w + fb, 5) || !same_bits(sa->b + fa, sb->b + fb, 4) ||
        !same_bits(sa->g + fa, sb->g + fb, 4))
        return 0;
    for (int k = 0; k < 4; k++)
        for (int j = 0; j < oa->n; j++)
            if (!same_bits(dir ? rg2_mesh_at(a, j, fa + k) : rg2_mesh_at(a, fa + k, j),
                           dir ? rg2_mesh_at(b, j, fb + k) : rg2_mesh_at(b, fb + k, j), 4))
                return 0;
    return 1;
}

void rg2__poles_keep_same(rg2__dmesh *out, const rg2__dmesh *from)
{
    for (int side = 0; side < 4; side++)
        if (from->poles >> side & 1u && end_same(&out->m, &from->m, side == 0 || side == 2, side == 1 || side == 2))
            pole_keep(out, side, from->pole[side]);
}

rg2_status rg2__dmesh_copy(const rg2__dmesh *in, rg2__dmesh *out, rg2_error *err)
{
    rg2_status st = rg2__dmesh_alloc(out, NULL, in->m.nu, in->m.nv, in->m.su.closed,
                                     in->m.sv.closed, err);
    if (st)
        return st;
    size_t np = (size_t)in->m.nu * (size_t)in->m.nv;
    memcpy(out->m.p, in->m.p, np * 4 * sizeof(double));
    memcpy(out->pp, in->pp, np * sizeof *in->pp);
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *a = dir_scalars(&in->m, k);
        rg2_scalars *b = dir_scalars_mut(&out->m, k);
        int nw = rg2_scalars_num_w(a);
        memcpy(b->w, a->w, (size_t)nw * sizeof(double));
        memcpy(b->b, a->b, (size_t)a->n * sizeof(double));
        memcpy(b->g, a->g, (size_t)a->n * sizeof(double));
        memcpy(out->leg[k], in->leg[k], (size_t)nw * sizeof(int));
        memcpy(out->jun[k], in->jun[k], (size_t)a->n * sizeof(int));
    }
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */

/* Control points a partition gives its direction: a closed circle of N arcs N, an open direction
 * of N segments N + 3 (its data-only ends). */
static long long part_points(const rg2_partition *p)
{
    int segs = rg2_partition_num_segments(p);
    return p->closed && (p->kind == RG2_PART_ANGLES) ? segs : segs + 3;
}

/* The shape placement's weights (rg2_shape_mesh refuses a placement that turns a positive
 * control weight <= 0): name the shape's matrix, the mesh and the first such point, as the
 * transform operation does (1: named in err; 0: no such point, err untouched). Recomputes the
 * unplaced mesh (on the error path only). */
static int placement_weights(const rg2_design *d, int shape, const rg2_partition *pu, const rg2_partition *pv,
                             const char *what, rg2_error *err)
{
    rg2_shape u = d->shapes[shape];
    const double *M = d->shapes[shape].xform;
    rg2_xform_identity(u.xform);
    rg2_mesh m = {0};
    if (rg2_shape_mesh(&u, pu, pv, &m, NULL))
        return 0;
    for (int i = 0; i < m.nu; i++)
        for (int j = 0; j < m.nv; j++) {
            const double *p = rg2_mesh_at(&m, i, j);
            double W = M[12] * p[0] + M[13] * p[1] + M[14] * p[2] + M[15] * p[3], before = p[3];
            if (!(before > 0.0) || W > 0.0)
                continue;
            rg2_mesh_free(&m);
            rg2__fail(err, rg2__finite(W) ? RG2_EWEIGHT : RG2_ENONFINITE,
                      "shapes.%s.matrix: the placement gives control point [%d, %d] of %s the weight W = %.6g (%.6g "
                      "unplaced); weights must stay > 0 (the placement matrix's last row must be positive on the "
                      "whole mesh, or the surface passes through infinity)",
                      d->labels[shape], i, j, what, W, before);
            return 1;
        }
    rg2_mesh_free(&m);
    return 0;
}

rg2_status rg2__op_shape(rg2_design *d, int shape, const rg2_partition *pu, const rg2_partition *pv,
                         rg2__dmesh *out, const char *what, const char *vpath, rg2_error *err)
{
    rg2_mesh base = {0};
    const rg2_shape *sh = &d->shapes[shape];
    rg2_status st = rg2__shape_check_range(sh, pv, err);
    if (st) {
        rg2_error e = *err;
        return rg2__fail(err, st, "%s: %s", vpath, e.msg);
    }
    long long nu = part_points(pu), nv = part_points(pv);
    if (nu * nv > RG2_MAX_POINTS)
        return rg2__fail(err, RG2_ELIMIT, "%s: the partitions give %lld x %lld control points, more than the limit "
                         "of %d per mesh", what, nu, nv, RG2_MAX_POINTS);
    st = rg2_shape_mesh(sh, pu, pv, &base, err);
    if (st) {
        if ((st == RG2_EWEIGHT || st == RG2_ENONFINITE) && placement_weights(d, shape, pu, pv, what, err))
            return err->code;
        rg2_error e = *err;
        return rg2__fail(err, st, "%s: %s", what, e.msg);
    }
    /* the design mesh is a copy of base with provenance; the source then owns base */
    const rg2_mesh *b = &base;
    st = rg2__dmesh_alloc(out, NULL, b->nu, b->nv, b->su.closed, b->sv.closed, err);
    if (!st) {
        rg2_mesh_free(&out->m);
        st = rg2_mesh_copy(b, &out->m, err);
    }
    if (st) {
        rg2_mesh_free(&base);
        return st;
    }
    int src = rg2__design_add_source(d, shape, &base, err);
    if (src < 0) {
        rg2_mesh_free(&base);
        return err->code;
    }
    b = &out->m;
    for (int i = 0; i < b->nu; i++)
        for (int j = 0; j < b->nv; j++)
            *rg2__dmesh_pp(out, i, j) = (rg2__pprov){src, i, j};
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *s = dir_scalars(b, k);
        for (int i = 0; i < rg2_scalars_num_w(s); i++)
            out->leg[k][i] = shape;
        for (int i = 0; i < s->n; i++)
            out->jun[k][i] = shape;
    }
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* cut */

rg2_status rg2__op_cut(const rg2__dmesh *in, const int first[2], const int last[2],
                       rg2__dmesh *out, const char *const what[2], rg2_error *err)
{
    int n[2], cl[2], f[2];
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *s = dir_scalars(&in->m, k);
        if (first[k] < 0) {
            n[k] = s->n;
            cl[k] = s->closed;
            f[k] = 0;
            continue;
        }
        /* (a C caller's indices may be anywhere in int: no sum of them may overflow) */
        int maxlast = s->closed ? (first[k] < s->n ? first[k] : s->n - 1) + s->n + 2 : s->n - 1;
        if (first[k] >= s->n || last[k] < first[k] || last[k] > maxlast)
            return rg2__fail(err, RG2_EINVAL,
                             "%s: range [%d, %d] is outside the %d control points of mesh '%s' in %s "
                             "(%s; need 0 <= first < %d, first <= last <= %d)",
                             what[k], first[k], last[k], s->n, in->name, dir_name(k),
                             s->closed ? "closed, last may wrap" : "open", s->n, maxlast);
        int cnt = last[k] - first[k] + 1;
        if (cnt < 4)
            return rg2__fail(err, RG2_EINVAL,
                             "%s: range [%d, %d] keeps %d control point%s; an open direction needs at least 4",
                             what[k], first[k], last[k], cnt, cnt == 1 ? "" : "s");
        n[k] = cnt;
        cl[k] = 0;
        f[k] = first[k];
    }
    rg2_status st = rg2__dmesh_alloc(out, NULL, n[0], n[1], cl[0], cl[1], err);
    if (st == RG2_ELIMIT) /* (a wrapping cut keeps up to n + 3 points of a closed direction: the one that grew) */
        return rg2__prefix(err, st, what[n[1] > in->m.sv.n ? 1 : 0]);
    if (st)
        return st;
    for (int i = 0; i < n[0]; i++)
        for (int j = 0; j < n[1]; j++) {
            int si = rg2__wrap(f[0] + i, in->m.nu, in->m.su.closed);
            int sj = rg2__wrap(f[1] + j, in->m.nv, in->m.sv.closed);
            memcpy(rg2_mesh_at(&out->m, i, j), rg2_mesh_at(&in->m, si, sj), 4 * sizeof(double));
            *rg2__dmesh_pp(out, i, j) = *rg2__dmesh_pp(in, si, sj);
        }
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *a = dir_scalars(&in->m, k);
        rg2_scalars *b = dir_scalars_mut(&out->m, k);
        int off_a = a->closed ? 0 : 1, off_b = b->closed ? 0 : 1;
        /* junctions */
        for (int i = 0; i < b->n; i++) {
            int si = rg2__wrap(f[k] + i, a->n, a->closed);
            b->b[i] = a->b[si];
            b->g[i] = a->g[si];
            out->jun[k][i] = in->jun[k][si];
        }
        /* legs: out leg l (stored l + off_b) is in leg f + l */
        int lo = b->closed ? 0 : -1, hi = b->n - 1;
        for (int l = lo; l <= hi; l++) {
            int sl = f[k] + l;
            if (a->closed)
                sl = rg2__wrap(sl, a->n, 1);
            b->w[l + off_b] = a->w[sl + off_a];
            out->leg[k][l + off_b] = in->leg[k][sl + off_a];
        }
    }
    /* a NURBS pole side stays where its end is kept (the pole sides of an open direction) */
    for (int side = 0; side < 4; side++) {
        int k = side == 0 || side == 2, hi = side == 1 || side == 2;
        if (in->poles >> side & 1u && (first[k] < 0 || (hi ? last[k] == dir_scalars(&in->m, k)->n - 1 : f[k] == 0)))
            pole_keep(out, side, in->pole[side]);
    }
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* transpose */

rg2_status rg2__op_transpose(const rg2__dmesh *in, rg2__dmesh *out, const char *what,
                             rg2_error *err)
{
    (void)what;
    rg2_status st = rg2__dmesh_alloc(out, NULL, in->m.nv, in->m.nu, in->m.sv.closed,
                                     in->m.su.closed, err);
    if (st)
        return st;
    for (int i = 0; i < in->m.nu; i++)
        for (int j = 0; j < in->m.nv; j++) {
            memcpy(rg2_mesh_at(&out->m, j, i), rg2_mesh_at(&in->m, i, j), 4 * sizeof(double));
            *rg2__dmesh_pp(out, j, i) = *rg2__dmesh_pp(in, i, j);
        }
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *a = dir_scalars(&in->m, 1 - k);
        rg2_scalars *b = dir_scalars_mut(&out->m, k);
        int nw = rg2_scalars_num_w(a);
        memcpy(b->w, a->w, (size_t)nw * sizeof(double));
        memcpy(b->b, a->b, (size_t)a->n * sizeof(double));
        memcpy(b->g, a->g, (size_t)a->n * sizeof(double));
        memcpy(out->leg[k], in->leg[1 - k], (size_t)nw * sizeof(int));
        memcpy(out->jun[k], in->jun[1 - k], (size_t)a->n * sizeof(int));
    }
    for (int side = 0; side < 4; side++) /* NURBS pole sides: v = 0 <-> u = 0, u = 1 <-> v = 1 */
        if (in->poles >> side & 1u)
            pole_keep(out, 3 - side, in->pole[side]);
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* reverse */

/*
 * METHOD: with L(t) = f_i(1 - t), R(t) = f_{i-1}(1 - t), Definition 1 at the junction gives
 * R'(0) = (1 / b) L'(1) and R''(0) = (1 / b^2) L''(1) + (g / b^3) L'(1): the reversed junction
 * has b' = 1 / b, g' = g / b^3 (so K' = K / b^3 > 0), and leg l of the reversed direction is
 * leg n - 2 - l. The construction is symmetric under this relabelling, so every patch is the
 * same patch traversed backwards (the provenance tags check it on the stencils).
 */
rg2_status rg2__op_reverse(const rg2__dmesh *in, int dir, rg2__dmesh *out, const char *what,
                           rg2_error *err)
{
    rg2_status st = rg2__dmesh_copy(in, out, err);
    if (st)
        return st;
    const rg2_scalars *a = dir_scalars(&in->m, dir);
    rg2_scalars *b = dir_scalars_mut(&out->m, dir);
    int n = a->n;
    for (int i = 0; i < in->m.nu; i++)
        for (int j = 0; j < in->m.nv; j++) {
            int si = dir == 0 ? n - 1 - i : i, sj = dir == 0 ? j : n - 1 - j;
            memcpy(rg2_mesh_at(&out->m, i, j), rg2_mesh_at(&in->m, si, sj), 4 * sizeof(double));
            *rg2__dmesh_pp(out, i, j) = *rg2__dmesh_pp(in, si, sj);
        }
    for (int j = 0; j < n; j++) {
        double bb = a->b[n - 1 - j];
        double g = a->g[n - 1 - j], b3 = bb * bb * bb;
        b->b[j] = 1.0 / bb;
        /* (b^3 subnormal, 0 or inf, b = 1e-110 or 1e110: divide step by step) */
        b->g[j] = b3 >= DBL_MIN && rg2__finite(b3) ? g / b3 : ((g / bb) / bb) / bb;
        out->jun[dir][j] = in->jun[dir][n - 1 - j];
        if (!rg2__finite(b->b[j]) || !rg2__finite(b->g[j])) { /* (a b of 1e-310: 1 / b = inf) */
            rg2__dmesh_free(out);
            double bj = 1.0 / bb;
            return rg2__fail(err, RG2_EDOMAIN, "%s: %s junction %d (b = %s, g = %s) cannot be reversed: %s",
                             what, dir_name(dir), n - 1 - j, rg2__num(bb).s, rg2__num(g).s,
                             !rg2__finite(bj) ? "b' = 1 / b is not a finite number"
                                              : "g' = g / b^3 is not a finite number");
        }
    }
    for (int s = 0; s < rg2_scalars_num_w(a); s++) {
        int from = a->closed ? rg2__wrap(n - 2 - s, n, 1) : n - s;
        b->w[s] = a->w[from];
        out->leg[dir][s] = in->leg[dir][from];
    }
    for (int j = 0; j < n; j++) /* K' = K / b^3: b = 1e-160 gives a finite b' = 1e160 but K' = inf */
        if (!rg2__finite(rg2_scalars_K(b, j))) {
            double bb = a->b[n - 1 - j], g = a->g[n - 1 - j];
            rg2__dmesh_free(out);
            return rg2__fail(err, RG2_EDOMAIN,
                             "%s: %s junction %d (b = %s, g = %s) cannot be reversed: K' = K / b^3 is not a "
                             "finite number",
                             what, dir_name(dir), n - 1 - j, rg2__num(bb).s, rg2__num(g).s);
        }
    st = rg2__dir_check(b, dir, what, "", err);
    if (st) {
        rg2__dmesh_free(out);
        return st;
    }
    for (int side = 0; side < 4; side++) /* NURBS pole sides: the reversed direction's ends swap */
        if (in->poles >> side & 1u) {
            int to = (side == 0 || side == 2) == (dir == 1) ? side ^ 2 : side;
            pole_keep(out, to, in->pole[side]);
        }
    return RG2_OK;
}

rg2_status rg2__op_roll(const rg2__dmesh *in, int dir, int by, rg2__dmesh *out, const char *what,
                        rg2_error *err)
{
    const rg2_scalars *a = dir_scalars(&in->m, dir);
    if (!a->closed)
        return rg2__fail(err, RG2_EINCOMPATIBLE,
                         "%s: mesh '%s' is open in %s; roll turns a closed direction (a circle) by whole "
                         "steps", what, in->name, dir_name(dir));
    rg2_status st = rg2__dmesh_copy(in, out, err);
    if (st)
        return st;
    rg2_scalars *b = dir_scalars_mut(&out->m, dir);
    int n = a->n, k = (int)(((long)by % n + n) % n); /* new index j takes the old j + k */
    for (int i = 0; i < in->m.nu; i++)
        for (int j = 0; j < in->m.nv; j++) {
            int si = dir == 0 ? (i + k) % n : i, sj = dir == 0 ? j : (j + k) % n;
            memcpy(rg2_mesh_at(&out->m, i, j), rg2_mesh_at(&in->m, si, sj), 4 * sizeof(double));
            *rg2__dmesh_pp(out, i, j) = *rg2__dmesh_pp(in, si, sj);
        }
    for (int j = 0; j < n; j++) { /* junction j and leg j (from junction j to j + 1) move alike */
        b->b[j] = a->b[(j + k) % n];
        b->g[j] = a->g[(j + k) % n];
        out->jun[dir][j] = in->jun[dir][(j + k) % n];
        b->w[j] = a->w[(j + k) % n];
        out->leg[dir][j] = in->leg[dir][(j + k) % n];
    }
    /* NURBS pole sides (along dir, the ends of the other direction: a ring merged from parts with
     * the pole): the same patches, relabelled, so the same side */
    for (int side = 0; side < 4; side++)
        if (in->poles >> side & 1u)
            pole_keep(out, side, in->pole[side]);
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* merge */

static int close_rel(double a, double b, double tol)
{
    return fabs(a - b) <= tol * fmax(1.0, fmax(fabs(a), fabs(b)));
}

/* First difference between two direction scalars, written to msg; 0 if they agree. */
static int scalars_differ(const rg2_scalars *a, const rg2_scalars *b, char *msg, size_t cap)
{
    if (a->n != b->n) {
        if (a->closed != b->closed) /* both differ: a closed circle against an open ring, say so */
            snprintf(msg, cap, "%d control points, %s, vs %d, %s", a->n, a->closed ? "closed" : "open", b->n,
                     b->closed ? "closed" : "open");
        else
            snprintf(msg, cap, "%d vs %d control points (make both with the same partition there: the same arcs "
                               "or knots)",
                     a->n, b->n);
        return 1;
    }
    if (a->closed != b->closed) {
        snprintf(msg, cap, "%s vs %s", a->closed ? "closed" : "open", b->closed ? "closed" : "open");
        return 1;
    }
    int nw = rg2_scalars_num_w(a), off = a->closed ? 0 : 1;
    const double tol = 1e-12;
    int ones_a = 1, ones_b = 1; /* all leg weights 1: a polynomial (knot) direction */
    for (int i = 0; i < nw; i++) {
        ones_a = ones_a && a->w[i] == 1.0;
        ones_b = ones_b && b->w[i] == 1.0;
    }
    for (int i = 0; i < nw; i++)
        if (!close_rel(a->w[i], b->w[i], tol)) {
            /* circle legs: an arc of opening angle t has w = (1 + 2 cos(t / 2)) / 3; name the arcs, which
             * the designer wrote (it gave only the weights) */
            char arcs[96] = "";
            double ca = (3.0 * a->w[i] - 1.0) / 2.0, cb = (3.0 * b->w[i] - 1.0) / 2.0;
            if (!ones_a && !ones_b && ca > -1.0 && ca < 1.0 && cb > -1.0 && cb < 1.0) {
                void *loc = rg2__c_numeric_begin(); /* (rg2_mesh_merge too) */
                snprintf(arcs, sizeof arcs, " (as circle arcs: %.6g vs %.6g degrees)", 2.0 * acos(ca) * 180.0 / M_PI,
                         2.0 * acos(cb) * 180.0 / M_PI);
                rg2__c_numeric_end(loc);
            }
            snprintf(msg, cap, "leg weight w[%d] = %s vs %s%s%s", i - off, rg2__num(a->w[i]).s, rg2__num(b->w[i]).s,
                     arcs,
                     ones_a != ones_b ? " (one has all its leg weights 1, like a polynomial direction (knots or "
                                        "a NURBS), the other not, like a circle direction or an edited one: a "
                                        "circle merges only with a circle of the same arcs)"
                                      : "");
            return 1;
        }
    for (int i = 0; i < a->n; i++) {
        if (!close_rel(a->b[i], b->b[i], tol)) {
            snprintf(msg, cap, "junction scalar b[%d] = %s vs %s", i, rg2__num(a->b[i]).s, rg2__num(b->b[i]).s);
            return 1;
        }
        if (!close_rel(a->g[i], b->g[i], tol)) {
            snprintf(msg, cap, "junction scalar g[%d] = %s vs %s", i, rg2__num(a->g[i]).s, rg2__num(b->g[i]).s);
            return 1;
        }
    }
    return 0;
}

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

static void cross3(const double a[3], const double b[3], double out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The design point of line `line` (along dir) at index i of the other direction. */
static void line_point(const rg2_mesh *m, int dir, int line, int i, double x[3])
{
    const double *p = dir ? rg2_mesh_at(m, i, line) : rg2_mesh_at(m, line, i);
    for (int c = 0; c < 3; c++)
        x[c] = p[c] / p[3];
}

/* Twist between two closed rows of n points (line la of a, line lb of b, along dir): their
 * centroids, their Newell normals (the way round each runs), and the circular mean of the signed
 * angles from a's point i to b's point i about the mean normal, positive along a's way round.
 * 0 when a row has no way round (collapsed, or a line); else 1 with *opposite set when they run
 * opposite ways round (then *deg is not measured). */
static int row_twist(const rg2_mesh *a, int la, const rg2_mesh *b, int lb, int dir, int n, double *deg,
                     int *opposite)
{
    double c[2][3] = {{0}}, N[2][3] = {{0}}, x[3], y[3];
    const rg2_mesh *m[2] = {a, b};
    int line[2] = {la, lb};
    for (int r = 0; r < 2; r++) {
        for (int i = 0; i < n; i++) {
            line_point(m[r], dir, line[r], i, x);
            for (int k = 0; k < 3; k++)
                c[r][k] += x[k] / n;
        }
        for (int i = 0; i < n; i++) { /* Newell: sum of (p_i - c) x (p_{i+1} - c) */
            line_point(m[r], dir, line[r], i, x);
            line_point(m[r], dir, line[r], (i + 1) % n, y);
            double cr[3];
            for (int k = 0; k < 3; k++)
                x[k] -= c[r][k], y[k] -= c[r][k];
            cross3(x, y, cr);
            for (int k = 0; k < 3; k++)
                N[r][k] += cr[k];
        }
    }
    double la2 = sqrt(dot3(N[0], N[0])), lb2 = sqrt(dot3(N[1], N[1]));
    if (!(la2 > 0.0) || !(lb2 > 0.0) || !isfinite(la2) || !isfinite(lb2))
        return 0;
    *opposite = dot3(N[0], N[1]) < 0.0;
    double ax[3], sc = 0.0, ss = 0.0;
    for (int k = 0; k < 3; k++)
        ax[k] = N[0][k] / la2 + N[1][k] / lb2;
    double len = sqrt(dot3(ax, ax));
    if (*opposite || !(len > 0.0))
        return 1;
    for (int k = 0; k < 3; k++)
        ax[k] /= len;
    for (int i = 0; i < n; i++) {
        line_point(a, dir, la, i, x);
        line_point(b, dir, lb, i, y);
        for (int k = 0; k < 3; k++)
            x[k] -= c[0][k], y[k] -= c[1][k];
        double xa = dot3(x, ax), ya = dot3(y, ax); /* project onto the plane normal to ax */
        for (int k = 0; k < 3; k++)
            x[k] -= xa * ax[k], y[k] -= ya * ax[k];
        double cr[3];
        cross3(x, y, cr);
        double t = atan2(dot3(cr, ax), dot3(x, y));
        sc += cos(t), ss += sin(t);
    }
    *deg = atan2(ss, sc) * 180.0 / M_PI;
    return 1;
}

/* The first control point of weight <= 0 on the two lines of m next to a seam (lines l0 and l1
 * along dir; those of them that exist): 1 with its line, its index along the other direction and
 * its weight. Its design point p / w lies on the far side (or at infinity), so the twist and
 * overlap notes, which measure design points, mean nothing there. */
static int seam_weight(const rg2_mesh *m, int dir, int l0, int l1, int *line, int *idx, double *w)
{
    int n = dir_scalars(m, 1 - dir)->n, nl = dir_scalars(m, dir)->n;
    for (int q = 0; q < 2; q++) {
        int ln = q ? l1 : l0;
        for (int i = 0; ln >= 0 && ln < nl && i < n; i++) {
            const double *p = dir ? rg2_mesh_at(m, i, ln) : rg2_mesh_at(m, ln, i);
            if (!(p[3] > 0.0)) {
                *line = ln, *idx = i, *w = p[3];
                return 1;
            }
        }
    }
    return 0;
}

/* Whether the seam between l and r has a control weight <= 0 on a line next to it; which part
 * (0 l, 1 r) and where. */
static int seam_weights_bad(const rg2_mesh *l, const rg2_mesh *r, int dir, int *part, int *line, int *idx,
                            double *w)
{
    int nl = dir_scalars(l, dir)->n;
    if (seam_weight(l, dir, nl - 1, nl - 2, line, idx, w)) {
        *part = 0;
        return 1;
    }
    *part = 1;
    return seam_weight(r, dir, 0, 1, line, idx, w);
}

rg2_status rg2__merge_twist_notes(rg2_design *d, const rg2__dmesh *const *in, int n_in, int dir, int closed,
                                  const char *what, rg2_error *err)
{
    int other = 1 - dir, n = dir_scalars(&in[0]->m, other)->n;
    if (!dir_scalars(&in[0]->m, other)->closed || n < 3)
        return RG2_OK;
    for (int t = closed ? 0 : 1; t < n_in; t++) {
        const rg2__dmesh *l = in[t ? t - 1 : n_in - 1], *r = in[t];
        double deg = 0.0, w;
        int opposite = 0, part, line, idx;
        if (seam_weights_bad(&l->m, &r->m, dir, &part, &line, &idx, &w)) /* (rg2__merge_overlap_notes) */
            continue;
        if (!row_twist(&l->m, dir_scalars(&l->m, dir)->n - 1, &r->m, 0, dir, n, &deg, &opposite) ||
            (!opposite && fabs(deg) <= 1.0))
            continue;
        char msg[900];
        if (opposite)
            snprintf(msg, sizeof msg,
                     "%s: %s.merge[%d]: the closed %s rows of '%s' and '%s' run opposite ways round at their seam: "
                     "the transition patches turn the tube through itself (rg2 check --intersections looks for "
                     "the crossings); reverse one of them along %s",
                     d->name, what, t, dir_name(other), l->name, r->name, dir_name(other));
        else {
            /* a whole number of equal steps (a circle in n equal arcs: 360 / n degrees): roll undoes it */
            double steps = deg / (360.0 / n), whole = round(steps);
            char roll[200] = "";
            if (whole != 0.0 && fabs(steps - whole) < 1e-3)
                snprintf(roll, sizeof roll, ", or roll it back: {\"roll\": \"%s\", \"dir\": \"%s\", \"by\": %d}",
                         r->name, dir_name(other), -(int)whole);
            snprintf(msg, sizeof msg,
                     "%s: %s.merge[%d]: the closed %s rows of '%s' and '%s' meet turned by %.4g degrees about their "
                     "axis ('%s' starts %.4g degrees %s along %s): the transition patches twist the tube; start "
                     "both circles at the same angle (the partition's \"from\") or rotate one part about its "
                     "axis%s",
                     d->name, what, t, dir_name(other), l->name, r->name, fabs(deg), r->name, fabs(deg),
                     deg > 0.0 ? "further" : "back", dir_name(other), roll);
        }
        rg2_status st = rg2__design_add_note(d, msg, err);
        if (st)
            return st;
    }
    return RG2_OK;
}

/* The centre (mean design point) of line `line` (along dir) of n points. */
static void line_centre(const rg2_mesh *m, int dir, int line, int n, double c[3])
{
    double x[3];
    c[0] = c[1] = c[2] = 0.0;
    for (int i = 0; i < n; i++) {
        line_point(m, dir, line, i, x);
        for (int k = 0; k < 3; k++)
            c[k] += x[k] / n;
    }
}

/* How far the seam step s runs back against the step a, in units of a's length: -s.a / |a|^2
 * (0 where a has no length). */
static double back_steps(const double s[3], const double a[3])
{
    double aa = dot3(a, a);
    return aa > 0.0 && isfinite(aa) ? -dot3(s, a) / aa : 0.0;
}

double rg2__merge_seam_back(const rg2_mesh *l, const rg2_mesh *r, int dir, int *by_left)
{
    int n = dir_scalars(l, 1 - dir)->n, nl = dir_scalars(l, dir)->n, nr = dir_scalars(r, dir)->n;
    if (by_left)
        *by_left = 1;
    if (nl < 2 || nr < 2)
        return 0.0;
    double c[4][3];
    line_centre(l, dir, nl - 2, n, c[0]);
    line_centre(l, dir, nl - 1, n, c[1]);
    line_centre(r, dir, 0, n, c[2]);
    line_centre(r, dir, 1, n, c[3]);
    double a[3], st3[3], b[3];
    for (int k = 0; k < 3; k++)
        a[k] = c[1][k] - c[0][k], st3[k] = c[2][k] - c[1][k], b[k] = c[3][k] - c[2][k];
    double back_l = back_steps(st3, a), back_r = back_steps(st3, b);
    if (by_left)
        *by_left = back_l >= back_r;
    return back_l > back_r ? back_l : back_r;
}

/* Whether the open ends of a merge, the last line of l (along dir) and the first of r, run on into
 * each other as a seam does: the step between their centres points forward along both parts'
 * steps there (within 60 degrees of each) and is at most 3 of their line spacings long; *ratio is
 * its length in spacings (the larger of the two parts'). A ring merged without "closed": true. */
static int open_ends_meet(const rg2_mesh *l, const rg2_mesh *r, int dir, double *ratio)
{
    int n = dir_scalars(l, 1 - dir)->n, nl = dir_scalars(l, dir)->n, nr = dir_scalars(r, dir)->n;
    if (nl < 2 || nr < 2 || n != dir_scalars(r, 1 - dir)->n)
        return 0;
    double c[4][3], a[3], st3[3], b[3];
    line_centre(l, dir, nl - 2, n, c[0]);
    line_centre(l, dir, nl - 1, n, c[1]);
    line_centre(r, dir, 0, n, c[2]);
    line_centre(r, dir, 1, n, c[3]);
    for (int k = 0; k < 3; k++)
        a[k] = c[1][k] - c[0][k], st3[k] = c[2][k] - c[1][k], b[k] = c[3][k] - c[2][k];
    double la = sqrt(dot3(a, a)), lb = sqrt(dot3(b, b)), ls = sqrt(dot3(st3, st3));
    double sp = la > lb ? la : lb;
    if (!(la > 0.0 && lb > 0.0 && ls > 0.0) || !isfinite(la + lb + ls))
        return 0;
    *ratio = ls / sp;
    return *ratio <= 3.0 && dot3(st3, a) >= 0.5 * ls * la && dot3(st3, b) >= 0.5 * ls * lb;
}

rg2_status rg2__merge_overlap_notes(rg2_design *d, const rg2__dmesh *const *in, int n_in, int dir, int closed,
                                    const char *what, int *weight_noted, rg2_error *err)
{
    *weight_noted = 0;
    int other = 1 - dir;
    double ratio;
    int part, line, idx;
    double w;
    if (!closed && n_in >= 2 && !seam_weights_bad(&in[n_in - 1]->m, &in[0]->m, dir, &part, &line, &idx, &w) &&
        open_ends_meet(&in[n_in - 1]->m, &in[0]->m, dir, &ratio)) {
        char msg[900], where[64];
        if (ratio < 1e-6) /* the same line to rounding: the open ends still stop short of it */
            snprintf(where, sizeof where, "lies on");
        else
            snprintf(where, sizeof where, "lies %.2g line spacings on from", ratio);
        snprintf(msg, sizeof msg,
                 "%s: %s: the merge is open along %s, but its ends run on into each other as a seam does: the "
                 "first %s line of '%s' %s the last of '%s', so the surface is a ring with a gap there; if a "
                 "closed ring is meant, add \"closed\": true (the gap then becomes 3 transition patches, as at "
                 "the other seams)",
                 d->name, what, dir_name(dir), dir_name(other), in[0]->name, where, in[n_in - 1]->name);
        rg2_status st = rg2__design_add_note(d, msg, err);
        if (st)
            return st;
    }
    for (int t = closed ? 0 : 1; t < n_in; t++) {
        const rg2__dmesh *l = in[t ? t - 1 : n_in - 1], *r = in[t];
        int by_left;
        char msg[900];
        if (seam_weights_bad(&l->m, &r->m, dir, &part, &line, &idx, &w)) {
            /* (a hyperboloid's data-only end rows past v = 0 or |v| = 1, say) */
            const rg2__dmesh *p = part ? r : l;
            snprintf(msg, sizeof msg,
                     "%s: %s.merge[%d]: '%s' has weight %.4g <= 0 at control point %d of its %s line %d, next to "
                     "its seam with '%s': the transition patches there can change sign and pass through infinity "
                     "(rg2 check reports their weights; STEP and IGES refuse weights <= 0); if it is a data-only "
                     "end row (a hyperboloid's knots mirrored past v = 0 or |v| = 1), keep that part's end knots "
                     "further from where its weight vanishes",
                     d->name, what, t, p->name, w, idx, dir_name(other), line, part ? l->name : r->name);
            rg2_status st = rg2__design_add_note(d, msg, err);
            if (st)
                return st;
            *weight_noted = 1;
            continue;
        }
        double back = rg2__merge_seam_back(&l->m, &r->m, dir, &by_left);
        if (!(back > RG2_MERGE_OVERLAP)) /* (examples that join well: up to 0.011) */
            continue;
        snprintf(msg, sizeof msg,
                 "%s: %s.merge[%d]: the control lines of '%s' and '%s' run back at their seam: the first %s line "
                 "of '%s' lies %.2g line spacings of '%s' behind the last of '%s' (centres of the lines): the "
                 "parts overlap, and the transition patches bend sharply or fold; leave a gap between the "
                 "parts (end the first earlier or start the second later)",
                 d->name, what, t, l->name, r->name, dir_name(other), r->name, back, by_left ? l->name : r->name,
                 l->name);
        rg2_status st = rg2__design_add_note(d, msg, err);
        if (st)
            return st;
    }
    return RG2_OK;
}

/*
 * METHOD (seam rule "preserve", docs/design-format.md): the parts are concatenated along dir
 * without new points. Part legs and junctions keep their scalars. The seam leg between the
 * last point of part L and the first of part R gets the mean of L's data-only end weight and
 * R's data-only start weight, w_s. The junction scalars b at both seam junctions stay; g is
 * re-solved so that the stencil quantities the parts' own end segments use are unchanged:
 *   at L's last junction j:  B_{j-1} = 2 b^2 (w_j + b w_{j-1}) / (w_j K_j)   is kept,
 *   at R's first junction j: A_j     = 2 (w_j + b w_{j-1}) / (w_{j-1} K_j)   is kept,
 * i.e. K_j is rescaled and g_j = K_j - 2 b (3 w_j - 2) - 2 b^2 (3 w_{j-1} - 2). Then every
 * patch of every part stays exactly what it was, K stays > 0 (a positive multiple of the
 * part's K), and the 3 patches straddling each seam are the transition.
 * Rule "plain" keeps b and g as they are (only w_s is new): simpler, but the end patches of
 * both parts change (they depend on w_s through K).
 */
rg2_status rg2__op_merge(const rg2__dmesh *const *in, int n_in, int dir, int closed,
                         rg2__seam_rule rule, rg2__dmesh *out, const char *what, rg2_error *err)
{
    int other = 1 - dir, n = 0;
    /* A seam joins the last line of one mesh to the first of the next (and, closed, the last
     * mesh back to the first). A polar end there (a line collapsed to the polar point) would put
     * the pole inside the merged mesh: the transitions run from a ring into a point and the parts
     * overlap, a surface no G2 promise describes. */
    for (int t = 0; t < n_in; t++) {
        const rg2_mesh *m = &in[t]->m;
        int nd = dir_scalars(m, dir)->n;
        if (dir_scalars(m, dir)->closed || nd < 1)
            continue;
        for (int end = 0; end < 2; end++) {
            int joined = end == 0 ? (t > 0 || closed) : (t < n_in - 1 || closed);
            int idx = end == 0 ? 0 : nd - 1;
            if (!joined || !rg2__mesh_line_collapsed(m, dir, idx))
                continue;
            const double *p = dir ? rg2_mesh_at(m, 0, idx) : rg2_mesh_at(m, idx, 0);
            return rg2__fail(err, RG2_EINCOMPATIBLE,
                             "%s.merge[%d]: mesh '%s' has a polar point at its %s end (%s %d collapsed to (%.6g, "
                             "%.6g, %.6g)), where the merge along %s joins it to %s: a merge cannot join at a pole; "
                             "order the meshes (or reverse '%s' along %s) so that its polar end is an end of "
                             "the merged mesh",
                             what, t, in[t]->name, end == 0 ? "first" : "last", dir ? "row v =" : "column u =", idx,
                             p[0] / p[3], p[1] / p[3], p[2] / p[3], dir_name(dir),
                             end == 0 ? (t > 0 ? "the mesh before it" : "the last mesh (closed)")
                                      : (t < n_in - 1 ? "the mesh after it" : "the first mesh (closed)"),
                             in[t]->name, dir_name(dir));
        }
    }
    for (int t = 0; t < n_in; t++) {
        const rg2_scalars *s = dir_scalars(&in[t]->m, dir);
        if (s->closed) {
            /* a mesh open the other way, closed in `other` where the first mesh is (a torus piece
             * whose tube circle is v, merged along v with a cylinder whose circle is u), is meant to
             * be transposed, not cut */
            char hint[300] = "";
            const rg2_mesh *m0 = &in[0]->m;
            if (t > 0 && !dir_scalars(&in[t]->m, other)->closed && dir_scalars(m0, other)->closed &&
                !dir_scalars(m0, dir)->closed)
                snprintf(hint, sizeof hint, ", or transpose it: it is open in %s, and '%s' is closed in %s",
                         dir_name(other), in[0]->name, dir_name(other));
            return rg2__fail(err, RG2_EINCOMPATIBLE,
                             "%s.merge[%d]: mesh '%s' is closed in %s; cut it open before merging along %s%s",
                             what, t, in[t]->name, dir_name(dir), dir_name(dir), hint);
        }
        n += s->n;
        if (n > RG2_MAX_POINTS)
            return rg2__fail(err, RG2_ELIMIT, "%s.merge[%d]: the merged meshes reach %d control points along %s, "
                             "more than the limit of %d", what, t, n, dir_name(dir), RG2_MAX_POINTS);
        if (t > 0) {
            char msg[400];
            const rg2_scalars *st = dir_scalars(&in[t]->m, other);
            if (scalars_differ(dir_scalars(&in[0]->m, other), st, msg, sizeof msg)) {
                /* name the mesh it is joined to, which it does not agree with (mesh t - 1); the first
                 * mesh only when it agrees with its neighbour to the tolerance and not with the first */
                int r = t - 1;
                if (!scalars_differ(dir_scalars(&in[r]->m, other), st, msg, sizeof msg)) {
                    r = 0;
                    scalars_differ(dir_scalars(&in[0]->m, other), st, msg, sizeof msg);
                }
                return rg2__fail(err, RG2_EINCOMPATIBLE,
                                 "%s.merge[%d]: meshes '%s' and '%s' do not agree in %s (the direction "
                                 "that must match when merging along %s): %s",
                                 what, t, in[r]->name, in[t]->name, dir_name(other), dir_name(dir), msg);
            }
        }
    }
    const rg2_scalars *so = dir_scalars(&in[0]->m, other);
    int nn[2], cc[2];
    nn[dir] = n;
    cc[dir] = closed;
    nn[other] = so->n;
    cc[other] = so->closed;
    rg2_status st = rg2__dmesh_alloc(out, NULL, nn[0], nn[1], cc[0], cc[1], err);
    if (st)
        return rg2__prefix(err, st, what);
    /* points */
    int off = 0;
    for (int t = 0; t < n_in; t++) {
        const rg2__dmesh *p = in[t];
        for (int i = 0; i < p->m.nu; i++)
            for (int j = 0; j < p->m.nv; j++) {
                int oi = dir == 0 ? off + i : i, oj = dir == 0 ? j : off + j;
                memcpy(rg2_mesh_at(&out->m, oi, oj), rg2_mesh_at(&p->m, i, j), 4 * sizeof(double));
                *rg2__dmesh_pp(out, oi, oj) = *rg2__dmesh_pp(p, i, j);
            }
        off += dir_scalars(&p->m, dir)->n;
    }
    /* the shared direction: the first mesh's scalars */
    {
        rg2_scalars *b = dir_scalars_mut(&out->m, other);
        int nw = rg2_scalars_num_w(so);
        memcpy(b->w, so->w, (size_t)nw * sizeof(double));
        memcpy(b->b, so->b, (size_t)so->n * sizeof(double));
        memcpy(b->g, so->g, (size_t)so->n * sizeof(double));
        memcpy(out->leg[other], in[0]->leg[other], (size_t)nw * sizeof(int));
        memcpy(out->jun[other], in[0]->jun[other], (size_t)so->n * sizeof(int));
        for (int t = 1; t < n_in; t++) {
            for (int i = 0; i < nw; i++)
                if (out->leg[other][i] != in[t]->leg[other][i])
                    out->leg[other][i] = -1;
            for (int i = 0; i < so->n; i++)
                if (out->jun[other][i] != in[t]->jun[other][i])
                    out->jun[other][i] = -1;
        }
    }
    /* the merge direction */
    rg2_scalars *S = dir_scalars_mut(&out->m, dir);
    int ooff = closed ? 0 : 1; /* stored index of leg l is l + ooff */
    off = 0;
    for (int t = 0; t < n_in; t++) {
        const rg2_scalars *a = dir_scalars(&in[t]->m, dir);
        for (int i = 0; i < a->n; i++) {
            S->b[off + i] = a->b[i];
            S->g[off + i] = a->g[i];
            out->jun[dir][off + i] = in[t]->jun[dir][i];
        }
        for (int l = 0; l <= a->n - 2; l++) { /* the part's own legs (stored l + 1) */
            S->w[off + l + ooff] = a->w[l + 1];
            out->leg[dir][off + l + ooff] = in[t]->leg[dir][l + 1];
        }
        off += a->n;
    }
    if (!closed) { /* data-only end legs of the whole */
        const rg2_scalars *a0 = dir_scalars(&in[0]->m, dir), *al = dir_scalars(&in[n_in - 1]->m, dir);
        S->w[0] = a0->w[0];
        out->leg[dir][0] = in[0]->leg[dir][0];
        S->w[n] = al->w[al->n];
        out->leg[dir][n] = in[n_in - 1]->leg[dir][al->n];
    }
    /* seams */
    off = 0;
    for (int t = 0; t < n_in; t++) {
        const rg2__dmesh *L = in[t];
        const rg2_scalars *a = dir_scalars(&L->m, dir);
        off += a->n;
        if (t == n_in - 1 && !closed)
            break;
        const rg2__dmesh *R = in[(t + 1) % n_in];
        const rg2_scalars *r = dir_scalars(&R->m, dir);
        int jl = off - 1, jr = off % n; /* seam junctions; seam leg = jl */
        double wvl = a->w[a->n], wvr = r->w[0];
        double ws = wvl == wvr ? wvl : 0.5 * (wvl + wvr);
        S->w[jl + ooff] = ws;
        out->leg[dir][jl + ooff] =
            (wvl == wvr && L->leg[dir][a->n] == R->leg[dir][0]) ? L->leg[dir][a->n] : -1;
        if (rule == RG2__SEAM_PLAIN || wvl == wvr)
            continue;
        /* left: keep B_{jl-1} */
        double b = a->b[a->n - 1], wp = a->w[a->n - 1], KL = rg2_scalars_K(a, a->n - 1);
        double K = KL * (ws + b * wp) * wvl / (ws * (wvl + b * wp));
        if (!rg2__finite(K)) /* (an intermediate overflowed: the same value by ratios) */
            K = KL * (((ws + b * wp) / ws) * (wvl / (wvl + b * wp))); /* (the product of the ratios is bounded) */
        S->g[jl] = K - 2.0 * b * (3.0 * ws - 2.0) - 2.0 * b * b * (3.0 * wp - 2.0);
        out->jun[dir][jl] = -1;
        /* right: keep A_{jr} */
        b = r->b[0];
        double wn = r->w[1], KR = rg2_scalars_K(r, 0);
        K = KR * wvr * (wn + b * ws) / (ws * (wn + b * wvr));
        if (!rg2__finite(K))
            K = KR * (wvr / ws) * ((wn + b * ws) / (wn + b * wvr));
        S->g[jr] = K - 2.0 * b * (3.0 * wn - 2.0) - 2.0 * b * b * (3.0 * ws - 2.0);
        out->jun[dir][jr] = -1;
    }
    st = rg2__dir_check(S, dir, what, "at a seam, ", err);
    if (st) {
        rg2__dmesh_free(out);
        return st;
    }
    /* NURBS pole sides whose patches come through unchanged: in practice the first part's start and
     * the last part's end along dir (open), when the seam's scalars leave their end segments alone */
    for (int t = 0; t < n_in; t++)
        rg2__poles_keep_same(out, in[t]);
    /* A side along dir (an end of `other`) runs through the seams' new transition patches, but it is
     * the point p wherever every part has the pole p there: the construction is linear, so the side
     * of the patch of dir segment k is sum_a c_a E_a over the patch's 4 lines a across dir (c_a the
     * dir stencil's row, the seams' new legs and junctions in it), E_a the other direction's end
     * stencil row over line a's 3 points nearest that end (curve.c: b0 of the end segment). With
     * `other`'s scalars those of the part that line comes from, E_a is the end point of the line's
     * curve in its part, (w_a p, w_a) but for the rounding of the part's mesh (its extrapolated end
     * lines, nurbs.c), and every combination of those is (W p, W): the point p, whatever the
     * merge direction's scalars. The construction spreads the side by the parts' rounding, as in the
     * parts (tests/test_nurbs.c, pole_merge), which the output's fix-up removes. A part whose pole
     * lies elsewhere, that has none or whose scalars across differ leaves the construction's side. */
    for (int side = dir; side < 4; side += 2) { /* the sides along u (v = 0, v = 1) or along v */
        int all = 1;
        for (int t = 0; t < n_in && all; t++)
            all = in[t]->poles >> side & 1u && same_bits(in[t]->pole[side], in[0]->pole[side], 3) &&
                  scalars_same(dir_scalars(&in[t]->m, other), so);
        if (all)
            pole_keep(out, side, in[0]->pole[side]);
    }
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* transform */

/* The indices a mesh refers to in one direction of a source of n points: their range, and (closed
 * direction) their range shifted by n / 2 mod n, which is the shorter one when they wrap past
 * n - 1 to 0 and lie within half the circle. */
typedef struct {
    int any;
    int lo[2], hi[2], slo[2], shi[2];
} src_window;

static void window_add(src_window *w, const rg2__source *S, int i, int j)
{
    int x[2] = {i, j}, n[2] = {S->nu, S->nv};
    for (int k = 0; k < 2; k++) {
        int sx = (x[k] + n[k] / 2) % n[k];
        if (!w->any || x[k] < w->lo[k]) w->lo[k] = x[k];
        if (!w->any || x[k] > w->hi[k]) w->hi[k] = x[k];
        if (!w->any || sx < w->slo[k]) w->slo[k] = sx;
        if (!w->any || sx > w->shi[k]) w->shi[k] = sx;
    }
    w->any = 1;
}

static void window_get(const src_window *w, const rg2__source *S, int *i0, int *j0, int *wu, int *wv)
{
    int n[2] = {S->nu, S->nv}, first[2], count[2];
    for (int k = 0; k < 2; k++) {
        first[k] = w->lo[k];
        count[k] = w->hi[k] - w->lo[k] + 1;
        if (S->closed[k] && w->shi[k] - w->slo[k] + 1 < count[k]) {
            count[k] = w->shi[k] - w->slo[k] + 1;
            first[k] = (w->slo[k] - n[k] / 2 + n[k]) % n[k];
        }
    }
    *i0 = first[0], *j0 = first[1], *wu = count[0], *wv = count[1];
}

/* The sources (or shapes) a transformed mesh uses, each with its slot in the order of first use:
 * an open-addressing hash of indices (a power-of-two table, key -1 empty, at most half full).
 * Sized by what the mesh uses, not by all the design's sources and shapes: a chain of T
 * transforms makes T of each, and tables of that size at every link made the chain O(T^2)
 * (80 000 transforms of a cylinder's 8 x 6 mesh, near the design's 4 million points: 3.3 s, now
 * 0.95 s; test_scaling counts the bytes). */
typedef struct {
    size_t cap, n;
    int *key, *val;
} index_map;

static size_t index_hash(int key, size_t cap)
{
    return ((size_t)(unsigned)key * (size_t)0x9E3779B1u) & (cap - 1);
}

/* The value of key, or -1. */
static int index_find(const index_map *m, int key)
{
    if (!m->cap)
        return -1;
    for (size_t h = index_hash(key, m->cap);; h = (h + 1) & (m->cap - 1)) {
        if (m->key[h] == key)
            return m->val[h];
        if (m->key[h] < 0)
            return -1;
    }
}

/* Enter key (not yet there) with value val. 0, or -1 out of memory (nothing entered). */
static int index_put(index_map *m, int key, int val)
{
    if (2 * (m->n + 1) > m->cap) {
        index_map g = {m->cap ? 2 * m->cap : 16, m->n, NULL, NULL};
        g.key = malloc(g.cap * sizeof *g.key);
        g.val = malloc(g.cap * sizeof *g.val);
        if (!g.key || !g.val) {
            free(g.key);
            free(g.val);
            return -1;
        }
        for (size_t h = 0; h < g.cap; h++)
            g.key[h] = -1;
        for (size_t k = 0; k < m->cap; k++)
            if (m->key[k] >= 0) {
                size_t h = index_hash(m->key[k], g.cap);
                while (g.key[h] >= 0)
                    h = (h + 1) & (g.cap - 1);
                g.key[h] = m->key[k];
                g.val[h] = m->val[k];
            }
        free(m->key);
        free(m->val);
        *m = g;
    }
    size_t h = index_hash(key, m->cap);
    while (m->key[h] >= 0)
        h = (h + 1) & (m->cap - 1);
    m->key[h] = key;
    m->val[h] = val;
    m->n++;
    return 0;
}

static void index_free(index_map *m)
{
    free(m->key);
    free(m->val);
    memset(m, 0, sizeof *m);
}

/* A source the transformed mesh uses: its index, the window of the indices it uses, its copy. */
typedef struct {
    int src, copy;
    src_window win;
} used_source;

rg2_status rg2__op_transform(rg2_design *d, const rg2__dmesh *in, const double M[16],
                             rg2__dmesh *out, const char *what, rg2_error *err)
{
    for (int k = 0; k < 16; k++)
        if (!rg2__finite(M[k]))
            return rg2__fail(err, RG2_ENONFINITE, "%s: the transform's matrix entry %d is not finite", what, k);
    rg2_status st = rg2__dmesh_copy(in, out, err);
    if (st)
        return st;
    rg2_mesh_transform(&out->m, M);
    for (int side = 0; side < 4; side++) /* NURBS pole sides: their points mapped (not to infinity) */
        if (in->poles >> side & 1u) {
            double q[4] = {in->pole[side][0], in->pole[side][1], in->pole[side][2], 1.0};
            rg2__xform_apply(M, q);
            double a[3] = {q[0] / q[3], q[1] / q[3], q[2] / q[3]};
            if (rg2__finite(a[0]) && rg2__finite(a[1]) && rg2__finite(a[2]))
                pole_keep(out, side, a);
        }
    /* every source (and shape) the mesh uses gets a transformed copy: of the points the mesh refers
     * to only (the window of their indices), so that a chain of transforms of a small cut of a big
     * shape mesh does not copy the big mesh each time; in the order the points first use them */
    index_map slot = {0, 0, NULL, NULL}, smap = {0, 0, NULL, NULL}; /* source -> used[], shape -> new shape */
    used_source *used = NULL;
    size_t n_used = 0, cap_used = 0;
    int nsh0 = d->n_shapes, last = -1, last_slot = -1;
    size_t np = (size_t)out->m.nu * (size_t)out->m.nv;
    for (size_t q = 0; q < np; q++) {
        int s = out->pp[q].src;
        if (s < 0)
            continue;
        int u = s == last ? last_slot : index_find(&slot, s);
        if (u < 0) {
            if (n_used == cap_used) {
                size_t nc = cap_used ? 2 * cap_used : 8;
                used_source *g = realloc(used, nc * sizeof *g);
                if (!g)
                    goto oom;
                used = g;
                cap_used = nc;
            }
            if (index_put(&slot, s, (int)n_used))
                goto oom;
            u = (int)n_used++;
            memset(&used[u], 0, sizeof used[u]);
            used[u].src = s;
        }
        last = s;
        last_slot = u;
        window_add(&used[u].win, &d->src[s], out->pp[q].i, out->pp[q].j);
    }
    for (size_t u = 0; u < n_used; u++) {
        int s = used[u].src, sh = d->src[s].shape, nsh = index_find(&smap, sh);
        if (nsh < 0) {
            rg2_shape ns = d->shapes[sh];
            rg2_xform_mul(M, d->shapes[sh].xform, ns.xform);
            /* "<label>@<what>", whole (cut to 256 bytes, two long labels gave one label, ending in
             * half a UTF-8 character); past 256 bytes a label made by earlier transforms keeps its
             * first part and this one, "<first>@...@<what>", so that a chain of T transforms does
             * not make labels of T parts (O(T^2) bytes) */
            const char *prev = d->labels[sh], *at = strchr(prev, '@');
            size_t lp = strlen(prev), lw = strlen(what), cut = at && lp + lw + 1 > 255 ? (size_t)(at - prev) : lp;
            size_t ll = cut + lw + 6;
            char *label = malloc(ll);
            if (!label) {
                rg2__fail(err, RG2_ENOMEM, "design: out of memory for shapes");
                goto fail;
            }
            snprintf(label, ll, "%.*s%s%s", (int)cut, prev, cut < lp ? "@...@" : "@", what);
            nsh = rg2__design_add_shape(d, &ns, label, err);
            free(label);
            if (nsh < 0)
                goto fail;
            if (index_put(&smap, sh, nsh))
                goto oom;
        }
        int i0, j0, wu, wv;
        window_get(&used[u].win, &d->src[s], &i0, &j0, &wu, &wv);
        used[u].copy = rg2__design_add_source_xform(d, nsh, s, M, i0, j0, wu, wv, err);
        if (used[u].copy < 0)
            goto fail;
    }
    last = -1;
    for (size_t q = 0; q < np; q++) {
        int s = out->pp[q].src;
        if (s < 0)
            continue;
        if (s != last)
            last_slot = index_find(&slot, s);
        last = s;
        out->pp[q].src = used[last_slot].copy;
    }
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *s = dir_scalars(&out->m, k);
        for (int i = 0; i < rg2_scalars_num_w(s); i++) {
            int t = out->leg[k][i] >= 0 && out->leg[k][i] < nsh0 ? index_find(&smap, out->leg[k][i]) : -1;
            if (t >= 0)
                out->leg[k][i] = t;
        }
        for (int i = 0; i < s->n; i++) {
            int t = out->jun[k][i] >= 0 && out->jun[k][i] < nsh0 ? index_find(&smap, out->jun[k][i]) : -1;
            if (t >= 0)
                out->jun[k][i] = t;
        }
    }
    index_free(&slot);
    index_free(&smap);
    free(used);
    return RG2_OK;
oom:
    rg2__fail(err, RG2_ENOMEM, "%s: out of memory", what);
fail:
    index_free(&slot);
    index_free(&smap);
    free(used);
    rg2__dmesh_free(out);
    return err ? err->code : RG2_ENOMEM;
}

/* ------------------------------------------------------------------------------------- */
/* morph */

static double blend(double a, double b, double t)
{
    if (t == 0.0 || a == b)
        return a;
    if (t == 1.0)
        return b;
    return (1.0 - t) * a + t * b;
}

/*
 * METHOD: the homogeneous 4-tuples and the scalars w, b, g are blended linearly,
 * (1 - t) A + t B; equal values are copied (no rounding), t = 0 and t = 1 copy A and B.
 * Provenance survives where both meshes agree in value and provenance (or at t = 0, 1).
 */
rg2_status rg2__op_morph(const rg2__dmesh *a, const rg2__dmesh *b, double t, rg2__dmesh *out,
                         const char *what, rg2_error *err)
{
    if (!rg2__finite(t) || t < 0.0 || t > 1.0)
        return rg2__fail(err, RG2_EDOMAIN, "%s.t: t = %s, must lie in [0, 1]", what, rg2__num(t).s);
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *sa = dir_scalars(&a->m, k), *sb = dir_scalars(&b->m, k);
        if (sa->n != sb->n || sa->closed != sb->closed) {
            /* b's u against a's v and b's v against a's u: b is a's structure transposed */
            const rg2_scalars *bt[2] = {&b->m.sv, &b->m.su};
            int swapped = 1;
            for (int q = 0; q < 2; q++)
                swapped = swapped && dir_scalars(&a->m, q)->n == bt[q]->n &&
                          dir_scalars(&a->m, q)->closed == bt[q]->closed;
            return rg2__fail(err, RG2_EINCOMPATIBLE,
                             "%s.morph: meshes '%s' (%d control points, %s) and '%s' (%d control points, %s) "
                             "differ in %s; a morph needs meshes of equal structure%s%s%s",
                             what, a->name, sa->n, sa->closed ? "closed" : "open", b->name, sb->n,
                             sb->closed ? "closed" : "open", dir_name(k),
                             swapped ? " ('" : "", swapped ? b->name : "",
                             swapped ? "' transposed would match)" : "");
        }
    }
    rg2_status st = rg2__dmesh_copy(t == 1.0 ? b : a, out, err);
    if (st)
        return st;
    if (t == 0.0 || t == 1.0) {
        rg2__poles_keep_same(out, t == 1.0 ? b : a);
        return RG2_OK;
    }
    size_t np = (size_t)a->m.nu * (size_t)a->m.nv;
    for (size_t q = 0; q < np; q++) {
        int same = 1;
        for (int c = 0; c < 4; c++) {
            double x = a->m.p[q * 4 + c], y = b->m.p[q * 4 + c];
            same = same && x == y;
            out->m.p[q * 4 + c] = blend(x, y, t);
        }
        if (!same || memcmp(&a->pp[q], &b->pp[q], sizeof a->pp[q]))
            out->pp[q].src = -1;
    }
    for (int k = 0; k < 2; k++) {
        const rg2_scalars *sa = dir_scalars(&a->m, k), *sb = dir_scalars(&b->m, k);
        rg2_scalars *so = dir_scalars_mut(&out->m, k);
        for (int i = 0; i < rg2_scalars_num_w(sa); i++) {
            so->w[i] = blend(sa->w[i], sb->w[i], t);
            if (sa->w[i] != sb->w[i] || a->leg[k][i] != b->leg[k][i])
                out->leg[k][i] = -1;
        }
        for (int i = 0; i < sa->n; i++) {
            so->b[i] = blend(sa->b[i], sb->b[i], t);
            so->g[i] = blend(sa->g[i], sb->g[i], t);
            if (sa->b[i] != sb->b[i] || sa->g[i] != sb->g[i] || a->jun[k][i] != b->jun[k][i])
                out->jun[k][i] = -1;
        }
        char w[300], when[40];
        if (snprintf(w, sizeof w, "%s.t", what) >= (int)sizeof w)
            rg2__utf8_cut(w);
        void *loc = rg2__c_numeric_begin(); /* (rg2_mesh_morph too: "at t = 0.5") */
        snprintf(when, sizeof when, "at t = %g, ", t);
        rg2__c_numeric_end(loc);
        st = rg2__dir_check(so, k, w, when, err);
        if (st) {
            rg2__dmesh_free(out);
            return st;
        }
    }
    /* NURBS pole sides where the meshes agree (blend copies equal values): the end unchanged */
    rg2__poles_keep_same(out, a);
    rg2__poles_keep_same(out, b);
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* edits */

rg2_status rg2__edit_point(rg2__dmesh *m, int i, int j, rg2__edit_kind kind, const double *v,
                           const char *what, rg2_error *err)
{
    if (i < 0 || i >= m->m.nu || j < 0 || j >= m->m.nv)
        return rg2__fail(err, RG2_EINVAL,
                         "%s: control point [%d, %d] is outside the %d x %d points of mesh '%s' "
                         "(indices count from 0: [0..%d, 0..%d])",
                         what, i, j, m->m.nu, m->m.nv, m->name, m->m.nu - 1, m->m.nv - 1);
    int nv = kind == RG2__EDIT_WEIGHT ? 1 : 3;
    for (int k = 0; k < nv; k++)
        if (!rg2__finite(v[k]))
            return rg2__fail(err, RG2_ENONFINITE, "%s: value %d is not finite", what, k);
    double *p = rg2_mesh_at(&m->m, i, j), W = p[3], q[4];
    if (kind == RG2__EDIT_WEIGHT && !(v[0] > 0.0))
        return rg2__fail(err, RG2_EWEIGHT, "%s: weight W = %g, must be > 0", what, v[0]);
    if (!(W > 0.0) && kind != RG2__EDIT_WEIGHT)
        return rg2__fail(err, RG2_EWEIGHT,
                         "%s: control point [%d, %d] has weight W = %g; design coordinates need W > 0",
                         what, i, j, W);
    /* a value the designer leaves as it is (offset 0, the point's own d = p / W or W) leaves p and
     * its provenance alone: W * (p / W) need not give p back (48 of the 120 points of
     * torus_sphere.json moved "to" their own d lost 20 of its 24 sphere tags) */
    if (kind == RG2__EDIT_MOVE && v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0)
        return RG2_OK;
    if (kind == RG2__EDIT_TO && v[0] == p[0] / W && v[1] == p[1] / W && v[2] == p[2] / W)
        return RG2_OK;
    if (kind == RG2__EDIT_WEIGHT && v[0] == W)
        return RG2_OK;
    switch (kind) {
    case RG2__EDIT_MOVE:
        for (int k = 0; k < 3; k++)
            q[k] = W * (p[k] / W + v[k]);
        q[3] = W;
        break;
    case RG2__EDIT_TO:
        for (int k = 0; k < 3; k++)
            q[k] = W * v[k];
        q[3] = W;
        break;
    default:
        if (!(W > 0.0))
            return rg2__fail(err, RG2_EWEIGHT, "%s: control point [%d, %d] has weight W = %g",
                             what, i, j, W);
        for (int k = 0; k < 3; k++)
            q[k] = v[0] * (p[k] / W);
        q[3] = v[0];
        break;
    }
    for (int k = 0; k < 4; k++)
        if (!rg2__finite(q[k]))
            return rg2__fail(err, RG2_ENONFINITE, "%s: control point [%d, %d] becomes non-finite",
                             what, i, j);
    if (memcmp(p, q, sizeof q)) {
        memcpy(p, q, sizeof q);
        rg2__dmesh_pp(m, i, j)->src = -1;
    }
    return RG2_OK;
}

rg2_status rg2__edit_scalar(rg2__dmesh *m, int dir, char which, int i, double value,
                            const char *what, rg2_error *err)
{
    rg2_scalars *s = dir_scalars_mut(&m->m, dir);
    if (!rg2__finite(value))
        return rg2__fail(err, RG2_ENONFINITE, "%s: %c is not finite", what, which);
    if (which == 'w') {
        int lo = s->closed ? 0 : -1, hi = s->n - 1;
        if (i < lo || i > hi)
            return rg2__fail(err, RG2_EINVAL, "%s: %s leg %d is outside %d..%d of mesh '%s'", what,
                             dir_name(dir), i, lo, hi, m->name);
        if (!(value > 0.0))
            return rg2__fail(err, RG2_EWEIGHT, "%s: leg weight w = %g, must be > 0", what, value);
        int si = i + (s->closed ? 0 : 1);
        if (s->w[si] != value) {
            s->w[si] = value;
            m->leg[dir][si] = -1;
        }
        return RG2_OK;
    }
    if (i < 0 || i >= s->n)
        return rg2__fail(err, RG2_EINVAL, "%s: %s junction %d is outside 0..%d of mesh '%s'", what,
                         dir_name(dir), i, s->n - 1, m->name);
    if (which == 'b' && !(value > 0.0))
        return rg2__fail(err, RG2_EWEIGHT, "%s: junction scalar b = %g, must be > 0", what, value);
    double *x = which == 'b' ? &s->b[i] : &s->g[i];
    if (*x != value) {
        *x = value;
        m->jun[dir][i] = -1;
    }
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* scalars of a design mesh */

int rg2__bad_junction(const rg2_scalars *s)
{
    for (int i = 0; i < s->n; i++) {
        double K = rg2_scalars_K(s, i);
        if (!(K > 0.0) || !rg2__finite(K))
            return i;
    }
    return -1;
}

rg2_status rg2__dir_check(const rg2_scalars *s, int dir, const char *what, const char *when, rg2_error *err)
{
    int i = rg2__bad_junction(s);
    if (i >= 0) {
        double K = rg2_scalars_K(s, i);
        return rg2__fail(err, rg2__finite(K) ? RG2_EWEIGHT : RG2_ENONFINITE,
                         "%s: %s%s junction %d has K = %g (from w[%d] = %g, w[%d] = %g, b = %g, g = %g); "
                         "K must be %s",
                         what, when, dir_name(dir), i, K, rg2__prev_leg(s, i), rg2_scalars_leg_w(s, i - 1), i,
                         rg2_scalars_leg_w(s, i), s->b[i], s->g[i],
                         rg2__finite(K) ? "> 0" : "a finite number > 0 (the scalars leave the double range)");
    }
    char w[340];
    if (snprintf(w, sizeof w, "%s: %s%s", what, when, dir_name(dir)) >= (int)sizeof w)
        rg2__utf8_cut(w);
    return rg2_scalars_check(s, w, err); /* (the operations keep w, b > 0: not reached) */
}
