/* test_locale.c -- the files rg2 writes do not depend on the host program's locale. printf's
 * decimal point follows LC_NUMERIC: a program that called setlocale(LC_ALL, "") under a German
 * locale got "3,5" in STEP (a second list item), IGES (wrong token counts), OBJ and the JSON
 * dump. Every format is written under de_DE.UTF-8 (compiled into a temporary directory with
 * localedef; scripts/deps.sh test installs the locales package that holds its source) and under
 * "C", large enough that the numbers are formatted on the threads too, and the files must be
 * the same bytes (SOURCE_DATE_EPOCH fixes the STEP and IGES time stamps). So must the check
 * reports, the error messages and a picture's colour bar. */
#define _GNU_SOURCE
#include "harness.h"

#include <locale.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int main(void)
{
    char dir[] = "/tmp/rg2-locale-XXXXXX", cmd[256];
    CHECK(mkdtemp(dir) != NULL, "mkdtemp");
    snprintf(cmd, sizeof cmd, "localedef -i de_DE -f UTF-8 %s/de_DE.UTF-8 >/dev/null 2>&1", dir);
    int rc = system(cmd); /* exit 1 is a warning only */
    setenv("LOCPATH", dir, 1);
    setenv("SOURCE_DATE_EPOCH", "1700000000", 1);
    char probe[16] = "";
    if (setlocale(LC_ALL, "de_DE.UTF-8"))
        snprintf(probe, sizeof probe, "%.1f", 3.5);
    CHECK(!strcmp(probe, "3,5"), "the de_DE.UTF-8 locale (localedef exit %d) formats 3.5 as '%s', not '3,5': is the "
          "Debian package 'locales' installed? (scripts/deps.sh test installs it)", rc, probe);
    setlocale(LC_ALL, "C");

    rg2_surface s;
    rg2_error err;
    CHECK_OK(rg2t_torus(3.0, 1.0, 48, 32, NULL, &s, &err), &err);
    struct {
        const char *ext;
        int layout, brep;
    } fmt[] = {{"step", 0, 0}, {"step", 1, 0}, {"igs", 0, 0}, {"igs", 1, 0}, {"igs", 0, 1},
               {"obj", 0, 0},  {"json", 0, 0}, {"bv", 0, 0},  {"bez", 0, 0}};
    int nf = (int)(sizeof fmt / sizeof fmt[0]);
    for (int k = 0; k < nf; k++) {
        char path[2][128];
        char *b[2];
        size_t len[2];
        for (int l = 0; l < 2; l++) {
            setlocale(LC_ALL, l ? "de_DE.UTF-8" : "C");
            snprintf(path[l], sizeof path[l], "%s/t%d_%d.%s", dir, k, l, fmt[k].ext);
            rg2_export_opts o;
            rg2_export_opts_default(&o);
            o.layout = (rg2_step_layout)fmt[k].layout;
            o.iges_brep = fmt[k].brep;
            o.density = 4; /* OBJ: 24 576 vertices, 12 blocks of lines on the threads */
            CHECK_OK(rg2_export_file(&s, 1, path[l], &o, &err), &err);
            CHECK_OK(rg2_read_text(path[l], &b[l], &len[l], &err), &err);
        }
        setlocale(LC_ALL, "C");
        /* the names differ in their last digit only: the same length, so the same bytes but there */
        size_t diff = 0, first = (size_t)-1;
        for (size_t q = 0; b[0] && b[1] && len[0] == len[1] && q < len[0]; q++)
            if (b[0][q] != b[1][q]) {
                diff++;
                if (first == (size_t)-1)
                    first = q;
            }
        int names = !strcmp(fmt[k].ext, "step") || !strcmp(fmt[k].ext, "igs");
        CHECK(b[0] && b[1] && len[0] == len[1] && diff <= (size_t)names,
              "%s (layout %d, brep %d) under de_DE: %zu bytes, under C %zu, %zu bytes differ (first at %zu: '%.40s')",
              fmt[k].ext, fmt[k].layout, fmt[k].brep, len[1], len[0], diff, first,
              b[1] && first < len[1] ? b[1] + first - (first > 10 ? 10 : 0) : "");
        free(b[0]);
        free(b[1]);
        remove(path[0]);
        remove(path[1]);
    }
    rg2_surface_free(&s);

    /* rg2_check_format: the report's numbers (the table's gaps, the points "(x, y, z)" whose commas
     * separate coordinates, the JSON's "where" of the worst residual) in the "C" locale too */
    rg2_design *d;
    CHECK_OK(rg2_design_load("examples/fig1_torus.json", &d, &err), &err);
    if (d) {
        int ns = rg2_design_num_surfaces(d), nsh = rg2_design_num_shapes(d);
        rg2_surface *ss = calloc((size_t)ns, sizeof *ss);
        rg2_shape *sh = calloc((size_t)nsh, sizeof *sh);
        for (int k = 0; ss && k < ns; k++)
            ss[k] = *rg2_design_surface(d, k);
        for (int k = 0; sh && k < nsh; k++)
            sh[k] = *rg2_design_shape(d, k);
        char *text[2][2] = {{NULL, NULL}, {NULL, NULL}};
        for (int l = 0; l < 2 && ss && sh; l++) {
            setlocale(LC_ALL, l ? "de_DE.UTF-8" : "C");
            rg2_check_opts co;
            rg2_check_opts_default(&co);
            for (int t = 0; t < 2; t++) { /* serial, then on threads (the residuals' "where") */
                co.threads = t ? 2 : 1;
                rg2_check_report r;
                CHECK_OK(rg2_check(ss, ns, sh, NULL, nsh, &co, &r, &err), &err);
                for (int json = 0; json < 2; json++) {
                    char *x = NULL;
                    CHECK_OK(rg2_check_format(&r, json, &x, &err), &err);
                    if (t == 0)
                        text[l][json] = x;
                    else {
                        CHECK(x && text[l][json] && !strcmp(x, text[l][json]), "check report (%s) differs on threads",
                              json ? "JSON" : "text");
                        free(x);
                    }
                }
                rg2_check_report_free(&r);
            }
        }
        setlocale(LC_ALL, "C");
        for (int json = 0; json < 2; json++) {
            const char *a = text[0][json], *b = text[1][json];
            size_t q = 0;
            while (a && b && a[q] && a[q] == b[q])
                q++;
            CHECK(a && b && !strcmp(a, b), "check report (%s) under de_DE differs from C at byte %zu: '%.60s' vs '%.60s'",
                  json ? "JSON" : "text", q, a ? a + (q > 20 ? q - 20 : 0) : "", b ? b + (q > 20 ? q - 20 : 0) : "");
            free(text[0][json]);
            free(text[1][json]);
        }
        free(ss);
        free(sh);
        rg2_design_free(d);
    }
    /* messages and pictures: their numbers in the "C" locale too. Under de_DE the messages read
     * "interval 2 [1,25, 1,25]", "r = 3,5 must be < R = 2,5" (3.5 in the design text),
     * "colour range 1,5,0,5", "t = 1,5", and the colour bar of a picture "1 25" for 1.25 (the
     * font has no comma: 60 bytes of a 400 x 300 picture differed) */
    {
        static const double kn[6] = {0, 0.5, 1.25, 1.25, 3, 4};
        static const char *const design_text =
            "{\"shapes\": {\"t\": {\"kind\": \"torus\", \"R\": 2.5, \"r\": 3.5}}, \"meshes\": {\"m\": {\"shape\": \"t\"}}}";
        rg2_mesh tm;
        rg2_surface ts;
        CHECK_OK(rg2t_torus(3.0, 1.0, 6, 4, &tm, &ts, &err), &err);
        char msg[2][4][512];
        rg2_image img[2];
        memset(img, 0, sizeof img);
        for (int l = 0; l < 2; l++) {
            setlocale(LC_ALL, l ? "de_DE.UTF-8" : "C");
            rg2_scalars sc;
            rg2_design *dd = NULL;
            rg2_mesh mo;
            CHECK(rg2_scalars_from_knots(&sc, kn, 6, 0, &err) == RG2_EDOMAIN, "repeated knot not refused");
            snprintf(msg[l][0], sizeof msg[l][0], "%s", err.msg);
            CHECK(rg2_design_parse(design_text, strlen(design_text), "x", &dd, &err) == RG2_EDOMAIN, "r > R not refused");
            snprintf(msg[l][1], sizeof msg[l][1], "%s", err.msg);
            CHECK(rg2_mesh_morph(&tm, &tm, 1.5, &mo, &err) == RG2_EDOMAIN, "t = 1.5 not refused");
            snprintf(msg[l][2], sizeof msg[l][2], "%s", err.msg);
            rg2_render_opts ro;
            rg2_render_opts_default(&ro);
            ro.width = 400, ro.height = 300, ro.threads = 1, ro.mode = RG2_RENDER_MEAN, ro.range_set = 1;
            ro.range[0] = 1.5, ro.range[1] = 0.5;
            CHECK(rg2_render(&ts, 1, NULL, &ro, &img[l], &err) == RG2_EINVAL, "colour range 1.5, 0.5 not refused");
            snprintf(msg[l][3], sizeof msg[l][3], "%s", err.msg);
            ro.range[0] = -0.75, ro.range[1] = 1.25;
            CHECK_OK(rg2_render(&ts, 1, NULL, &ro, &img[l], &err), &err);
        }
        setlocale(LC_ALL, "C");
        static const char *const want[4] = {"[1.25, 1.25]", "r = 3.5 must be < R = 2.5", "t = 1.5,", "colour range 1.5,0.5"};
        for (int k = 0; k < 4; k++)
            CHECK(!strcmp(msg[0][k], msg[1][k]) && strstr(msg[1][k], want[k]),
                  "message under de_DE '%s', under C '%s' (want '%s')", msg[1][k], msg[0][k], want[k]);
        size_t nb = (size_t)img[0].width * (size_t)img[0].height * 3, diff = 0;
        for (size_t q = 0; img[0].rgb && img[1].rgb && q < nb; q++)
            diff += img[0].rgb[q] != img[1].rgb[q];
        CHECK(img[0].rgb && img[1].rgb && diff == 0, "a picture with a colour bar of 1.25: %zu of %zu bytes differ under de_DE",
              diff, nb);
        rg2_image_free(&img[0]);
        rg2_image_free(&img[1]);
        rg2_mesh_free(&tm);
        rg2_surface_free(&ts);
    }
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    CHECK(system(cmd) == 0, "%s", cmd);
    return rg2t_done("test_locale");
}
