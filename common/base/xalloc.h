/* xalloc: the allocation policy (Redis's): memory for the program's own bookkeeping is
 * allocated with xmalloc()/xcalloc()/xrealloc(), which print one line and exit when the
 * machine has none left, so that call sites do not each write an out-of-memory branch.
 *
 * Not for memory whose size comes from outside: a lattice, image, scene, RSM or file size
 * a user or a file asked for is allocated with malloc() and a failure is a one-line error
 * naming the setting (a 2048^3 lattice is a mistake to report, not a crash), and a
 * library parsing untrusted input (glTF, PNG, wire messages) never exits. Each such raw
 * call says why in a "not xalloc:" comment beside it (tests/integration/
 * test_product_rules.sh checks that every one does). */
#ifndef CAVELIGHT_XALLOC_H
#define CAVELIGHT_XALLOC_H

#include <stddef.h>

void *xmalloc(size_t size);
void *xcalloc(size_t count, size_t size);
void *xrealloc(void *p, size_t size);

#endif
