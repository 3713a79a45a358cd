/* clocale.c -- numbers written in the "C" locale whatever the host program chose: printf's
 * decimal point follows LC_NUMERIC, so a host that called setlocale(LC_ALL, "") under a German
 * locale got "3,5" in STEP (a second list item), IGES (wrong token counts), OBJ and the JSON dump.
 * uselocale switches only the calling thread, so every thread that formats numbers for a file
 * switches for itself. */
#define _POSIX_C_SOURCE 200809L
#include "internal.h"

#include <locale.h>
#include <pthread.h>

static locale_t c_locale;
static pthread_once_t c_locale_once = PTHREAD_ONCE_INIT;

static void make_c_locale(void)
{
    c_locale = newlocale(LC_ALL_MASK, "C", (locale_t)0);
}

void *rg2__c_numeric_begin(void)
{
    pthread_once(&c_locale_once, make_c_locale);
    return c_locale ? (void *)uselocale(c_locale) : NULL;
}

void rg2__c_numeric_end(void *old)
{
    if (old)
        uselocale((locale_t)old);
}
