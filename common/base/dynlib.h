/* dynlib: a shared library loaded when a feature asks for it (dlopen), with its entry
 * points resolved from one table, instead of linked into every program.
 *
 * A render node on a GPU host needs neither Mesa's software renderer (OSMesa, which pulls
 * in LLVM) nor Embree (the path-traced reference and the vpl view rule): glctx_osmesa.c
 * and scene_rt.c load them here on first use, so `ldd cavelight-node` lists neither. The
 * library is searched the usual way (the program's RUNPATH, LD_LIBRARY_PATH, the system's
 * folders) under each of its known file names. Once loaded it stays loaded: the entry
 * points are shared by every user in the process. Thread-safe. */
#ifndef CAVELIGHT_DYNLIB_H
#define CAVELIGHT_DYNLIB_H

#include <stddef.h>

typedef struct dynlib_symbol {
    const char *name;
    void *fn;                  /* the function pointer variable that gets its address */
} dynlib_symbol;

typedef struct dynlib {
    const char *what;                 /* "OSMesa", for messages */
    const char *const *files;         /* file names to try, NULL-terminated */
    const char *package;              /* the Debian package that has it, for the hint */
    const dynlib_symbol *symbols;     /* every entry point the users call */
    int symbol_count;
} dynlib;

/* Loads lib and resolves every symbol once (later calls return the first result). Returns
 * 0, or -1 with one line in err: which library is missing (and the package to install) or
 * which entry point it lacks. */
int dynlib_load(const dynlib *lib, char *err, size_t errlen);

#endif
