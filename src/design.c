/* design.c -- designs (paper section 4): registries of shapes, sources and meshes, the
 * build of the output surfaces, and the provenance tags telling which patches are exact
 * pieces of which shape (MATH.md section 6). */
#include "design_internal.h"

#include <cjson/cJSON.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ------------------------------------------------------------------------------------- */
/* registries */

static int grow(void **arr, int *cap, int need, size_t size)
{
    if (need <= *cap)
        return 1;
    int nc = *cap ? *cap * 2 : 8;
    while (nc < need)
        nc *= 2;
    void *p = realloc(*arr, (size_t)nc * size);
    if (!p)
        return 0;
    memset((char *)p + (size_t)*cap * size, 0, (size_t)(nc - *cap) * size);
    *arr = p;
    *cap = nc;
    return 1;
}

static char *dupstr(const char *s)
{
    char *r = malloc(strlen(s) + 1);
    if (r)
        strcpy(r, s);
    return r;
}

/* FNV-1a */
static size_t name_hash(const char *s)
{
    uint64_t h = 1469598103934665603ull;
    for (; *s; s++)
        h = (h ^ (unsigned char)*s) * 1099511628211ull;
    return (size_t)(h ^ (h >> 32));
}

static int names_find(const rg2__names *t, const char *key)
{
    if (!t->cap)
        return -1;
    for (size_t h = name_hash(key) & (t->cap - 1);; h = (h + 1) & (t->cap - 1)) {
        if (!t->key[h])
            return -1;
        if (!strcmp(t->key[h], key))
            return t->idx[h];
    }
}

static void names_put(rg2__names *t, const char *key, int idx)
{
    size_t h = name_hash(key) & (t->cap - 1);
    while (t->key[h] && strcmp(t->key[h], key))
        h = (h + 1) & (t->cap - 1);
    if (t->key[h])
        return; /* the first one stays */
    t->key[h] = key;
    t->idx[h] = idx;
    t->n++;
}

/* Index key as idx unless already there. Returns 0, or -1 out of memory. */
static int names_add(rg2__names *t, const char *key, int idx)
{
    if (2 * (t->n + 1) > t->cap) {
        rg2__names g = {t->cap ? 2 * t->cap : 64, 0, NULL, NULL};
        g.key = rg2__calloc(g.cap, sizeof *g.key);
        g.idx = rg2__calloc(g.cap, sizeof *g.idx);
        if (!g.key || !g.idx) {
            free(g.key);
            free(g.idx);
            return -1;
        }
        for (size_t k = 0; k < t->cap; k++)
            if (t->key[k])
                names_put(&g, t->key[k], t->idx[k]);
        free(t->key);
        free(t->idx);
        *t = g;
    }
    names_put(t, key, idx);
    return 0;
}

static void names_free(rg2__names *t)
{
    free(t->key);
    free(t->idx);
    memset(t, 0, sizeof *t);
}

int rg2__design_add_shape(rg2_design *d, const rg2_shape *s, const char *label, rg2_error *err)
{
    int cap = d->cap_shapes;
    if (!grow((void **)&d->shapes, &cap, d->n_shapes + 1, sizeof *d->shapes) ||
        !grow((void **)&d->labels, &d->cap_shapes, d->n_shapes + 1, sizeof *d->labels)) {
        rg2__fail(err, RG2_ENOMEM, "design: out of memory for shapes");
        return -1;
    }
    char *l = dupstr(label);
    if (!l || names_add(&d->shape_index, l, d->n_shapes)) {
        free(l);
        rg2__fail(err, RG2_ENOMEM, "design: out of memory for shapes");
        return -1;
    }
    d->shapes[d->n_shapes] = *s;
    d->labels[d->n_shapes] = l;
    return d->n_shapes++;
}

int rg2__design_add_source(rg2_design *d, int shape, rg2_mesh *base, rg2_error *err)
{
    if (!grow((void **)&d->src, &d->cap_src, d->n_src + 1, sizeof *d->src)) {
        rg2__fail(err, RG2_ENOMEM, "design: out of memory for source meshes");
        return -1;
    }
    rg2__source *s = &d->src[d->n_src];
    memset(s, 0, sizeof *s);
    s->shape = shape;
    if (rg2__stencil_make(&base->su, &s->st[0], err) || rg2__stencil_make(&base->sv, &s->st[1], err)) {
        rg2__stencil_free(&s->st[0]);
        return -1;
    }
    s->own_st = 1;
    s->nu = s->wu = base->nu;
    s->nv = s->wv = base->nv;
    s->closed[0] = base->su.closed;
    s->closed[1] = base->sv.closed;
    s->p = base->p; /* takes the points; the scalars live on in the stencils */
    base->p = NULL;
    rg2_mesh_free(base);
    return d->n_src++;
}

int rg2__design_add_source_xform(rg2_design *d, int shape, int from, const double M[16], int i0, int j0, int wu,
                                 int wv, rg2_error *err)
{
    if (!grow((void **)&d->src, &d->cap_src, d->n_src + 1, sizeof *d->src)) {
        rg2__fail(err, RG2_ENOMEM, "design: out of memory for source meshes");
        return -1;
    }
    const rg2__source *F = &d->src[from];
    double *p = rg2__calloc((size_t)wu * (size_t)wv, 4 * sizeof *p);
    if (!p) {
        rg2__fail(err, RG2_ENOMEM, "design: out of memory for a transformed source of %d x %d points", wu, wv);
        return -1;
    }
    for (int a = 0; a < wu; a++)
        for (int b = 0; b < wv; b++) {
            int i = F->closed[0] ? (i0 + a) % F->nu : i0 + a, j = F->closed[1] ? (j0 + b) % F->nv : j0 + b;
            const double *q = rg2__source_at(F, i, j);
            double *o = p + ((size_t)a * (size_t)wv + (size_t)b) * 4;
            if (q) {
                memcpy(o, q, 4 * sizeof *o);
                rg2__xform_apply(M, o); /* as rg2_mesh_transform does to the mesh's copy of the point */
            } else /* (not stored by `from`, so no mesh point comes from there) */
                o[0] = o[1] = o[2] = o[3] = NAN;
        }
    rg2__source *s = &d->src[d->n_src];
    *s = *F; /* shape, grid size and the shared stencils */
    s->shape = shape;
    s->i0 = i0;
    s->j0 = j0;
    s->wu = wu;
    s->wv = wv;
    s->p = p;
    s->own_st = 0;
    return d->n_src++;
}

rg2__dmesh *rg2__design_new_mesh(rg2_design *d, rg2_error *err)
{
    if (!grow((void **)&d->mesh, &d->cap_mesh, d->n_mesh + 1, sizeof *d->mesh)) {
        rg2__fail(err, RG2_ENOMEM, "design: out of memory for meshes");
        return NULL;
    }
    memset(&d->mesh[d->n_mesh], 0, sizeof d->mesh[0]);
    return &d->mesh[d->n_mesh];
}

int rg2__design_commit_mesh(rg2_design *d, rg2_error *err)
{
    rg2__dmesh *m = &d->mesh[d->n_mesh];
    if (m->name && names_add(&d->mesh_index, m->name, d->n_mesh)) {
        rg2__fail(err, RG2_ENOMEM, "design: out of memory for meshes");
        return -1;
    }
    d->mesh_points += (size_t)m->m.nu * (size_t)m->m.nv;
    d->n_mesh++;
    return 0;
}

int rg2__design_find_mesh(const rg2_design *d, const char *name)
{
    return names_find(&d->mesh_index, name);
}

int rg2__design_find_shape(const rg2_design *d, const char *label)
{
    return names_find(&d->shape_index, label);
}

void rg2_design_free(rg2_design *d)
{
    if (!d)
        return;
    for (int k = 0; k < d->n_shapes; k++)
        free(d->labels[k]);
    free(d->labels);
    free(d->shapes);
    for (int k = 0; k < d->n_src; k++) {
        free(d->src[k].p);
        if (d->src[k].own_st) {
            rg2__stencil_free(&d->src[k].st[0]);
            rg2__stencil_free(&d->src[k].st[1]);
        }
    }
    free(d->src);
    for (int k = 0; k < d->n_mesh; k++)
        rg2__dmesh_free(&d->mesh[k]);
    free(d->mesh);
    if (d->surf)
        for (int k = 0; k < d->n_out; k++)
            rg2_surface_free(&d->surf[k]);
    free(d->surf);
    free(d->out);
    free(d->name);
    for (int k = 0; k < d->n_notes; k++)
        free(d->notes[k]);
    free(d->notes);
    names_free(&d->mesh_index);
    names_free(&d->shape_index);
    free(d);
}

/* ------------------------------------------------------------------------------------- */
/* provenance tags */

/* Stencil segment of the source direction whose leg is L (the segment from point L to L+1),
 * or -1 if the source does not produce it. */
static int source_segment(const rg2__stencil *st, int L)
{
    if (st->closed)
        return rg2__wrap(L, st->n, 1);
    return (L >= 1 && L <= st->n - 3) ? L - 1 : -1;
}

/* Stencil segment ka of a equals segment kb of b (to 1e-14); flip: b runs the other way, so
 * coefficient r over point a corresponds to b's coefficient 3 - r over point 3 - a. */
static int stencil_equal(const rg2__stencil *a, int ka, const rg2__stencil *b, int kb, int flip)
{
    const double tol = 1e-14;
    if (fabs(a->w[ka] - b->w[kb]) > tol * fabs(b->w[kb]))
        return 0;
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            if (fabs(a->c[ka][r][c] - b->c[kb][flip ? 3 - r : r][flip ? 3 - c : c]) > tol)
                return 0;
    return 1;
}

/*
 * METHOD: patch (k, l) is the image of the 4x4 control block starting at p^{i-1, j-1}
 * (i, j its legs) under the u and v stencils of the mesh. It is a piece of shape s exactly
 * when (1) the 16 points are, bit for bit, a consecutive 4x4 block of one source mesh of s,
 * in any of the 8 orientations (transposed or not, each direction forwards or reversed), and
 * (2) the u and v stencils of the patch agree (to 1e-14) with the source's stencils of the
 * corresponding segments (read backwards for a reversed direction), which must be segments the
 * source itself produces. Then the patch equals the source's own patch up to rounding and
 * reparameterization. This is the dependency rule of MATH.md section 6 (points p^{i-1..i+2},
 * the scalars of junctions i-1..i+2 and legs i-2..i+2 enter only through the stencil), checked
 * on values, so it also accepts seams whose scalars were re-solved to keep the stencils.
 */
int rg2__patch_tag(const rg2_design *d, const rg2__dmesh *dm, const rg2__stencil st[2], int k, int l)
{
    const rg2_mesh *m = &dm->m;
    int iu = st[0].first[k], jv = st[1].first[l];
    const rg2__pprov *p0 =
        rg2__dmesh_pp(dm, rg2__wrap(iu, m->nu, m->su.closed), rg2__wrap(jv, m->nv, m->sv.closed));
    if (p0->src < 0)
        return -1;
    const rg2__source *S = &d->src[p0->src];
    for (int o = 0; o < 8; o++) {
        int tr = o & 1, ru = (o >> 1) & 1, rv = (o >> 2) & 1, ok = 1;
        for (int a = 0; a < 4 && ok; a++)
            for (int b = 0; b < 4 && ok; b++) {
                int mi = rg2__wrap(iu + a, m->nu, m->su.closed), mj = rg2__wrap(jv + b, m->nv, m->sv.closed);
                const rg2__pprov *q = rg2__dmesh_pp(dm, mi, mj);
                int du = ru ? -a : a, dv = rv ? -b : b;
                int ei = p0->i + (tr ? dv : du), ej = p0->j + (tr ? du : dv);
                if (S->closed[0])
                    ei = rg2__wrap(ei, S->nu, 1);
                if (S->closed[1])
                    ej = rg2__wrap(ej, S->nv, 1);
                const double *sp = ei < 0 || ej < 0 || ei >= S->nu || ej >= S->nv ? NULL : rg2__source_at(S, ei, ej);
                if (!sp || q->src != p0->src || q->i != ei || q->j != ej ||
                    memcmp(rg2_mesh_at(m, mi, mj), sp, 4 * sizeof(double)))
                    ok = 0;
            }
        if (!ok)
            continue;
        /* mesh u follows source u (tr = 0) or source v (tr = 1); a reversed direction's first
         * point is the source's last of the four, so the source leg is 2 before it */
        int bu = tr ? p0->j : p0->i, bv = tr ? p0->i : p0->j;
        int su = source_segment(&S->st[tr], ru ? bu - 2 : bu + 1);
        int sv = source_segment(&S->st[1 - tr], rv ? bv - 2 : bv + 1);
        if (su < 0 || sv < 0)
            continue;
        if (stencil_equal(&st[0], k, &S->st[tr], su, ru) && stencil_equal(&st[1], l, &S->st[1 - tr], sv, rv))
            return S->shape;
    }
    return -1;
}

rg2_status rg2_number_check(double x, const char *what, rg2_error *err)
{
    if (!what)
        what = "number";
    if (!rg2__finite(x))
        return rg2__fail(err, RG2_ENONFINITE, "%s: number is not finite", what);
    double a = fabs(x);
    if (a > RG2_DESIGN_MAX_ABS || (a > 0.0 && a < RG2_DESIGN_MIN_ABS))
        return rg2__fail(err, RG2_EDOMAIN,
                         "%s: number %g is outside the supported range (0 or a magnitude from %g to %g)",
                         what, x, RG2_DESIGN_MIN_ABS, RG2_DESIGN_MAX_ABS);
    rg2__ok(err);
    return RG2_OK;
}

/* The supported numeric range (internal.h): coordinates and size of a mesh's design points. */
rg2_status rg2_mesh_check_range(const rg2_mesh *m, const char *what, rg2_error *err)
{
    if (!what)
        what = "mesh";
    rg2__box box;
    rg2__box_init(&box);
    size_t with = 0;
    for (size_t k = 0; k < (size_t)m->nu * (size_t)m->nv; k++)
        if (m->p[4 * k + 3] != 0.0) { /* W = 0: a point at infinity (a hyperboloid's mirrored data
                                         knot at v = 0), no coordinates */
            rg2__box_add(&box, &m->p[4 * k], m->p[4 * k + 3]);
            with++;
        }
    if (!with) /* (the box of no point read "coordinates up to inf, size inf": rg2_mesh_init's mesh) */
        return rg2__fail(err, RG2_EDOMAIN,
                         "%s: none of the %d x %d control points has a weight p_4 != 0: no design points to measure "
                         "(every point at infinity; rg2_mesh_init leaves all four values 0)",
                         what, m->nu, m->nv);
    double big, diag;
    rg2__box_extent(&box, &big, &diag);
    if (!(big <= RG2_DESIGN_MAX_COORD) || !(diag >= RG2_DESIGN_MIN_SIZE))
        return rg2__fail(err, RG2_EDOMAIN,
                         "%s: coordinates up to %g, size %g: outside the supported range "
                         "(coordinates up to %g, size at least %g)",
                         what, big, diag, RG2_DESIGN_MAX_COORD, RG2_DESIGN_MIN_SIZE);
    if (diag < 1e-12 * big) /* (a part of size 1e-20 at x = 1 was built, its points rounded together) */
        return rg2__fail(err, RG2_EDOMAIN,
                         "%s: size %g at coordinates up to %g: below 1e-12 of its distance from the origin, so "
                         "the rounding of its coordinates (about %.2g) takes its shape apart; place it nearer the "
                         "origin or make it larger",
                         what, diag, big, big * 2.220446049250313e-16);
    rg2__ok(err);
    return RG2_OK;
}

/* The output meshes are built here, after the whole file is read: their messages name the mesh
 * entry by its path (meshes.<name>), after the file name. */
static rg2_status mesh_range(const rg2_mesh *m, const char *file, const char *name, rg2_error *err)
{
    char what[300];
    if (snprintf(what, sizeof what, "%s: meshes.%s", file, name) >= (int)sizeof what)
        rg2__utf8_cut(what); /* (long names: cut between UTF-8 characters) */
    return rg2_mesh_check_range(m, what, err);
}

/* A note for an output surface with a patch weight <= 0 (an exact shape over coarse arcs, or a
 * mesh made from one): it builds, and pictures and the mesh formats take it, but STEP and IGES
 * export refuse it; the note says so before a write does. A merge into this very mesh whose
 * seam note already named a weight <= 0 (rg2__merge_overlap_notes) gets no second note. */
static rg2_status weight_note(rg2_design *d, const rg2__dmesh *dm, const rg2_surface *s, rg2_error *err)
{
    rg2_weight_report rep;
    rg2_surface_weight_report(s, &rep);
    if (!(rep.flags & RG2_SHAPE_WARN_WEIGHT))
        return RG2_OK;
    if (dm->weight_noted) /* its merge named the weight <= 0 at its seam, and the remedy */
        return RG2_OK;
    char msg[700];
    snprintf(msg, sizeof msg,
             "%s: meshes.%s: %d of its %d patches %s a homogeneous weight <= 0 (the smallest %g, at patch "
             "(%d, %d)): STEP and IGES export refuse it (pictures and the mesh formats do not); use more arcs or "
             "knots there (docs/shapes.md \"Homogeneous weights\")",
             d->name, dm->name, rep.n_nonpositive, s->nu * s->nv, rep.n_nonpositive == 1 ? "has" : "have",
             rep.min_weight, rep.patch_i, rep.patch_j);
    return rg2__design_add_note(d, msg, err);
}

rg2_status rg2__design_build(rg2_design *d, rg2_error *err)
{
    size_t patches = 0;
    for (int o = 0; o < d->n_out; o++) {
        const rg2_mesh *m = &d->mesh[d->out[o]].m;
        patches += (size_t)rg2_scalars_num_segments(&m->su) * (size_t)rg2_scalars_num_segments(&m->sv);
    }
    if (patches > RG2_DESIGN_MAX_PATCHES && d->out_key)
        return rg2__fail(err, RG2_ELIMIT, "%s: output: the outputs have %zu patches, more than the limit of %d",
                         d->name, patches, RG2_DESIGN_MAX_PATCHES);
    if (patches > RG2_DESIGN_MAX_PATCHES) /* no "output": the last mesh */
        return rg2__fail(err, RG2_ELIMIT,
                         "%s: meshes.%s: the output (the last mesh) has %zu patches, more than the limit of %d",
                         d->name, d->mesh[d->out[0]].name, patches, RG2_DESIGN_MAX_PATCHES);
    d->surf = rg2__calloc((size_t)d->n_out, sizeof *d->surf);
    if (!d->surf)
        return rg2__fail(err, RG2_ENOMEM, "design: out of memory");
    for (int o = 0; o < d->n_out; o++) {
        const rg2__dmesh *dm = &d->mesh[d->out[o]];
        rg2_surface *s = &d->surf[o];
        rg2_status st = mesh_range(&dm->m, d->name, dm->name, err);
        if (st)
            return st;
        if (dm->capped) {
            if ((st = rg2__design_build_capped(d, dm, s, err)))
                return st;
            rg2__surface_normalize_weights(s); /* (rg2_surface_build does it for the uncapped) */
            if ((st = weight_note(d, dm, s, err)))
                return st;
            /* (no NURBS pole side set: a cap's body is closed in u with the legs and junctions of a
             * circle, 1/3 < w < 1 (cap.c, ucircle_make), so a pole side could only be a v end, along u,
             * whose legs are the NURBS's polynomial-mode w = 1, which rg2_cap_build refuses, unless an
             * edit along the pole line made them a circle's: that side stays as the construction makes it) */
            continue; /* tagged by the caps module */
        }
        if ((st = rg2_surface_build(&dm->m, s, err))) {
            rg2_error e = *err;
            return rg2__fail(err, st, "%s: meshes.%s: %s", d->name, dm->name, e.msg);
        }
        rg2__surface_set_poles(s, dm->poles, dm->pole); /* a NURBS's pole: its point, exactly */
        rg2__stencil sten[2];
        if ((st = rg2__stencil_make(&dm->m.su, &sten[0], err)))
            return st;
        if ((st = rg2__stencil_make(&dm->m.sv, &sten[1], err))) {
            rg2__stencil_free(&sten[0]);
            return st;
        }
        s->tag = rg2__calloc((size_t)s->nu * (size_t)s->nv, sizeof(int));
        if (!s->tag) {
            rg2__stencil_free(&sten[0]);
            rg2__stencil_free(&sten[1]);
            return rg2__fail(err, RG2_ENOMEM, "design: out of memory for tags");
        }
        for (int k = 0; k < s->nu; k++)
            for (int l = 0; l < s->nv; l++)
                s->tag[k * s->nv + l] = rg2__patch_tag(d, dm, sten, k, l);
        rg2__stencil_free(&sten[0]);
        rg2__stencil_free(&sten[1]);
        if ((st = weight_note(d, dm, s, err)))
            return st;
    }
    return RG2_OK;
}

/* ------------------------------------------------------------------------------------- */
/* public entry points */

rg2_status rg2_design_parse(const char *json, size_t len, const char *name, rg2_design **out,
                            rg2_error *err)
{
    if (!out)
        return rg2__fail(err, RG2_EINVAL, "design: NULL output pointer");
    *out = NULL;
    if (!name)
        name = "design";
    if (!json)
        return rg2__fail(err, RG2_EINVAL, "%s: no text", name);
    if (len > RG2_TEXT_MAX_BYTES) /* (as rg2_design_load: also keeps len + 1 from wrapping) */
        return rg2__fail(err, RG2_ELIMIT, "%s: %zu bytes of design text, more than the limit of %u", name, len,
                         RG2_TEXT_MAX_BYTES);
    rg2_design *d = rg2__calloc(1, sizeof *d);
    if (!d)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory", name);
    d->name = dupstr(name);
    rg2_error local;
    if (!err)
        err = &local;
    /* the notes' and messages' numbers in the "C" locale whatever the host's (rg2__fail's own) */
    void *loc = rg2__c_numeric_begin();
    rg2_status st = d->name ? rg2__design_parse_json(d, json, len, name, err)
                            : rg2__fail(err, RG2_ENOMEM, "%s: out of memory", name);
    if (!st)
        st = rg2__design_build(d, err);
    rg2__c_numeric_end(loc);
    if (st) {
        rg2_design_free(d);
        return st;
    }
    rg2__ok(err);
    *out = d;
    return RG2_OK;
}

rg2_status rg2_design_load(const char *path, rg2_design **out, rg2_error *err)
{
    if (!out) /* (as rg2_design_parse) */
        return rg2__fail(err, RG2_EINVAL, "design: NULL output pointer");
    *out = NULL;
    if (!path)
        return rg2__fail(err, RG2_EINVAL, "design: no file name (NULL path)");
    char *buf;
    size_t len;
    rg2_status st = rg2_read_text(path, &buf, &len, err);
    if (st)
        return st;
    st = rg2_design_parse(buf, len, path, out, err);
    free(buf);
    return st;
}

int rg2_design_num_surfaces(const rg2_design *d) { return d ? d->n_out : 0; }

const rg2_surface *rg2_design_surface(const rg2_design *d, int k)
{
    return (d && k >= 0 && k < d->n_out) ? &d->surf[k] : NULL;
}

const rg2_mesh *rg2_design_mesh(const rg2_design *d, int k)
{
    return (d && k >= 0 && k < d->n_out) ? &d->mesh[d->out[k]].m : NULL;
}

int rg2_design_cap(const rg2_design *d, int k, rg2_cap_opts *opts)
{
    const rg2__dmesh *dm = (d && k >= 0 && k < d->n_out) ? &d->mesh[d->out[k]] : NULL;
    if (!dm || !dm->capped)
        return 0;
    if (opts)
        *opts = dm->cap;
    return 1;
}

const char *rg2_design_mesh_name(const rg2_design *d, int k)
{
    return (d && k >= 0 && k < d->n_out) ? d->mesh[d->out[k]].name : NULL;
}

int rg2_design_num_shapes(const rg2_design *d) { return d ? d->n_shapes : 0; }

rg2_status rg2__design_add_note(rg2_design *d, const char *text, rg2_error *err)
{
    char **grown = realloc(d->notes, ((size_t)d->n_notes + 1) * sizeof *grown);
    if (!grown)
        return rg2__fail(err, RG2_ENOMEM, "design notes: out of memory");
    d->notes = grown;
    if (!(d->notes[d->n_notes] = dupstr(text)))
        return rg2__fail(err, RG2_ENOMEM, "design notes: out of memory");
    d->n_notes++;
    return RG2_OK;
}

int rg2_design_num_notes(const rg2_design *d) { return d ? d->n_notes : 0; }

const char *rg2_design_note(const rg2_design *d, int k)
{
    return (d && k >= 0 && k < d->n_notes) ? d->notes[k] : NULL;
}

const rg2_shape *rg2_design_shape(const rg2_design *d, int k)
{
    return (d && k >= 0 && k < d->n_shapes) ? &d->shapes[k] : NULL;
}

const char *rg2_design_shape_label(const rg2_design *d, int k)
{
    return (d && k >= 0 && k < d->n_shapes) ? d->labels[k] : NULL;
}

int rg2_design_point_shape(const rg2_design *d, int k, int i, int j)
{
    if (!d || k < 0 || k >= d->n_out)
        return -1;
    const rg2__dmesh *dm = &d->mesh[d->out[k]];
    if (i < 0 || i >= dm->m.nu || j < 0 || j >= dm->m.nv)
        return -1;
    int s = rg2__dmesh_pp(dm, i, j)->src;
    return s < 0 ? -1 : d->src[s].shape;
}

/* ------------------------------------------------------------------------------------- */
/* the control mesh as JSON (rg2 mesh) */

/* The mesh file is written as it goes, with the bytes cJSON_Print gave for the tree of cJSON items
 * this used to build first (objects a key per line, indented by tabs, "key":<tab>value; arrays on
 * one line, ", " between items; numbers as rg2__json_double's text, integers as %d, a non-finite
 * number as null; strings escaped as cJSON escapes them). The tree (about 6 items a control point)
 * and the whole text were in memory at once: rg2 mesh of a 1000 x 1000 NURBS peaked at 1239 MB
 * for a 33 MB file, 380 MB above the design's own 859 MB, and took 4.4 s, now 3.0 s. */
typedef struct {
    FILE *f;
    int depth;   /* cJSON's print depth: + 1 inside each object and array */
    int first;   /* nothing yet in the innermost object or array */
} jw;

static void jw_string(jw *w, const char *s)
{
    putc('"', w->f);
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        switch (*c) {
        case '"': fputs("\\\"", w->f); break;
        case '\\': fputs("\\\\", w->f); break;
        case '\b': fputs("\\b", w->f); break;
        case '\f': fputs("\\f", w->f); break;
        case '\n': fputs("\\n", w->f); break;
        case '\r': fputs("\\r", w->f); break;
        case '\t': fputs("\\t", w->f); break;
        default:
            if (*c < 32)
                fprintf(w->f, "\\u%04x", *c);
            else
                putc(*c, w->f);
        }
    }
    putc('"', w->f);
}

/* Before an item of the innermost object (key) or array (key NULL). */
static void jw_item(jw *w, const char *key)
{
    if (key) {
        fputs(w->first ? "" : ",\n", w->f);
        for (int k = 0; k < w->depth; k++)
            putc('\t', w->f);
        jw_string(w, key);
        fputs(":\t", w->f);
    } else if (!w->first)
        fputs(", ", w->f);
    w->first = 0;
}

static void jw_open(jw *w, const char *key, char bracket)
{
    jw_item(w, key);
    putc(bracket, w->f);
    if (bracket == '{')
        putc('\n', w->f);
    w->depth++;
    w->first = 1;
}

static void jw_close(jw *w, char bracket)
{
    if (bracket == '}') {
        if (!w->first)
            putc('\n', w->f);
        for (int k = 0; k < w->depth - 1; k++)
            putc('\t', w->f);
    }
    putc(bracket, w->f);
    w->depth--;
    w->first = 0;
}

static void jw_double(jw *w, const char *key, double x)
{
    jw_item(w, key);
    if (!isfinite(x)) {
        fputs("null", w->f);
        return;
    }
    char buf[40];
    rg2__json_number_text(x, buf);
    fputs(buf, w->f);
}

static void jw_doubles(jw *w, const char *key, const double *x, int n)
{
    jw_open(w, key, '[');
    for (int i = 0; i < n; i++)
        jw_double(w, NULL, x[i]);
    jw_close(w, ']');
}

static void jw_int(jw *w, const char *key, int x)
{
    jw_item(w, key);
    fprintf(w->f, "%d", x);
}

static void jw_ints(jw *w, const char *key, const int *v, int n)
{
    jw_open(w, key, '[');
    for (int i = 0; i < n; i++)
        jw_int(w, NULL, v[i]);
    jw_close(w, ']');
}

static void jw_text(jw *w, const char *key, const char *s)
{
    jw_item(w, key);
    jw_string(w, s);
}

static void scalars_json(jw *w, const char *key, const rg2_scalars *s, const int *leg, const int *jun)
{
    jw_open(w, key, '{');
    jw_item(w, "closed");
    fputs(s->closed ? "true" : "false", w->f);
    jw_int(w, "first_leg", s->closed ? 0 : -1);
    jw_doubles(w, "w", s->w, rg2_scalars_num_w(s));
    jw_doubles(w, "b", s->b, s->n);
    jw_doubles(w, "g", s->g, s->n);
    jw_ints(w, "w_shape", leg, rg2_scalars_num_w(s));
    jw_ints(w, "junction_shape", jun, s->n);
    jw_close(w, '}');
}

static void write_mesh_json(const rg2_design *d, const char *name, FILE *f)
{
    jw W = {f, 0, 1}, *w = &W;
    jw_open(w, NULL, '{');
    jw_text(w, "format", "rg2 control mesh 1");
    jw_text(w, "design", name);
    jw_open(w, "shapes", '[');
    for (int k = 0; k < d->n_shapes; k++) {
        const rg2_shape_desc *desc = rg2_shape_describe(d->shapes[k].kind);
        jw_open(w, NULL, '{');
        jw_text(w, "label", d->labels[k]);
        jw_text(w, "kind", desc ? desc->name : "?");
        if (desc)
            for (int p = 0; p < desc->n_params; p++)
                jw_double(w, desc->param_names[p], d->shapes[k].param[p]);
        jw_doubles(w, "matrix", d->shapes[k].xform, 16);
        jw_close(w, '}');
    }
    jw_close(w, ']');
    jw_open(w, "meshes", '[');
    for (int o = 0; o < d->n_out; o++) {
        const rg2__dmesh *dm = &d->mesh[d->out[o]];
        const rg2_mesh *m = &dm->m;
        jw_open(w, NULL, '{');
        jw_text(w, "name", dm->name);
        jw_int(w, "nu", m->nu);
        jw_int(w, "nv", m->nv);
        jw_open(w, "d", '[');
        for (int i = 0; i < m->nu; i++) {
            jw_open(w, NULL, '[');
            for (int j = 0; j < m->nv; j++) {
                const double *p = rg2_mesh_at(m, i, j);
                double x[3] = {p[0] / p[3], p[1] / p[3], p[2] / p[3]};
                jw_doubles(w, NULL, x, 3);
            }
            jw_close(w, ']');
        }
        jw_close(w, ']');
        jw_open(w, "W", '[');
        for (int i = 0; i < m->nu; i++) {
            jw_open(w, NULL, '[');
            for (int j = 0; j < m->nv; j++)
                jw_double(w, NULL, rg2_mesh_at(m, i, j)[3]);
            jw_close(w, ']');
        }
        jw_close(w, ']');
        jw_open(w, "shape", '[');
        for (int i = 0; i < m->nu; i++) {
            jw_open(w, NULL, '[');
            for (int j = 0; j < m->nv; j++) {
                int sp = rg2__dmesh_pp(dm, i, j)->src;
                jw_int(w, NULL, sp < 0 ? -1 : d->src[sp].shape);
            }
            jw_close(w, ']');
        }
        jw_close(w, ']');
        scalars_json(w, "u", &m->su, dm->leg[0], dm->jun[0]);
        scalars_json(w, "v", &m->sv, dm->leg[1], dm->jun[1]);
        const rg2_surface *s = &d->surf[o];
        jw_ints(w, "patch_shape", s->tag, s->nu * s->nv);
        jw_close(w, '}');
    }
    jw_close(w, ']');
    jw_close(w, '}');
    putc('\n', f);
}

rg2_status rg2_design_write_mesh(const rg2_design *d, const char *path, rg2_error *err)
{
    if (!d) /* (as rg2_design_load's NULL path and output; the accessors return 0 / NULL) */
        return rg2__fail(err, RG2_EINVAL, "design: no design to write (NULL design)");
    if (!path || !*path)
        return rg2__fail(err, RG2_EINVAL, "%s: no output path (%s path)", d->name, path ? "empty" : "NULL");
    /* the design's name (its file's path) as UTF-8 text: a byte that is not (a Latin-1 file name)
     * becomes '?', so the mesh file stays JSON (the design text itself is UTF-8, checked) */
    char *name = rg2__text_clean(d->name, 0);
    if (!name)
        return rg2__fail(err, RG2_ENOMEM, "%s: out of memory", path);
    rg2__out out;
    rg2_status st = rg2__out_open(&out, path, err);
    if (st == RG2_OK) {
        void *loc = rg2__c_numeric_begin();
        write_mesh_json(d, name, out.f); /* a failed write sets the stream's error flag, which the close reports */
        rg2__c_numeric_end(loc);
        st = rg2__out_close(&out, RG2_OK, err);
    }
    free(name);
    if (!st)
        rg2__ok(err);
    return st;
}
