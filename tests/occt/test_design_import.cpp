// test_design_import.cpp -- every example design, built and written as STEP (one face per
// patch), is read back by OpenCASCADE: one face per patch, a valid shape, OCCT's surface
// points equal rg2's patches, and the faces of exact patches lie on their shapes.
extern "C" {
#include "../harness.h"
}

#include <BRepCheck_Analyzer.hxx>
#include <BRep_Tool.hxx>
#include <Geom_Surface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>

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

struct Patch {
    rg2_xpatch p; // any degree (rg2_surface_patch_get)
    const rg2_shape *shape; // NULL for a transition patch
    double scale;
};

void check_example(const std::string &file, const std::string &dir)
{
    rg2_design *d = nullptr;
    rg2_error err;
    CHECK_OK(rg2_design_load(file.c_str(), &d, &err), &err);
    if (!d)
        return;
    int ns = rg2_design_num_surfaces(d);
    std::vector<rg2_surface> surfs;
    std::vector<Patch> patches;
    for (int o = 0; o < ns; o++) {
        const rg2_surface *s = rg2_design_surface(d, o);
        surfs.push_back(*s);
        double scale = rg2t_surface_scale(s);
        for (int k = 0; k < s->nu * s->nv; k++) {
            Patch P;
            rg2_surface_patch_get(s, k / s->nv, k % s->nv, &P.p);
            P.shape = s->tag[k] >= 0 ? rg2_design_shape(d, s->tag[k]) : nullptr;
            P.scale = scale;
            patches.push_back(P);
        }
    }
    std::string path = dir + "/" + file.substr(file.find_last_of('/') + 1) + ".step";
    rg2_export_opts opts;
    rg2_export_opts_default(&opts);
    CHECK_OK(rg2_export_file(surfs.data(), ns, path.c_str(), &opts, &err), &err);
    STEPControl_Reader r;
    bool ok = r.ReadFile(path.c_str()) == IFSelect_RetDone;
    CHECK(ok, "%s: OCCT cannot read the STEP file", file.c_str());
    if (!ok) {
        rg2_design_free(d);
        return;
    }
    r.TransferRoots();
    TopoDS_Shape shape = r.OneShape();
    std::vector<TopoDS_Face> faces;
    for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next())
        faces.push_back(TopoDS::Face(ex.Current()));
    CHECK(faces.size() == patches.size(), "%s: %zu faces for %zu patches", file.c_str(), faces.size(),
          patches.size());
    BRepCheck_Analyzer an(shape);
    CHECK(an.IsValid(), "%s: BRepCheck finds the shape invalid", file.c_str());
    // match faces to patches by their centres, compare points, check exact ones on the shape
    std::vector<int> used(patches.size(), 0);
    double worst_pt = 0, worst_exact = 0;
    int matched = 0, exact_faces = 0;
    for (const TopoDS_Face &F : faces) {
        Handle(Geom_Surface) S = BRep_Tool::Surface(F);
        gp_Pnt c = S->Value(0.5, 0.5);
        int best = -1;
        double bd = 1e300;
        for (size_t k = 0; k < patches.size(); k++) {
            rg2_eval e;
            rg2_xpatch_eval(&patches[k].p, 0.5, 0.5, 0, &e);
            double dist = c.Distance(gp_Pnt(e.p[0], e.p[1], e.p[2]));
            if (!used[k] && dist < bd) {
                bd = dist;
                best = (int)k;
            }
        }
        if (best < 0)
            continue;
        used[best] = 1;
        matched++;
        const Patch &P = patches[best];
        exact_faces += P.shape != nullptr;
        for (int a = 0; a <= 6; a++)
            for (int b = 0; b <= 6; b++) {
                rg2_eval e;
                rg2_xpatch_eval(&P.p, a / 6.0, b / 6.0, 0, &e);
                gp_Pnt p = S->Value(a / 6.0, b / 6.0);
                worst_pt = std::max(worst_pt, p.Distance(gp_Pnt(e.p[0], e.p[1], e.p[2])) / P.scale);
                if (P.shape) {
                    double x[3] = {p.X(), p.Y(), p.Z()}, g[3];
                    double F0 = rg2_shape_implicit(P.shape, x, g);
                    double gn = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                    worst_exact = std::max(worst_exact, std::fabs(F0) / (gn * P.scale));
                }
            }
    }
    CHECK(matched == (int)patches.size(), "%s: %d of %zu patches matched", file.c_str(), matched, patches.size());
    CHECK(worst_pt <= 1e-9, "%s: OCCT points vs rg2 %.3g relative", file.c_str(), worst_pt);
    CHECK(worst_exact <= 1e-12, "%s: OCCT faces of exact patches off their shapes by %.3g", file.c_str(),
          worst_exact);
    printf("  %-38s %4zu faces, valid %d, OCCT vs rg2 %.1e, %d exact faces on their shapes to %.1e\n",
           file.c_str(), faces.size(), (int)an.IsValid(), worst_pt, exact_faces, worst_exact);
    if (!getenv("RG2_OCCT_KEEP"))
        remove(path.c_str());
    rg2_design_free(d);
}

} // namespace

int main()
{
    if (!getenv("RG2_OCCT_VERBOSE"))
        Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_Printer));
    char tmpl[] = "/tmp/rg2_design_occt_XXXXXX";
    const char *dir = mkdtemp(tmpl);
    if (!dir) {
        perror("mkdtemp");
        return 1;
    }
    std::vector<std::string> files;
    if (DIR *dd = opendir("examples")) {
        while (struct dirent *de = readdir(dd)) {
            std::string n = de->d_name;
            if (n.size() > 5 && n.compare(n.size() - 5, 5, ".json") == 0)
                files.push_back("examples/" + n);
        }
        closedir(dd);
    }
    std::sort(files.begin(), files.end());
    CHECK(files.size() >= 6, "only %zu examples found (run from the source directory)", files.size());
    printf("example designs through STEP into OpenCASCADE:\n");
    for (const std::string &f : files)
        check_example(f, dir);
    rmdir(dir);
    return rg2t_done("occt_test_design_import");
}
