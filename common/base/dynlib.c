/* dynlib: libraries loaded on first use (dynlib.h). */
#include "dynlib.h"

#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;

/* The outcome of each library's first load, keyed by its descriptor. */
enum { MAX_LIBS = 8 };
static struct {
    const dynlib *lib;
    int rc;
    char err[256];
} loaded[MAX_LIBS];
static int loaded_count;

static int open_library(const dynlib *lib, char *err, size_t errlen)
{
    char first[200] = "";
    void *h = NULL;
    for (int i = 0; !h && lib->files[i]; i++)
        if (!(h = dlopen(lib->files[i], RTLD_NOW | RTLD_LOCAL)) && i == 0)
            snprintf(first, sizeof first, "%s", dlerror()); /* the usual name's reason */
    if (!h) {
        snprintf(err, errlen, "%s: cannot load %s (%s); install %s", lib->what, lib->files[0], first,
                 lib->package);
        return -1;
    }
    for (int i = 0; i < lib->symbol_count; i++) {
        void *p = dlsym(h, lib->symbols[i].name);
        if (!p) {
            snprintf(err, errlen, "%s: %s has no %s (too old? install %s)", lib->what, lib->files[0],
                     lib->symbols[i].name, lib->package);
            return -1;
        }
        /* POSIX: a function's address passes through void *, and function pointers have
         * its size. */
        memcpy(lib->symbols[i].fn, &p, sizeof p);
    }
    return 0;
}

int dynlib_load(const dynlib *lib, char *err, size_t errlen)
{
    pthread_mutex_lock(&lock);
    int i = 0;
    while (i < loaded_count && loaded[i].lib != lib)
        i++;
    if (i == loaded_count && i < MAX_LIBS) {
        loaded[i].lib = lib;
        loaded[i].rc = open_library(lib, loaded[i].err, sizeof loaded[i].err);
        loaded_count++;
    }
    int rc = i < MAX_LIBS ? loaded[i].rc : -1;
    snprintf(err, errlen, "%s", i < MAX_LIBS ? loaded[i].err : "dynlib: too many libraries");
    pthread_mutex_unlock(&lock);
    return rc;
}
