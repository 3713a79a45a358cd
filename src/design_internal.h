/* design_internal.h -- private structures of the design module (design.c, design_ops.c,
 * design_parse.c); never installed. */
#ifndef RG2_DESIGN_INTERNAL_H
#define RG2_DESIGN_INTERNAL_H

#include "internal.h"

/* Where a control point came from: source mesh `src` (index into rg2_design.src) at
 * its point (i, j); src = -1 for a point that was edited or blended. */
typedef struct {
    int src, i, j;
} rg2__pprov;

/* A source: the control mesh of one shape over one pair of partitions, as the shape module
 * produced it (or a transformed copy). Patches whose 4x4 control block is a consecutive block
 * of a source and whose construction stencils agree with the source's are pieces of its shape.
 * The source is an nu x nv grid (closed[d]: direction d wraps); of its points it stores the
 * window of wu x wv points starting at (i0, j0) (wrapping in a closed direction): a shape's
 * mesh stores them all, a transformed copy only those the transformed mesh refers to (a chain
 * of transforms of a small cut of a big shape mesh copied the whole big mesh each time). */
typedef struct {
    int shape;          /* index into rg2_design.shapes */
    int nu, nv, closed[2];
    int i0, j0, wu, wv; /* the stored window */
    double *p;          /* wu * wv homogeneous 4-tuples, (a, b) at p[(a * wv + b) * 4] */
    rg2__stencil st[2]; /* u and v stencils of the source's scalars */
    int own_st;         /* st allocated here (else shared with the source it was transformed from) */
} rg2__source;

/* Point (i, j) (0 <= i < nu, 0 <= j < nv) of a source, or NULL outside its stored window. */
static inline double *rg2__source_at(const rg2__source *S, int i, int j)
{
    int a = i - S->i0, b = j - S->j0;
    if (S->closed[0] && a < 0)
        a += S->nu;
    if (S->closed[1] && b < 0)
        b += S->nv;
    if (a < 0 || a >= S->wu || b < 0 || b >= S->wv)
        return NULL;
    return S->p + ((size_t)a * (size_t)S->wv + (size_t)b) * 4;
}

/* A design mesh: a control mesh with provenance. Scalar provenance (shape index or -1) is
 * kept per stored weight (leg) and per junction of each direction, for reporting. */
typedef struct {
    char *name;
    rg2_mesh m;
    rg2__pprov *pp;    /* nu * nv */
    int *leg[2];       /* rg2_scalars_num_w entries per direction (u = 0, v = 1) */
    int *jun[2];       /* n entries per direction */
    int capped;        /* built with polar caps (design_poles.c; an output property, not copied) */
    rg2_cap_opts cap;
    int cap_src;       /* the capped mesh (index into rg2_design.mesh), for messages */
    int uncapped_of;   /* 1 + the capped mesh an uncapped mesh was made from (an operation uses a
                          capped input uncapped), 0 none: an uncapped output made so gets a note */
    int weight_noted;  /* the merge that made this mesh noted a weight <= 0 at a seam
                          (rg2__merge_overlap_notes): its output surface gets no second note */
    unsigned poles;    /* the sides (bits as rg2__nurbs_pole_ends: 0 v = 0, 1 u = 1, 2 v = 1, 3 u = 0)
                          that are a NURBS's clamped end whose control line is one point, pole[k]:
                          the output build makes those patch sides that point. Kept by cut,
                          transpose, reverse, roll and transform, by an edit, merge, morph or cap
                          whose output builds that side from the same values across it, the scalars
                          along it free (rg2__poles_keep_same), and by a merge along the side whose
                          parts all have that pole (the same point and scalars across) */
    double pole[4][3];
} rg2__dmesh;

/* A hash index of names (mesh names, shape labels) to their registry index; the keys are the
 * registries' own strings. The first name entered wins (the registries' linear search did so). */
typedef struct {
    size_t cap, n; /* cap: 0 or a power of two */
    const char **key;
    int *idx;
} rg2__names;

struct rg2_design {
    char *name;
    int n_shapes, cap_shapes;
    rg2_shape *shapes;
    char **labels;
    int n_src, cap_src;
    rg2__source *src;
    int n_mesh, cap_mesh;
    rg2__dmesh *mesh;
    int n_out;
    int *out;             /* indices into mesh */
    int out_key;          /* the file lists its outputs ("output"); else the last mesh is the output */
    rg2_surface *surf;    /* n_out built surfaces with tags */
    rg2__names mesh_index, shape_index; /* mesh names and shape labels (a design of many meshes
                                           looked each name up by a linear search: quadratic) */
    size_t mesh_points;   /* control points of all the meshes */
    int n_notes;          /* notes that are not errors (rg2_design_note) */
    char **notes;
};

/* Seam rules of merge (docs/design-format.md). */
typedef enum { RG2__SEAM_PRESERVE = 0, RG2__SEAM_PLAIN = 1 } rg2__seam_rule;

/* Design-mesh storage. */
rg2_status rg2__dmesh_alloc(rg2__dmesh *d, const char *name, int nu, int nv, int cu, int cv,
                            rg2_error *err);
void rg2__dmesh_free(rg2__dmesh *d);
static inline rg2__pprov *rg2__dmesh_pp(const rg2__dmesh *d, int i, int j)
{
    return d->pp + (size_t)i * (size_t)d->m.nv + (size_t)j;
}

/* Registries of the design (grow arrays); return the new index or -1 (err set). */
int rg2__design_add_shape(rg2_design *d, const rg2_shape *s, const char *label, rg2_error *err);
/* A shape's mesh as a source: takes base (its points and scalars) on success; the caller frees
 * it on failure. */
int rg2__design_add_source(rg2_design *d, int shape, rg2_mesh *base, rg2_error *err);
/* The copy of source `from` under the projective map M, as shape `shape`, storing only the points
 * a mesh refers to: those in the window of wu x wv points from (i0, j0) (wrapping in a closed
 * direction), which must lie in the stored window of `from`. Shares from's stencils. */
int rg2__design_add_source_xform(rg2_design *d, int shape, int from, const double M[16], int i0, int j0, int wu,
                                 int wv, rg2_error *err);
/* Append a copy of text to the design's notes (rg2_design_note); RG2_ENOMEM only. */
rg2_status rg2__design_add_note(rg2_design *d, const char *text, rg2_error *err);
rg2__dmesh *rg2__design_new_mesh(rg2_design *d, rg2_error *err);
/* Enter the new mesh d->mesh[d->n_mesh] (its name set) into the registry: index its name, count
 * its points, n_mesh + 1. Returns 0, or -1 out of memory (err set; nothing entered). */
int rg2__design_commit_mesh(rg2_design *d, rg2_error *err);
int rg2__design_find_mesh(const rg2_design *d, const char *name);
int rg2__design_find_shape(const rg2_design *d, const char *label);

/* Operations (design_ops.c). `what` is the JSON path of the mesh entry (e.g. "meshes.A"); every
 * message starts with it or with the path of the offending item below it ("meshes.A.merge[1]",
 * "shapes.t.matrix"), without the file name (the parser adds it). Each writes a new design mesh
 * into *out (allocated by the callee, name set by caller). */
/* vpath: the path of the v partition (its knots are checked against the shape's range). */
rg2_status rg2__op_shape(rg2_design *d, int shape, const rg2_partition *pu, const rg2_partition *pv,
                         rg2__dmesh *out, const char *what, const char *vpath, rg2_error *err);
/* Keep points first[dir]..last[dir] (inclusive; closed directions may wrap: last may exceed
 * n - 1). A direction with first = -1 is kept as is; what[dir] is the path of its range. */
rg2_status rg2__op_cut(const rg2__dmesh *in, const int first[2], const int last[2],
                       rg2__dmesh *out, const char *const what[2], rg2_error *err);
rg2_status rg2__op_transpose(const rg2__dmesh *in, rg2__dmesh *out, const char *what,
                             rg2_error *err);
/* Reverse direction dir: points in reverse order, legs reversed, junction scalars
 * b' = 1 / b, g' = g / b^3 (the same curves traversed backwards). */
/* The same mesh with a closed direction started `by` control points further (any sign): point,
 * junction and leg j take those of j + by (mod n); every patch is the same patch, relabelled.
 * RG2_EINCOMPATIBLE for an open direction (naming the mesh), RG2_ENOMEM. */
rg2_status rg2__op_roll(const rg2__dmesh *in, int dir, int by, rg2__dmesh *out, const char *what,
                        rg2_error *err);
rg2_status rg2__op_reverse(const rg2__dmesh *in, int dir, rg2__dmesh *out, const char *what,
                           rg2_error *err);
/* Notes (rg2_design_note) on the seams of a merge of in[0..n_in) along dir whose other direction
 * is closed: the closed rows a seam joins run opposite ways round, or meet turned about their axis
 * by more than a degree (the transitions twist or pinch the tube). RG2_ENOMEM only. */
rg2_status rg2__merge_twist_notes(rg2_design *d, const rg2__dmesh *const *in, int n_in, int dir, int closed,
                                  const char *what, rg2_error *err);
/* How far the seam between l's last line and r's first (lines along dir, the same count in the
 * other direction) runs back: the step from the centre of l's last line to the centre of r's
 * first, against the step between either part's two lines there, in units of that step's length
 * (the larger of the two; *by_left, nullable: whether l's step gave it). 0 where a part has fewer
 * than 2 lines or the step has no length (rg2_mesh_merge_overlap). */
double rg2__merge_seam_back(const rg2_mesh *l, const rg2_mesh *r, int dir, int *by_left);
/* Notes on the seams of a merge where the control lines run back by more than
 * RG2_MERGE_OVERLAP (rg2__merge_seam_back; the parts overlap: the transition patches bend
 * sharply or fold), or where a part has a weight <= 0 next to the seam (then *weight_noted = 1,
 * else 0). RG2_ENOMEM only. */
rg2_status rg2__merge_overlap_notes(rg2_design *d, const rg2__dmesh *const *in, int n_in, int dir, int closed,
                                    const char *what, int *weight_noted, rg2_error *err);
rg2_status rg2__op_merge(const rg2__dmesh *const *in, int n_in, int dir, int closed,
                         rg2__seam_rule rule, rg2__dmesh *out, const char *what, rg2_error *err);
rg2_status rg2__op_transform(rg2_design *d, const rg2__dmesh *in, const double M[16],
                             rg2__dmesh *out, const char *what, rg2_error *err);
rg2_status rg2__op_morph(const rg2__dmesh *a, const rg2__dmesh *b, double t, rg2__dmesh *out,
                         const char *what, rg2_error *err);
rg2_status rg2__dmesh_copy(const rg2__dmesh *in, rg2__dmesh *out, rg2_error *err);
/* Set the NURBS pole sides of `from` on out (its output) whose patches out builds from the same
 * values, bit for bit: the 4 lines, 5 legs and 4 junctions nearest that end and all the scalars of
 * the other direction (the patches along a side read nothing else), so the side is the same. */
void rg2__poles_keep_same(rg2__dmesh *out, const rg2__dmesh *from);
/* Edits in place on a copy. */
typedef enum { RG2__EDIT_MOVE, RG2__EDIT_TO, RG2__EDIT_WEIGHT } rg2__edit_kind;
rg2_status rg2__edit_point(rg2__dmesh *m, int i, int j, rg2__edit_kind kind, const double *v,
                           const char *what, rg2_error *err);
rg2_status rg2__edit_pole(rg2__dmesh *m, int end, rg2__edit_kind kind, const double *v, const char *what,
                          rg2_error *err);
/* rg2_mesh_net_normal with its messages prefixed by what (meshops.c). */
rg2_status rg2__net_normal(const rg2_mesh *m, int i, int j, double n[3], const char *what, rg2_error *err);
/* Scalars: which = 'w' (leg index i), 'b' or 'g' (junction index i). */
rg2_status rg2__edit_scalar(rg2__dmesh *m, int dir, char which, int i, double value,
                            const char *what, rg2_error *err);
/* The first junction of s whose K is not > 0 (or not finite), or -1. */
int rg2__bad_junction(const rg2_scalars *s);
/* rg2_scalars_check of direction dir of a design mesh, the message "<what>: <when><dir> junction i
 * has K = ..." (when: "" or e.g. "at t = 0.5, "); the core check's own message for anything else. */
rg2_status rg2__dir_check(const rg2_scalars *s, int dir, const char *what, const char *when, rg2_error *err);

/* Poles (design_poles.c, docs/poles.md): a polar configuration of a sphere, ellipsoid,
 * paraboloid or two-sheeted hyperboloid over interior knots v[0..m-1]; the Moebius map of a
 * reference sphere (shape index or -1 for the unit sphere; b for eq. 16, else the two poles in
 * world coordinates); a polar point edit (end 0 south, 1 north); a capped output surface. */
/* kpath: the path of the knots v. rg2__polar_kind: RG2_EINVAL naming what.polar unless the shape
 * has a polar configuration. */
rg2_status rg2__polar_kind(const rg2_design *d, int shape, const char *what, rg2_error *err);
rg2_status rg2__op_polar(rg2_design *d, int shape, const rg2_partition *pu, const double *v, int m,
                         rg2__dmesh *out, const char *what, const char *kpath, rg2_error *err);
rg2_status rg2__op_mobius(rg2_design *d, const rg2__dmesh *in, int shape, const double *b,
                          double poles[2][3], rg2__dmesh *out, const char *what, rg2_error *err);
/* Its messages name the cap's entry ("meshes.C.cap: mesh 'T' cannot be capped: ...",
 * "meshes.C.jet_weights: ..."), after the file name. */
rg2_status rg2__design_build_capped(const rg2_design *d, const rg2__dmesh *dm, rg2_surface *s,
                                    rg2_error *err);

/* Build the output surfaces with provenance tags (design.c). */
rg2_status rg2__design_build(rg2_design *d, rg2_error *err);
/* Tag of patch (k, l) of surface s built from dmesh dm: shape index or -1. */
int rg2__patch_tag(const rg2_design *d, const rg2__dmesh *dm, const rg2__stencil st[2], int k,
                   int l);

/* JSON design parser (design_parse.c). */
rg2_status rg2__design_parse_json(rg2_design *d, const char *json, size_t len, const char *name,
                                  rg2_error *err);

#endif
