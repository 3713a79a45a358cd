/* design_poles.c -- the poles operations of the design format (docs/design-format.md,
 * docs/poles.md): polar configurations of a shape, Moebius pole placement, polar point edits,
 * and capped output surfaces. */
#include "design_internal.h"

#include <math.h>
#include <stdio.h>

#include <stdlib.h>
#include <string.h>

/* The same on a shape's source (which stores all its points). */
static void collapse_source_row(rg2__source *S, int j)
{
    for (int i = 1; i < S->nu; i++)
        memcpy(rg2__source_at(S, i, j), rg2__source_at(S, 0, j), 4 * sizeof(double));
}

rg2_status rg2__polar_kind(const rg2_design *d, int shape, const char *what, rg2_error *err)
{
    rg2_shape_kind kind = d->shapes[shape].kind;
    if (kind != RG2_SHAPE_SPHERE && kind != RG2_SHAPE_ELLIPSOID && kind != RG2_SHAPE_PARABOLOID &&
        kind != RG2_SHAPE_HYPERBOLOID2)
        return rg2__fail(err, RG2_EINVAL,
                         "%s.polar: '%s' is a %s, which has no polar configuration (sphere, ellipsoid: both "
                         "poles; paraboloid, hyperboloid2: the pole at v = 0)",
                         what, d->labels[shape], rg2_shape_name(kind));
    return RG2_OK;
}

/*
 * METHOD: a polar configuration is the shape's own family-2 mesh over the full knot vector of
 * the polar configuration (RG2_PART_KNOTS_FULL): sphere and ellipsoid v_{-1} = v_1/(v_1 - 1),
 * 0, v_1..v_m, 1, 1/v_m (MATH.md section 7, both poles); paraboloid and two-sheeted
 * hyperboloid -v_1, 0, v_1..v_m and two data-only knots past v_m (the blossom of v vanishes on
 * row 0: the pole at v = 0 is the south end), or, for knots below 0, two data-only knots before
 * v_1 and v_1..v_m, 0, -v_m (the pole is the north end). The rows that collapse mathematically are made bit-exact in the
 * source too, so provenance sees the band patches as pieces of the shape.
 */
rg2_status rg2__op_polar(rg2_design *d, int shape, const rg2_partition *pu, const double *v, int m,
                         rg2__dmesh *out, const char *what, const char *kpath, rg2_error *err)
{
    rg2_shape_kind kind = d->shapes[shape].kind;
    int both = kind == RG2_SHAPE_SPHERE || kind == RG2_SHAPE_ELLIPSOID;
    rg2_status st = rg2__polar_kind(d, shape, what, err);
    if (st)
        return st;
    if (m < 2)
        return rg2__fail(err, RG2_EINVAL, "%s: %d knot; a polar configuration needs at least 2", kpath, m);
    double *k = rg2__calloc((size_t)m + 4, sizeof(double));
    if (!k)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory", what);
    int north = 0;
    st = rg2__polar_full_knots(kind, v, m, k, &north, err);
    if (st) { /* (rg2_polar_knots: "polar knots: knot 1 = ..."; the path names the knots) */
        rg2_error e = *err;
        free(k);
        return rg2__fail(err, st, "%s: %s", kpath, rg2__after(e.msg, "polar knots: "));
    }
    rg2_partition pv = {RG2_PART_KNOTS_FULL, 0, m + 4, k, 0.0};
    st = rg2__op_shape(d, shape, pu, &pv, out, what, kpath, err);
    free(k);
    if (st)
        return st;
    rg2__source *base = &d->src[d->n_src - 1];
    for (int e = 0; e < 2; e++) {
        if (!both && e != north)
            continue;
        int j = e ? base->nv - 1 : 0;
        collapse_source_row(base, j);
        rg2__collapse_row(&out->m, j);
    }
    return RG2_OK;
}

/* The design's `mobius`: the mesh gets rg2__mobius_world's X M X^-1 (a transform: the sources
 * and the shape get transformed copies, and the placed shape's implicit equation is carried
 * through the projective map). */
/* A mobius without "sphere" maps about the unit sphere at the origin. When the mesh's points
 * came from another sphere or ellipsoid, that sphere does not stay itself (its poles leave it):
 * a note names the "sphere" the designer most likely meant. */
static rg2_status note_missing_sphere(rg2_design *d, const rg2__dmesh *in, const char *what, rg2_error *err)
{
    int k = -1;
    for (int q = 0; q < in->m.nu * in->m.nv && k < 0; q++)
        if (in->pp[q].src >= 0)
            k = d->src[in->pp[q].src].shape;
    if (k < 0)
        return RG2_OK;
    const rg2_shape *s = &d->shapes[k];
    double I[16];
    rg2_xform_identity(I);
    int unit = s->kind == RG2_SHAPE_SPHERE && s->param[0] == 1.0 && !memcmp(s->xform, I, sizeof I);
    if (unit || (s->kind != RG2_SHAPE_SPHERE && s->kind != RG2_SHAPE_ELLIPSOID))
        return RG2_OK;
    char msg[700];
    snprintf(msg, sizeof msg,
             "%s: %s: no \"sphere\" given: the Moebius map is about the unit sphere at the origin, but '%s' "
             "comes from the %s '%s', which the map turns into another %s; to move the poles on '%s' itself, "
             "give \"sphere\": \"%s\"",
             d->name, what, in->name, rg2_shape_name(s->kind), d->labels[k], rg2_shape_name(s->kind), d->labels[k],
             d->labels[k]);
    return rg2__design_add_note(d, msg, err);
}

rg2_status rg2__op_mobius(rg2_design *d, const rg2__dmesh *in, int shape, const double *b,
                          double poles[2][3], rg2__dmesh *out, const char *what, rg2_error *err)
{
    double A[16];
    if (shape < 0) {
        rg2_status st = note_missing_sphere(d, in, what, err);
        if (st)
            return st;
    }
    rg2_status st = rg2__mobius_world(shape >= 0 ? &d->shapes[shape] : NULL, shape >= 0 ? d->labels[shape] : NULL,
                                      b, poles[0], poles[1], A, what, "sphere", "poles.", err);
    if (st)
        return st;
    if ((st = rg2__op_transform(d, in, A, out, what, err)))
        return st;
    for (int i = 0; i < out->m.nu; i++)
        for (int j = 0; j < out->m.nv; j++)
            if (!(rg2_mesh_at(&out->m, i, j)[3] > 0.0)) {
                double w = rg2_mesh_at(&out->m, i, j)[3];
                rg2__dmesh_free(out);
                return rg2__fail(err, RG2_EWEIGHT,
                                 "%s.%s: the Moebius map gives control point [%d, %d] the weight %g, sending it "
                                 "through infinity (move the poles less far, or refine the u partition)",
                                 what, b ? "b" : "poles", i, j, w);
            }
    return RG2_OK;
}

rg2_status rg2__edit_pole(rg2__dmesh *m, int end, rg2__edit_kind kind, const double *v, const char *what,
                          rg2_error *err)
{
    if (m->m.sv.closed)
        return rg2__fail(err, RG2_EINVAL, "%s: mesh '%s' is closed in v; it has no poles", what, m->name);
    int j = end ? m->m.nv - 1 : 0;
    if (!rg2_mesh_row_collapsed(&m->m, j))
        return rg2__fail(err, RG2_EINVAL,
                         "%s: row %d (the %s end) of mesh '%s' is not a polar point (not collapsed)", what, j,
                         end ? "north" : "south", m->name);
    for (int i = 0; i < m->m.nu; i++) {
        rg2_status st = rg2__edit_point(m, i, j, kind, v, what, err);
        if (st)
            return st;
    }
    /* one position for the whole row (each point's own rounding could differ in the last bit),
     * each point keeping its own weight: a row collapsed only projectively (a NURBS pole with
     * weights 1, 1.5, 2, ...) keeps the weights the surface depends on; copying point 0 over
     * the row made them all 1, so even a zero move changed the surface */
    const double *p0 = rg2_mesh_at(&m->m, 0, j);
    for (int i = 1; i < m->m.nu; i++) {
        double *p = rg2_mesh_at(&m->m, i, j), q[4] = {0.0, 0.0, 0.0, p[3]};
        for (int k = 0; k < 3; k++)
            q[k] = p[3] == p0[3] ? p0[k] : p[3] * (p0[k] / p0[3]);
        if (memcmp(p, q, sizeof q)) {
            memcpy(p, q, sizeof q);
            rg2__dmesh_pp(m, i, j)->src = -1;
        }
    }
    return RG2_OK;
}

/*
 * Build a capped output: rg2_cap_build on the mesh; body patches are tagged like an uncapped
 * build (offset by the cap rows before them); a cap takes the shape tag of its boundary ring
 * when every ring patch carries that tag and the fit reproduced the ring's jets (relative
 * residual <= 1e-12: the fit is unique, so the cap map is the shape's own, e.g. the sphere),
 * else -1.
 */
/* A failed cap names the cap's entry and the mesh it caps (cap.c's messages start with "cap: ";
 * its options, the jet weights among them, are checked by the parser, naming their keys). */
static rg2_status cap_fail(const rg2_design *d, const rg2__dmesh *dm, rg2_status st, rg2_error *err)
{
    rg2_error e = *err;
    const char *m = rg2__after(e.msg, "cap: ");
    return rg2__fail(err, st, "%s: meshes.%s.cap: mesh '%s' cannot be capped: %s", d->name, dm->name,
                     d->mesh[dm->cap_src].name, m);
}

rg2_status rg2__design_build_capped(const rg2_design *d, const rg2__dmesh *dm, rg2_surface *s,
                                    rg2_error *err)
{
    rg2_cap_info info;
    rg2_status st = rg2_cap_build(&dm->m, &dm->cap, s, &info, err);
    if (st)
        return cap_fail(d, dm, st, err);
    rg2__stencil sten[2];
    if ((st = rg2__stencil_make(&dm->m.su, &sten[0], err)))
        goto fail;
    if ((st = rg2__stencil_make(&dm->m.sv, &sten[1], err))) {
        rg2__stencil_free(&sten[0]);
        goto fail;
    }
    s->tag = rg2__calloc((size_t)s->nu * (size_t)s->nv, sizeof(int));
    if (!s->tag) {
        rg2__stencil_free(&sten[0]);
        rg2__stencil_free(&sten[1]);
        st = rg2__fail(err, RG2_ENOMEM, "design: out of memory for tags");
        goto fail;
    }
    int rb = info.rows_before, nb = s->nv - rb - info.rows_after;
    for (int k = 0; k < s->nu; k++)
        for (int l = 0; l < nb; l++)
            s->tag[k * s->nv + rb + l] = rg2__patch_tag(d, dm, sten, k, l);
    rg2__stencil_free(&sten[0]);
    rg2__stencil_free(&sten[1]);
    for (int e = 0; e < 2; e++) {
        if (!info.capped[e])
            continue;
        int ring = e ? rb + nb - 1 : rb, t = s->tag[ring];
        for (int k = 0; k < s->nu; k++)
            if (s->tag[k * s->nv + ring] != t)
                t = -1;
        if (!(info.residual[e] <= 1e-12))
            t = -1;
        for (int k = 0; k < s->nu; k++)
            for (int r = 0; r < 3; r++)
                s->tag[k * s->nv + (e ? s->nv - 1 - r : r)] = t;
    }
    return RG2_OK;
fail:
    rg2_surface_free(s);
    return st;
}
