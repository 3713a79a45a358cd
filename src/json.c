/* json.c -- rg2's calls into cJSON's parser and printer, one at a time in the process.
 *
 * Debian's libcjson (1.7.15) writes a process-wide struct (global_error, what
 * cJSON_GetErrorPtr returns) on every parse, so two threads in rg2_design_parse at once raced
 * on it (valgrind's helgrind: "Possible data race during write of size 8 ... in the BSS segment
 * of libcjson.so"). And both directions read the decimal point through localeconv(), whose one
 * result struct glibc rewrites on every call, from the calling thread's locale: a thread under
 * de_DE.UTF-8 (uselocale) parsing while another under "C" parsed now and then read the other's
 * decimal point and failed on "1.5" ("malformed JSON near '.5'": 1 to 3 parses of
 * fig1_torus.json in 6000 on two threads, docs/robustness.md). Here every parse and print
 * holds one lock and runs in the "C" locale (the same numbers: JSON's decimal point is '.'
 * whatever the locale), so rg2's own calls neither race on cJSON's global nor see another
 * thread's decimal point. A host that calls cJSON or
 * localeconv() itself in another thread at the same time is outside this lock (rg2.h). The
 * error position of a failed parse comes from the call's own end pointer, never from
 * cJSON_GetErrorPtr. */
#define _POSIX_C_SOURCE 200809L
#include "internal.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

static pthread_mutex_t json_lock = PTHREAD_MUTEX_INITIALIZER;
static pthread_once_t json_once = PTHREAD_ONCE_INIT;

/* A fork while another thread held the lock would leave it held for good in the child: the
 * forking thread takes it first and releases it on both sides. */
static void json_prepare(void) { pthread_mutex_lock(&json_lock); }
static void json_release(void) { pthread_mutex_unlock(&json_lock); }
static void json_register(void) { pthread_atfork(json_prepare, json_release, json_release); }

static void *json_begin(void)
{
    pthread_once(&json_once, json_register);
    pthread_mutex_lock(&json_lock);
    return rg2__c_numeric_begin();
}

static void json_end(void *loc)
{
    rg2__c_numeric_end(loc);
    pthread_mutex_unlock(&json_lock);
}

cJSON *rg2__json_parse(const char *text, size_t len, const char **end)
{
    void *loc = json_begin();
    cJSON *root = cJSON_ParseWithLengthOpts(text, len, end, 1);
    json_end(loc);
    return root;
}

char *rg2__json_print(const cJSON *item, int formatted)
{
    void *loc = json_begin();
    char *text = formatted ? cJSON_Print(item) : cJSON_PrintUnformatted(item);
    json_end(loc);
    return text;
}

/* cJSON prints a number with 15 significant digits whenever they read back within about one
 * unit in the last place (its compare_double), so 3.0000000000000004 came out as "3": 80 of
 * the 576 numbers of a torus + cylinder control mesh were off by an ulp, and a point set with
 * "to" from its printed position was no longer the shape's. Here the shortest of 15, 16 and 17
 * digits that reads back to the same double, as a raw item (non-finite: cJSON's null). */
void rg2__json_number_text(double x, char buf[40])
{
    for (int digits = 15; digits <= 17; digits++) {
        snprintf(buf, 40, "%.*g", digits, x);
        if (strtod(buf, NULL) == x)
            break;
    }
}

cJSON *rg2__json_double(double x)
{
    if (!isfinite(x))
        return cJSON_CreateNumber(x);
    char buf[40];
    void *loc = rg2__c_numeric_begin();
    rg2__json_number_text(x, buf);
    rg2__c_numeric_end(loc);
    return cJSON_CreateRaw(buf);
}

/* An array of n such numbers (NULL when out of memory). */
cJSON *rg2__json_doubles(const double *x, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; a && i < n; i++)
        cJSON_AddItemToArray(a, rg2__json_double(x[i]));
    return a;
}
