#include "base/xalloc.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

static void *checked(void *p, size_t size)
{
    if (!p && size) {
        fprintf(stderr, "cavelight: out of memory (%zu bytes more were needed): close other "
                "programs or lower the settings\n", size);
        exit(EXIT_FAILURE);
    }
    return p;
}

void *xmalloc(size_t size) { return checked(malloc(size), size); }

void *xcalloc(size_t count, size_t size)
{
    /* calloc refuses a count * size that overflows; the message then says SIZE_MAX. */
    size_t total = count && size ? (size > SIZE_MAX / count ? SIZE_MAX : count * size) : 0;
    return checked(calloc(count, size), total);
}

void *xrealloc(void *p, size_t size) { return checked(realloc(p, size), size); }
