// test_edited_import.cpp -- designs a designer edits (tests/data/edited/*.json: moved points and
// weights, scalar edits, rolls, reversals, transposes, cuts, merges along u and v, Moebius maps,
// morphs, pole moves, bi-3 and general caps, clamped NURBS, 11 surfaces in one file, a design
// 0.00071 mm across and one 1.06e5 mm across), every output surface written into one file in six
// forms (STEP and IGES plain and IGES B-rep, face per patch and face per mesh) and read back by
// OpenCASCADE as a CAD user would: the faces (count, file order), a valid shape, OCCT's points
// against rg2's evaluation at 10 x 10 (per mesh 7 x 7) parameters of every patch, OCCT's normals
// (with the face's orientation) along rg2's n = Su x Sv, the rational flag and degrees of every
// face's B-spline, the closed flags of the per-mesh surfaces, tolerances, every pcurve's points
// on its edge's 3D curve, the faces on both sides of every edge meeting, the vertices on their
// edges' ends, the faces of exact patches on their shapes, and STEP and IGES of one layout giving
// the same points.
extern "C" {
#include "../harness.h"
}

#include <BRepCheck_Analyzer.hxx>
#include <BRep_Tool.hxx>
#include <GeomLProp_SLProps.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Curve.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

struct Worst {
    double pt = 0, nang = 0, tol = 0, dev = 0, gap = 0, vgap = 0, exact = 0, step_iges = 0;
    int files = 0, faces = 0, samples = 0, edges = 0;
};
Worst g_w;

struct Measure {
    double pt = 0, nang = 0, exact = 0, tol = 0, dev = 0, gap = 0, vgap = 0;
    int normals = 0, inward = 0, rational_bad = 0, degree_bad = 0, order_bad = 0, closed_bad = 0, other = 0;
    int shared = 0, free_e = 0, more = 0, uses = 0;
};

Handle(Geom_BSplineSurface) bspline_of(Handle(Geom_Surface) S)
{
    while (S->IsKind(STANDARD_TYPE(Geom_RectangularTrimmedSurface)))
        S = Handle(Geom_RectangularTrimmedSurface)::DownCast(S)->BasisSurface();
    return Handle(Geom_BSplineSurface)::DownCast(S);
}

// weights of the control points (all patches for a surface, one patch otherwise) not all equal
bool weights_vary(const rg2_surface *s, int i0, int i1, int j0, int j1)
{
    double w0 = 0;
    bool first = true;
    for (int i = i0; i < i1; i++)
        for (int j = j0; j < j1; j++) {
            rg2_xpatch X;
            rg2_surface_patch_get(s, i, j, &X);
            for (int r = 0; r <= X.du; r++)
                for (int t = 0; t <= X.dv; t++) {
                    if (first)
                        w0 = X.h[r][t][3];
                    first = false;
                    if (std::fabs(X.h[r][t][3] - w0) > 1e-15 * std::fabs(w0))
                        return true;
                }
        }
    return false;
}

// OCCT's face F (surface S) against patch (i, j) of s at n x n parameters (per mesh the knot
// span [i, i + 1] x [j, j + 1]); the tagged patches' points on their shapes.
void compare_patch(const rg2_design *d, const TopoDS_Face &F, const Handle(Geom_Surface) & S, const rg2_surface *s,
                   int i, int j, bool per_mesh, double scale, int n, Measure &M, std::vector<gp_Pnt> *keep)
{
    bool rev = F.Orientation() == TopAbs_REVERSED;
    const rg2_shape *shape = s->tag && s->tag[i * s->nv + j] >= 0 ? rg2_design_shape(d, s->tag[i * s->nv + j]) : nullptr;
    for (int a = 0; a < n; a++)
        for (int b = 0; b < n; b++) {
            double u = a / (n - 1.0), v = b / (n - 1.0);
            rg2_eval e;
            rg2_surface_eval(s, i, j, u, v, 1, &e);
            double U = per_mesh ? i + u : u, V = per_mesh ? j + v : v;
            gp_Pnt p = S->Value(U, V);
            if (keep)
                keep->push_back(p);
            M.pt = std::max(M.pt, p.Distance(gp_Pnt(e.p[0], e.p[1], e.p[2])) / scale);
            if (shape) {
                double x[3] = {p.X(), p.Y(), p.Z()}, g[3];
                double f = rg2_shape_implicit(shape, x, g), gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                if (gn > 0)
                    M.exact = std::max(M.exact, std::fabs(f) / (gn * scale));
            }
            if (e.flags & RG2_EVAL_NORMAL_UNDEFINED)
                continue;
            GeomLProp_SLProps pr(S, U, V, 1, 1e-12);
            if (!pr.IsNormalDefined())
                continue;
            gp_Dir nd = pr.Normal();
            if (rev)
                nd.Reverse();
            double dt = nd.X() * e.n[0] + nd.Y() * e.n[1] + nd.Z() * e.n[2];
            double cx = nd.Y() * e.n[2] - nd.Z() * e.n[1], cy = nd.Z() * e.n[0] - nd.X() * e.n[2],
                   cz = nd.X() * e.n[1] - nd.Y() * e.n[0];
            M.normals++;
            M.inward += dt < 0;
            M.nang = std::max(M.nang, std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), std::fabs(dt)));
        }
}

// Edges: uses by faces, each pcurve's points against the 3D curve, the faces' points along the
// edge against each other, the vertices against the curve's ends; tolerances.
void edges_of(const TopoDS_Shape &shape, double scale, Measure &M)
{
    TopTools_IndexedDataMapOfShapeListOfShape m;
    TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, m);
    for (int k = 1; k <= m.Extent(); k++) {
        TopoDS_Edge E = TopoDS::Edge(m.FindKey(k));
        M.tol = std::max(M.tol, BRep_Tool::Tolerance(E));
        double f, l;
        Handle(Geom_Curve) c3 = BRep_Tool::Curve(E, f, l);
        TopoDS_Vertex v1, v2;
        TopExp::Vertices(E, v1, v2);
        for (const TopoDS_Vertex &V : {v1, v2})
            if (!V.IsNull())
                M.tol = std::max(M.tol, BRep_Tool::Tolerance(V));
        if (BRep_Tool::Degenerated(E) || c3.IsNull())
            continue;
        if (!v1.IsNull())
            M.vgap = std::max(M.vgap, BRep_Tool::Pnt(v1).Distance(c3->Value(f)) / scale);
        if (!v2.IsNull())
            M.vgap = std::max(M.vgap, BRep_Tool::Pnt(v2).Distance(c3->Value(l)) / scale);
        int nuse = m.FindFromIndex(k).Extent();
        M.shared += nuse == 2;
        M.free_e += nuse == 1;
        M.more += nuse > 2;
        std::vector<TopoDS_Face> fs;
        for (TopTools_ListOfShape::Iterator it(m.FindFromIndex(k)); it.More(); it.Next()) {
            TopoDS_Face F = TopoDS::Face(it.Value());
            bool dup = false;
            for (const TopoDS_Face &g : fs)
                dup |= g.IsSame(F);
            if (!dup)
                fs.push_back(F);
        }
        for (int q = 0; q <= 8; q++) {
            double t = f + (l - f) * q / 8.0;
            gp_Pnt p3 = c3->Value(t);
            std::vector<gp_Pnt> on;
            for (const TopoDS_Face &F : fs)
                for (int o = 0; o < 2; o++) { // both of a seam's pcurves
                    double pf, pl;
                    Handle(Geom2d_Curve) pc =
                        BRep_Tool::CurveOnSurface(TopoDS::Edge(o ? E.Reversed() : E), F, pf, pl);
                    if (pc.IsNull())
                        continue;
                    gp_Pnt2d uv = pc->Value(pf + (pl - pf) * (t - f) / (l - f));
                    gp_Pnt ps = BRep_Tool::Surface(F)->Value(uv.X(), uv.Y());
                    M.dev = std::max(M.dev, ps.Distance(p3) / scale);
                    on.push_back(ps);
                    M.uses++;
                }
            for (size_t a = 0; a < on.size(); a++)
                for (size_t b = a + 1; b < on.size(); b++)
                    M.gap = std::max(M.gap, on[a].Distance(on[b]) / scale);
        }
    }
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next())
        M.tol = std::max(M.tol, BRep_Tool::Tolerance(TopoDS::Face(ex.Current())));
}

struct Form {
    const char *name, *ext;
    bool per_mesh, brep;
};

void check_design(const std::string &file, const std::string &dir)
{
    rg2_design *d = nullptr;
    rg2_error err;
    CHECK_OK(rg2_design_load(file.c_str(), &d, &err), &err);
    if (!d)
        return;
    int ns = rg2_design_num_surfaces(d), np = 0;
    std::vector<rg2_surface> surfs;
    std::vector<double> scale;
    for (int k = 0; k < ns; k++) {
        surfs.push_back(*rg2_design_surface(d, k));
        scale.push_back(rg2t_surface_scale(&surfs[k]));
        np += surfs[k].nu * surfs[k].nv;
    }
    double big = *std::max_element(scale.begin(), scale.end());
    // the expected edges of the file's own topology: every surface's, as the STEP writer builds it
    static const Form forms[6] = {{"STEP per patch", "step", false, false}, {"STEP per mesh", "step", true, false},
                                  {"IGES per patch", "igs", false, false}, {"IGES per mesh", "igs", true, false},
                                  {"IGES B-rep per patch", "igs", false, true},
                                  {"IGES B-rep per mesh", "igs", true, true}};
    std::vector<gp_Pnt> pts[6];
    int shared[2] = {-1, -1}, free_e[2] = {-1, -1};
    std::string base = file.substr(file.find_last_of('/') + 1);
    for (int fi = 0; fi < 6; fi++) {
        const Form &fm = forms[fi];
        std::string what = base + " " + fm.name, path = dir + "/edited." + fm.ext;
        rg2_export_opts o;
        rg2_export_opts_default(&o);
        o.layout = fm.per_mesh ? RG2_STEP_FACE_PER_MESH : RG2_STEP_FACE_PER_PATCH;
        o.iges_brep = fm.brep;
        CHECK_OK(rg2_export_file(surfs.data(), ns, path.c_str(), &o, &err), &err);
        TopoDS_Shape shape;
        bool ok;
        if (fm.ext[0] == 'i') {
            IGESControl_Reader r;
            ok = r.ReadFile(path.c_str()) == IFSelect_RetDone;
            if (ok) {
                r.TransferRoots();
                shape = r.OneShape();
            }
        } else {
            STEPControl_Reader r;
            ok = r.ReadFile(path.c_str()) == IFSelect_RetDone;
            if (ok) {
                r.TransferRoots();
                shape = r.OneShape();
            }
        }
        CHECK(ok && !shape.IsNull(), "%s: OCCT cannot read it", what.c_str());
        if (!ok || shape.IsNull())
            continue;
        std::vector<TopoDS_Face> faces;
        for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next())
            faces.push_back(TopoDS::Face(ex.Current()));
        int want = fm.per_mesh ? ns : np;
        CHECK((int)faces.size() == want, "%s: %zu faces, expected %d", what.c_str(), faces.size(), want);
        BRepCheck_Analyzer an(shape);
        CHECK(an.IsValid(), "%s: BRepCheck finds the shape invalid", what.c_str());
        Measure M;
        if ((int)faces.size() == want) {
            int k = 0;
            for (int s = 0; s < ns; s++) {
                const rg2_surface *S = &surfs[s];
                if (fm.per_mesh) {
                    Handle(Geom_Surface) G = BRep_Tool::Surface(faces[k]);
                    Handle(Geom_BSplineSurface) B = bspline_of(G);
                    int du, dv;
                    rg2_surface_degree(S, &du, &dv);
                    if (B.IsNull())
                        M.other++;
                    else {
                        M.rational_bad += (B->IsURational() || B->IsVRational()) != weights_vary(S, 0, S->nu, 0, S->nv);
                        M.degree_bad += B->UDegree() != du || B->VDegree() != dv;
                        M.closed_bad += B->IsUClosed() != (S->closed_u != 0) || B->IsVClosed() != (S->closed_v != 0);
                    }
                    for (int i = 0; i < S->nu; i++)
                        for (int j = 0; j < S->nv; j++)
                            compare_patch(d, faces[k], G, S, i, j, true, scale[s], 7, M, &pts[fi]);
                    k++;
                    continue;
                }
                for (int i = 0; i < S->nu; i++)
                    for (int j = 0; j < S->nv; j++, k++) {
                        Handle(Geom_Surface) G = BRep_Tool::Surface(faces[k]);
                        Handle(Geom_BSplineSurface) B = bspline_of(G);
                        rg2_eval e;
                        rg2_surface_eval(S, i, j, 0.5, 0.5, 0, &e);
                        M.order_bad += G->Value(0.5, 0.5).Distance(gp_Pnt(e.p[0], e.p[1], e.p[2])) > 1e-9 * scale[s];
                        rg2_xpatch X;
                        rg2_surface_patch_get(S, i, j, &X);
                        if (B.IsNull())
                            M.other++;
                        else {
                            M.rational_bad += (B->IsURational() || B->IsVRational()) != weights_vary(S, i, i + 1, j, j + 1);
                            M.degree_bad += B->UDegree() != X.du || B->VDegree() != X.dv;
                        }
                        compare_patch(d, faces[k], G, S, i, j, false, scale[s], 10, M, &pts[fi]);
                    }
            }
        }
        edges_of(shape, big, M);
        CHECK(M.pt <= 1e-13, "%s: OCCT points %.3g of the size from rg2's", what.c_str(), M.pt);
        CHECK(M.exact <= 1e-13, "%s: OCCT points of exact patches %.3g off their shapes", what.c_str(), M.exact);
        CHECK(M.inward == 0 && M.nang <= 1e-9 && M.normals > 0,
              "%s: %d of %d OCCT normals against rg2's Su x Sv, angle up to %.3g rad", what.c_str(), M.inward,
              M.normals, M.nang);
        CHECK(M.rational_bad == 0 && M.degree_bad == 0 && M.order_bad == 0 && M.other == 0 && M.closed_bad == 0,
              "%s: faces with rational flags %d, degrees %d, file order %d, closed flags %d other than rg2's, %d "
              "not B-splines",
              what.c_str(), M.rational_bad, M.degree_bad, M.order_bad, M.closed_bad, M.other);
        CHECK(M.tol <= 1e-6 && M.dev <= 1e-13 && M.gap <= 1e-13 && M.vgap <= 1e-13 && M.more == 0,
              "%s: tolerance up to %.3g, pcurve points %.3g off their edges, faces %.3g apart along them, vertices "
              "%.3g off the curve ends (of the size), %d edges in more than two faces",
              what.c_str(), M.tol, M.dev, M.gap, M.vgap, M.more);
        int layout = fm.per_mesh ? 1 : 0;
        if (fm.ext[0] == 's') {
            shared[layout] = M.shared;
            free_e[layout] = M.free_e;
        } else if (fm.brep) {
            CHECK(M.shared == shared[layout] && M.free_e == free_e[layout],
                  "%s: %d shared and %d free edges, the STEP file %d and %d", what.c_str(), M.shared, M.free_e,
                  shared[layout], free_e[layout]);
        } else {
            CHECK(M.shared == (fm.per_mesh ? shared[1] : 0), "%s: %d shared edges before sewing", what.c_str(),
                  M.shared);
        }
        printf("  %-58s %4zu faces, valid %d, points %.1e, exact %.1e, normals %.1e rad, tolerance %.1e, pcurves "
               "%.1e, edges %d shared %d free\n",
               what.c_str(), faces.size(), (int)an.IsValid(), M.pt, M.exact, M.nang, M.tol, M.dev, M.shared,
               M.free_e);
        g_w.pt = std::max(g_w.pt, M.pt);
        g_w.exact = std::max(g_w.exact, M.exact);
        g_w.nang = std::max(g_w.nang, M.nang);
        g_w.tol = std::max(g_w.tol, M.tol);
        g_w.dev = std::max(g_w.dev, M.dev);
        g_w.gap = std::max(g_w.gap, M.gap);
        g_w.vgap = std::max(g_w.vgap, M.vgap);
        g_w.files++;
        g_w.faces += (int)faces.size();
        g_w.samples += (int)pts[fi].size();
        g_w.edges += M.shared;
        if (!getenv("RG2_OCCT_KEEP"))
            remove(path.c_str());
    }
    // STEP and IGES of one layout: the same points
    for (int a = 0; a < 2; a++)
        for (int b : {2 + a, 4 + a}) {
            double m = pts[a].size() == pts[b].size() ? 0 : INFINITY;
            for (size_t q = 0; q < pts[a].size() && q < pts[b].size(); q++)
                m = std::max(m, pts[a][q].Distance(pts[b][q]) / big);
            CHECK(m <= 1e-15, "%s: %s and %s %.3g apart (of the size)", base.c_str(), forms[a].name, forms[b].name, m);
            g_w.step_iges = std::max(g_w.step_iges, m);
        }
    rg2_design_free(d);
}

} // namespace

int main()
{
    if (!getenv("RG2_OCCT_VERBOSE"))
        Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    char tmpl[] = "/tmp/rg2_edited_occt_XXXXXX";
    const char *dir = mkdtemp(tmpl);
    if (!dir) {
        perror("mkdtemp");
        return 1;
    }
    std::string src = getenv("RG2_SRC") ? getenv("RG2_SRC") : ".";
    std::vector<std::string> files;
    if (DIR *dd = opendir((src + "/tests/data/edited").c_str())) {
        while (struct dirent *de = readdir(dd)) {
            std::string n = de->d_name;
            if (n.size() > 5 && n.compare(n.size() - 5, 5, ".json") == 0)
                files.push_back(src + "/tests/data/edited/" + n);
        }
        closedir(dd);
    }
    std::sort(files.begin(), files.end());
    CHECK(files.size() >= 8, "only %zu edited designs found under %s/tests/data/edited", files.size(), src.c_str());
    printf("edited designs through STEP and IGES into OpenCASCADE:\n");
    for (const std::string &f : files)
        check_design(f, dir);
    printf("worst of %d files (%d faces, %d points, %d shared edges): points %.2e of the size from rg2's, exact "
           "patches %.2e off their shapes, normals %.2e rad from Su x Sv, tolerance %.2e, pcurves %.2e, faces along "
           "edges %.2e, vertices %.2e, STEP vs IGES %.2e\n",
           g_w.files, g_w.faces, g_w.samples, g_w.edges, g_w.pt, g_w.exact, g_w.nang, g_w.tol, g_w.dev, g_w.gap,
           g_w.vgap, g_w.step_iges);
    rmdir(dir);
    return rg2t_done("occt_edited_import");
}
