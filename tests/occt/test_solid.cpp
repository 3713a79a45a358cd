// test_solid.cpp -- a CAD user's solid from rg2's STEP and IGES: every closed surface (closed in
// both directions, or closed in u with both v ends collapsed to poles) is written through the
// library, read back with OpenCASCADE's readers, its shell made a solid with
// BRepBuilderAPI_MakeSolid (which keeps the faces' orientations as read, so faces written
// inward show as a negative volume instead of being turned round, as ShapeFix_Solid would), and
// measured: no message from the reader's transfer (it would turn a face written inward round
// quietly), a valid solid with no free edge, volume > 0 as exported, and area, volume and
// centroid (BRepGProp, adaptive Gauss integration to a relative eps) against the exact shape
// (torus, sphere) or against an integration of rg2's own patches written here (Gauss-Legendre
// per patch, volume by the divergence theorem).
extern "C" {
#include "../export_fixtures.h"
}

#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeAnalysis_FreeBounds.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <gp_Pnt.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_Reader.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

// BRepGProp's adaptive Gauss integration is asked for this relative error; on the face-per-patch
// solids it reports estimates of 1e-16 .. 1.5e-13.
const double OCCT_EPS = 1e-10;
// Tolerances, relative (areas and volumes to the reference's value, centroids to the surface's
// size), against the worst measured (docs/export.md):
//  - TOL_EXACT, BRepGProp against the exact torus / sphere: 8.8e-16 measured; 1e-12 is above
//    OCCT's own largest estimate (1.5e-13), which is all it promises;
//  - TOL_GEOM, Gauss-Legendre over OCCT's faces (its geometry, our integrator) and over rg2's
//    patches, and our integration against the exact shapes and against itself with more
//    points: the same rational surfaces, 6.7e-16 measured;
//  - TOL_AREA, TOL_VOLUME, BRepGProp against rg2's patches where there is no exact shape:
//    6.4e-10 (area) and 2.4e-12 (volume, centroid) measured. OCCT's area integration stops
//    early on strongly rational transition patches: 3.9e-9 on one face of fig7_torus_cyclide,
//    with an error estimate of 0 at any eps, while Gauss-Legendre over the same OCCT face agrees
//    with rg2 to 1e-16 (and VolumePropertiesGK over the spans, 4.5 s for that solid, gives
//    rg2's volume to 6e-16);
//  - TOL_MESH, BRepGProp on the face-per-mesh layout's one B-spline face (C0 in its parameters
//    at the knots of multiplicity 3): 3.3e-5 measured on fig9's sphere, where OCCT estimates
//    7e-5 itself, though the face is rg2's surface to 2.8e-16 by the Gauss check.
const double TOL_EXACT = 1e-12, TOL_GEOM = 1e-14, TOL_AREA = 5e-9, TOL_VOLUME = 2e-11, TOL_MESH = 1e-4;

// Area, volume and volume centroid of a closed surface.
struct Props {
    double area = 0, volume = 0, c[3] = {0, 0, 0};
};

// Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n from the Chebyshev guesses).
void gauss_legendre(int n, std::vector<double> &x, std::vector<double> &w)
{
    x.assign(n, 0);
    w.assign(n, 0);
    for (int i = 0; i < n; i++) {
        double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = z;
            for (int k = 2; k <= n; k++) {
                double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (z * p1 - p0) / (z * z - 1);
            double dz = p1 / dp;
            z -= dz;
            if (std::fabs(dz) < 1e-16)
                break;
        }
        x[i] = 0.5 * (1 - z);
        w[i] = 1.0 / ((1 - z * z) * dp * dp); // 2 / ((1 - z^2) P'^2), halved for [0, 1]
    }
}

// Sums of one integration: dA = |N| du dv with N = Su x Sv the outward normal as oriented, the
// volume by the divergence theorem V = 1/3 int p . N, the centroid c_d = 1/(2V) int x_d^2 N_d.
struct Sums {
    long double area = 0, vol = 0, m[3] = {0, 0, 0};
    void add(double wt, const double p[3], const double su[3], const double sv[3], double sign)
    {
        double N[3] = {su[1] * sv[2] - su[2] * sv[1], su[2] * sv[0] - su[0] * sv[2], su[0] * sv[1] - su[1] * sv[0]};
        for (double &x : N)
            x *= sign;
        area += wt * std::sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
        vol += wt * (p[0] * N[0] + p[1] * N[1] + p[2] * N[2]) / 3;
        for (int d = 0; d < 3; d++)
            m[d] += wt * p[d] * p[d] * N[d] / 2;
    }
    Props props() const
    {
        Props P;
        P.area = (double)area;
        P.volume = (double)vol;
        for (int d = 0; d < 3; d++)
            P.c[d] = (double)(m[d] / vol);
        return P;
    }
};

// rg2's own patches (rg2_surface_eval), n x n Gauss-Legendre points per patch. The integrands
// are smooth (positive denominators), poles included, where N -> 0 smoothly.
Props own_props(const rg2_surface *s, int n)
{
    std::vector<double> x, w;
    gauss_legendre(n, x, w);
    Sums S;
    for (int i = 0; i < s->nu; i++)
        for (int j = 0; j < s->nv; j++)
            for (int a = 0; a < n; a++)
                for (int b = 0; b < n; b++) {
                    rg2_eval e;
                    rg2_surface_eval(s, i, j, x[a], x[b], 1, &e);
                    S.add(w[a] * w[b], e.p, e.su, e.sv, 1.0);
                }
    return S.props();
}

// The same integration over OCCT's faces of the solid (its surfaces, its face orientations,
// its parameter bounds): whether OCCT holds our geometry, apart from how BRepGProp integrates.
Props occt_gauss(const TopoDS_Shape &solid, int n)
{
    std::vector<double> x, w;
    gauss_legendre(n, x, w);
    Sums S;
    for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
        TopoDS_Face F = TopoDS::Face(ex.Current());
        Handle(Geom_Surface) G = BRep_Tool::Surface(F);
        double u1, u2, v1, v2, sign = F.Orientation() == TopAbs_REVERSED ? -1 : 1;
        BRepTools::UVBounds(F, u1, u2, v1, v2);
        // Gauss per knot span (the face-per-mesh surface is only C0 in its parameters there)
        std::vector<double> ku{u1, u2}, kv{v1, v2};
        Handle(Geom_BSplineSurface) B = Handle(Geom_BSplineSurface)::DownCast(G);
        if (!B.IsNull()) {
            ku.assign(1, u1);
            kv.assign(1, v1);
            for (int k = 1; k <= B->NbUKnots(); k++)
                if (B->UKnot(k) > ku.back() + 1e-12 && B->UKnot(k) < u2 - 1e-12)
                    ku.push_back(B->UKnot(k));
            for (int k = 1; k <= B->NbVKnots(); k++)
                if (B->VKnot(k) > kv.back() + 1e-12 && B->VKnot(k) < v2 - 1e-12)
                    kv.push_back(B->VKnot(k));
            ku.push_back(u2);
            kv.push_back(v2);
        }
        for (size_t i = 0; i + 1 < ku.size(); i++)
            for (size_t j = 0; j + 1 < kv.size(); j++) {
                double a0 = ku[i], da = ku[i + 1] - ku[i], b0 = kv[j], db = kv[j + 1] - kv[j];
                for (int a = 0; a < n; a++)
                    for (int b = 0; b < n; b++) {
                        gp_Pnt q;
                        gp_Vec du, dv;
                        G->D1(a0 + da * x[a], b0 + db * x[b], q, du, dv);
                        double p[3] = {q.X(), q.Y(), q.Z()}, su[3] = {du.X(), du.Y(), du.Z()},
                               sv[3] = {dv.X(), dv.Y(), dv.Z()};
                        S.add(w[a] * w[b] * da * db, p, su, sv, sign);
                    }
            }
    }
    return S.props();
}

double rel(double a, double b) { return std::fabs(a - b) / std::fabs(b); }

double cdist(const double a[3], const double b[3])
{
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// worst relative differences of area, volume and centroid
struct Diff {
    double area = 0, volume = 0, centre = 0;
    void max_with(const Diff &d)
    {
        area = std::max(area, d.area);
        volume = std::max(volume, d.volume);
        centre = std::max(centre, d.centre);
    }
};

Diff diff(const Props &a, const Props &ref, double scale)
{
    Diff d;
    d.area = rel(a.area, ref.area);
    d.volume = rel(a.volume, ref.volume);
    d.centre = cdist(a.c, ref.c) / scale;
    return d;
}

// Whether a surface bounds a solid: each direction closed, or open with both of its end
// sides collapsed to a point (a pole) for every patch along them.
bool side_collapsed(const rg2_surface *s, int dir, int end)
{
    double tol = 1e-11 * rg2t_surface_scale(s);
    int along = dir ? s->nu : s->nv;
    for (int k = 0; k < along; k++) {
        rg2_xpatch P;
        if (dir) // a v = 0 / v = 1 side
            rg2_surface_patch_get(s, k, end ? s->nv - 1 : 0, &P);
        else // a u = 0 / u = 1 side
            rg2_surface_patch_get(s, end ? s->nu - 1 : 0, k, &P);
        int n = dir ? P.du : P.dv, c0 = end ? (dir ? P.dv : P.du) : 0;
        for (int a = 1; a <= n; a++) {
            const double *q = dir ? P.h[a][c0] : P.h[c0][a], *q0 = dir ? P.h[0][c0] : P.h[c0][0];
            for (int d = 0; d < 3; d++)
                if (std::fabs(q[d] / q[3] - q0[d] / q0[3]) > tol)
                    return false;
        }
    }
    return true;
}

bool bounds_solid(const rg2_surface *s)
{
    return (s->closed_u || (side_collapsed(s, 0, 0) && side_collapsed(s, 0, 1))) &&
           (s->closed_v || (side_collapsed(s, 1, 0) && side_collapsed(s, 1, 1)));
}

enum Exact { NONE, TORUS, SPHERE };

struct Case {
    std::string name;
    const rg2_surface *s;
    Exact exact = NONE;
    double R = 0, r = 0;          // torus R, r; sphere radius R
    double centre[3] = {0, 0, 0}; // of the exact shape
    bool per_mesh = false;        // also the STEP face-per-mesh layout
};

struct Worst {
    Diff exact, own, mesh, geom, own_exact;
    double conv = 0, seconds = 0;
    int solids = 0, inward = 0;
};
Worst g_worst;

// One closed surface through one format: export, read, solid, measure. ref: the exact shape's
// properties, or rg2's own integration.
void check_solid(const Case &c, const Props &ref, const Props &own, const std::string &dir, const char *ext,
                 int layout, int brep)
{
    auto t0 = std::chrono::steady_clock::now();
    bool iges = ext[0] == 'i', per_mesh = layout == RG2_STEP_FACE_PER_MESH;
    std::string path = dir + "/" + c.name + (per_mesh ? "_mesh" : "") + (brep ? "_brep" : "") + "." + ext;
    char what[160];
    snprintf(what, sizeof what, "%s%s%s.%s", c.name.c_str(), per_mesh ? " per-mesh" : "", brep ? " B-rep" : "", ext);
    rg2_export_opts o;
    rg2_export_opts_default(&o);
    o.layout = (rg2_step_layout)layout;
    o.iges_brep = brep;
    o.name = c.name.c_str();
    rg2_error err;
    rg2_status st = rg2_export_file(c.s, 1, path.c_str(), &o, &err);
    CHECK(st == RG2_OK, "%s: export failed: %s", what, err.msg);
    if (st)
        return;
    // OCCT's reader turns faces round to agree with the shell's first one ("Faces were
    // incorrectly oriented in the shell, corrected"), so one face written inward would come
    // out right: every message of the transfer is checked too. The one expected: "Surface
    // forced to be periodic" (face per mesh, closed directions).
    IGESControl_Reader ir;
    STEPControl_Reader sr;
    XSControl_Reader &r = iges ? (XSControl_Reader &)ir : (XSControl_Reader &)sr;
    bool ok = r.ReadFile(path.c_str()) == IFSelect_RetDone;
    CHECK(ok, "%s: %s read failed", what, iges ? "IGES" : "STEP");
    if (!ok)
        return;
    r.TransferRoots();
    TopoDS_Shape shape = r.OneShape();
    Interface_CheckIterator checks = r.WS()->TransferReader()->TransientProcess()->CheckList(Standard_False);
    int messages = 0;
    std::string first;
    for (checks.Start(); checks.More(); checks.Next()) {
        const Handle(Interface_Check) &ch = checks.Value();
        for (int q = 1; q <= ch->NbFails(); q++, messages++)
            if (first.empty())
                first = std::string("fail: ") + ch->CFail(q);
        for (int q = 1; q <= ch->NbWarnings(); q++)
            if (strcmp(ch->CWarning(q), "Surface forced to be periodic") != 0) {
                if (first.empty())
                    first = std::string("warning: ") + ch->CWarning(q);
                messages++;
            }
    }
    CHECK(messages == 0, "%s: %d messages from the reader's transfer, the first %s", what, messages, first.c_str());
    if (!getenv("RG2_OCCT_KEEP"))
        remove(path.c_str());
    // exactly one shell, holding every face
    std::vector<TopoDS_Shell> shells;
    for (TopExp_Explorer ex(shape, TopAbs_SHELL); ex.More(); ex.Next())
        shells.push_back(TopoDS::Shell(ex.Current()));
    int faces = 0, want_faces = per_mesh ? 1 : c.s->nu * c.s->nv;
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next())
        faces++;
    CHECK(shells.size() == 1 && faces == want_faces, "%s: %zu shells, %d faces (expected 1, %d)", what,
          shells.size(), faces, want_faces);
    if (shells.size() != 1)
        return;
    // closed: every edge but OCCT's degenerated ones (at the poles) bounds exactly two faces (a
    // seam bounds one face twice), and ShapeAnalysis_FreeBounds finds no free boundary
    TopTools_IndexedDataMapOfShapeListOfShape ef;
    TopExp::MapShapesAndAncestors(shells[0], TopAbs_EDGE, TopAbs_FACE, ef);
    int bad_edges = 0, degenerated = 0;
    for (int k = 1; k <= ef.Extent(); k++) {
        if (BRep_Tool::Degenerated(TopoDS::Edge(ef.FindKey(k))))
            degenerated++;
        else
            bad_edges += ef(k).Extent() != 2;
    }
    ShapeAnalysis_FreeBounds fb(shells[0], 1e-7, Standard_False, Standard_False);
    int free_edges = 0;
    for (TopExp_Explorer ex(fb.GetClosedWires(), TopAbs_EDGE); ex.More(); ex.Next())
        free_edges++;
    for (TopExp_Explorer ex(fb.GetOpenWires(), TopAbs_EDGE); ex.More(); ex.Next())
        free_edges++;
    CHECK(bad_edges == 0 && free_edges == 0, "%s: %d edges not bounding two faces, %d free edges", what, bad_edges,
          free_edges);
    CHECK(BRep_Tool::IsClosed(shells[0]), "%s: OCCT does not find the shell closed", what);
    // the solid as the file gives it: BRepBuilderAPI_MakeSolid keeps the faces' orientations
    BRepBuilderAPI_MakeSolid ms(shells[0]);
    CHECK(ms.IsDone(), "%s: BRepBuilderAPI_MakeSolid failed", what);
    if (!ms.IsDone())
        return;
    TopoDS_Solid solid = ms.Solid();
    BRepCheck_Analyzer an(solid);
    CHECK(an.IsValid(), "%s: BRepCheck finds the solid invalid", what);
    auto t1 = std::chrono::steady_clock::now();
    GProp_GProps vp, sp;
    double vol_est = BRepGProp::VolumeProperties(solid, vp, OCCT_EPS);
    double area_est = BRepGProp::SurfaceProperties(solid, sp, OCCT_EPS);
    auto t2 = std::chrono::steady_clock::now();
    Props occ;
    occ.area = sp.Mass();
    occ.volume = vp.Mass();
    gp_Pnt g = vp.CentreOfMass();
    occ.c[0] = g.X();
    occ.c[1] = g.Y();
    occ.c[2] = g.Z();
    CHECK(occ.volume > 0, "%s: volume %.17g: the faces are oriented inward (rg2's Su x Sv gives %.17g)", what,
          occ.volume, own.volume);
    g_worst.inward += !(occ.volume > 0);
    double scale = rg2t_surface_scale(c.s);
    // OCCT's geometry (its faces, Gauss-Legendre here) against rg2's patches
    Diff dg = diff(occt_gauss(solid, 24), own, scale);
    g_worst.geom.max_with(dg);
    CHECK(dg.area <= TOL_GEOM && dg.volume <= TOL_GEOM && dg.centre <= TOL_GEOM,
          "%s: integrated over OCCT's faces: area, volume, centroid %.3g, %.3g, %.3g off rg2's patches", what,
          dg.area, dg.volume, dg.centre);
    auto t3 = std::chrono::steady_clock::now();
    // BRepGProp against the reference
    Diff d = diff(occ, ref, scale);
    (per_mesh ? g_worst.mesh : c.exact ? g_worst.exact : g_worst.own).max_with(d);
    double ta = per_mesh ? TOL_MESH : c.exact ? TOL_EXACT : TOL_AREA;
    double tv = per_mesh ? TOL_MESH : c.exact ? TOL_EXACT : TOL_VOLUME;
    CHECK(d.area <= ta && d.volume <= tv && d.centre <= tv,
          "%s: BRepGProp area %.17g, volume %.17g, centroid (%.17g %.17g %.17g) against %s: relative errors %.3g, "
          "%.3g, %.3g",
          what, occ.area, occ.volume, occ.c[0], occ.c[1], occ.c[2], c.exact ? "the exact shape" : "rg2's patches",
          d.area, d.volume, d.centre);
    double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    double s_gprop = std::chrono::duration<double>(t2 - t1).count(), s_gauss = std::chrono::duration<double>(t3 - t2).count();
    g_worst.seconds += sec;
    g_worst.solids++;
    printf("  %-40s %3d faces, %2d degenerated edges, %d reader messages, valid %d, volume %+.12f, area %.12f; BRepGProp vs %s: area "
           "%.1e, volume %.1e, centroid %.1e (its estimates %.0e, %.0e); OCCT faces vs rg2 %.1e; %.2f s (BRepGProp %.2f, Gauss %.2f)\n",
           what, faces, degenerated, messages, (int)an.IsValid(), occ.volume, occ.area, c.exact ? "exact" : "rg2  ", d.area,
           d.volume, d.centre, area_est, vol_est, std::max(dg.area, std::max(dg.volume, dg.centre)), sec, s_gprop, s_gauss);
}

} // namespace

int main()
{
    if (!getenv("RG2_OCCT_VERBOSE"))
        Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    char tmpl[] = "/tmp/rg2_solid_XXXXXX";
    const char *dir = mkdtemp(tmpl);
    if (!dir) {
        perror("mkdtemp");
        return 1;
    }
    rg2_error err;
    std::vector<Case> cases;
    // the fixtures: a torus (closed both ways) and a capped unit sphere (polar mesh + bi-3 caps)
    rg2_surface torus, capped;
    memset(&torus, 0, sizeof torus);
    memset(&capped, 0, sizeof capped);
    CHECK_OK(fx_torus(13.0, 4.0, 8, 6, &torus, &err), &err);
    rg2_mesh cm;
    memset(&cm, 0, sizeof cm);
    CHECK_OK(rg2t_capped_sphere(&cm, &capped, &err), &err);
    rg2_mesh_free(&cm);
    {
        Case c;
        c.name = "torus 13 4";
        c.s = &torus;
        c.exact = TORUS;
        c.R = 13;
        c.r = 4;
        c.per_mesh = true;
        cases.push_back(c);
        c = Case();
        c.name = "capped sphere";
        c.s = &capped;
        c.exact = SPHERE;
        c.R = 1;
        c.per_mesh = true;
        cases.push_back(c);
    }
    // every closed surface of the example designs; those that are one exact shape as a whole
    // (every patch tagged with it) are measured against that shape
    struct ExactSurface {
        const char *name; // file without .json, '_', surface index
        Exact exact;
        double R, r, cx, cy, cz;
    } exact_list[] = {
        {"fig1_torus_0", TORUS, 3, 1, 0, 0, 0},           // 8 x 6 equal arcs
        {"fig1_torus_1", TORUS, 3, 1, 0, 0, 0},           // 12 x 6 unequal arcs
        {"fig9_polar_sphere_1", SPHERE, 1, 0, 2.5, 0, 0}, // polar mesh, capped, beside
        {"fig14_mobius_0", SPHERE, 1.5, 0, 0, 0, 1},      // poles moved (eq. 16), capped
        {"fig14_mobius_2", SPHERE, 1.5, 0, 8, 0, 1},      // poles placed, capped, beside
    };
    std::vector<rg2_design *> designs;
    std::vector<std::string> files;
    const std::string exdir = std::string(getenv("RG2_SRC") ? getenv("RG2_SRC") : ".") + "/examples";
    if (DIR *ed = opendir(exdir.c_str())) {
        while (struct dirent *ent = readdir(ed)) {
            std::string n = ent->d_name;
            if (n.size() > 5 && n.compare(n.size() - 5, 5, ".json") == 0)
                files.push_back(n.substr(0, n.size() - 5));
        }
        closedir(ed);
    }
    std::sort(files.begin(), files.end());
    int open_surfaces = 0, exact_found = 0;
    for (const std::string &f : files) {
        std::string path = exdir + "/" + f + ".json";
        rg2_design *d = nullptr;
        rg2_status st = rg2_design_load(path.c_str(), &d, &err);
        CHECK(st == RG2_OK, "%s: %s", path.c_str(), err.msg);
        if (st)
            continue;
        designs.push_back(d);
        for (int k = 0; k < rg2_design_num_surfaces(d); k++) {
            const rg2_surface *s = rg2_design_surface(d, k);
            if (!bounds_solid(s)) {
                open_surfaces++;
                continue;
            }
            Case c;
            c.name = f + "_" + std::to_string(k);
            c.s = s;
            for (const ExactSurface &e : exact_list)
                if (c.name == e.name) {
                    c.exact = e.exact;
                    c.R = e.R;
                    c.r = e.r;
                    c.centre[0] = e.cx;
                    c.centre[1] = e.cy;
                    c.centre[2] = e.cz;
                    exact_found++;
                    // the whole surface is the shape: every patch carries a shape tag
                    bool all = s->tag != nullptr;
                    for (int q = 0; all && q < s->nu * s->nv; q++)
                        all = s->tag[q] >= 0;
                    CHECK(all, "%s: listed as one exact shape, but has transition patches", c.name.c_str());
                }
            c.per_mesh = c.name == "fig9_polar_sphere_1";
            cases.push_back(c);
        }
    }
    CHECK(exact_found == (int)(sizeof exact_list / sizeof exact_list[0]), "%d of the %zu exact surfaces found",
          exact_found, sizeof exact_list / sizeof exact_list[0]);
    // 16 today: the 4 tori of Fig. 1, Fig. 7, 13, the torus + sphere, the capped spheres and
    // tubes of Fig. 9, 10, 11, 12, 14
    CHECK(cases.size() >= 2 + 16, "only %zu closed surfaces found (run from the source directory)", cases.size());
    printf("%zu closed surfaces (2 fixtures, %zu of the example designs; %d example surfaces are open)\n",
           cases.size(), cases.size() - 2, open_surfaces);
    for (const Case &c : cases) {
        // rg2's own patches, 24 x 24 Gauss points per patch, converged: compared with 32 x 32
        double scale = rg2t_surface_scale(c.s);
        Props own = own_props(c.s, 24);
        Diff conv = diff(own, own_props(c.s, 32), scale);
        double cv = std::max(conv.area, std::max(conv.volume, conv.centre));
        g_worst.conv = std::max(g_worst.conv, cv);
        CHECK(cv <= TOL_GEOM, "%s: own integration, 24 against 32 points per direction: %.3g", c.name.c_str(), cv);
        Props ref = own;
        if (c.exact) {
            if (c.exact == TORUS) {
                ref.area = 4 * M_PI * M_PI * c.R * c.r;
                ref.volume = 2 * M_PI * M_PI * c.R * c.r * c.r;
            } else {
                ref.area = 4 * M_PI * c.R * c.R;
                ref.volume = 4.0 / 3.0 * M_PI * c.R * c.R * c.R;
            }
            for (int d = 0; d < 3; d++)
                ref.c[d] = c.centre[d];
            // the integration itself, on the exact shapes
            Diff de = diff(own, ref, scale);
            g_worst.own_exact.max_with(de);
            CHECK(de.area <= TOL_GEOM && de.volume <= TOL_GEOM && de.centre <= TOL_GEOM,
                  "%s: own integration against the exact shape: area, volume, centroid %.3g, %.3g, %.3g",
                  c.name.c_str(), de.area, de.volume, de.centre);
        }
        printf("%s: %d x %d patches, area %.15f, volume %.15f, centroid (%.12f %.12f %.12f)%s, 24 vs 32 points %.1e\n",
               c.name.c_str(), c.s->nu, c.s->nv, own.area, own.volume, own.c[0], own.c[1], own.c[2],
               c.exact ? (c.exact == TORUS ? " (exact torus)" : " (exact sphere)") : "", cv);
        check_solid(c, ref, own, dir, "step", RG2_STEP_FACE_PER_PATCH, 0);
        check_solid(c, ref, own, dir, "igs", RG2_STEP_FACE_PER_PATCH, 1);
        if (c.per_mesh)
            check_solid(c, ref, own, dir, "step", RG2_STEP_FACE_PER_MESH, 0);
    }
    printf("worst BRepGProp against the exact shapes: area %.2e, volume %.2e, centroid %.2e\n", g_worst.exact.area,
           g_worst.exact.volume, g_worst.exact.centre);
    printf("worst BRepGProp against rg2's patches (no exact shape): area %.2e, volume %.2e, centroid %.2e\n",
           g_worst.own.area, g_worst.own.volume, g_worst.own.centre);
    printf("worst BRepGProp on the face-per-mesh layout against the exact shapes: area %.2e, volume %.2e, centroid %.2e\n",
           g_worst.mesh.area, g_worst.mesh.volume, g_worst.mesh.centre);
    printf("worst Gauss-Legendre over OCCT's faces against rg2's patches: area %.2e, volume %.2e, centroid %.2e\n",
           g_worst.geom.area, g_worst.geom.volume, g_worst.geom.centre);
    printf("own integration: against the exact shapes %.2e, 24 against 32 points %.2e\n",
           std::max(g_worst.own_exact.area, std::max(g_worst.own_exact.volume, g_worst.own_exact.centre)),
           g_worst.conv);
    printf("%d solids (%d with inward faces) in %.1f s\n", g_worst.solids, g_worst.inward, g_worst.seconds);
    for (rg2_design *d : designs)
        rg2_design_free(d);
    rg2_surface_free(&torus);
    rg2_surface_free(&capped);
    if (!getenv("RG2_OCCT_KEEP"))
        rmdir(dir);
    else
        printf("files kept in %s\n", dir);
    return rg2t_done("occt_test_solid");
}
