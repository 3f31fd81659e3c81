#include "base/textfile.h"

#include "base/regular_file.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

char *textfile_read(const char *path, size_t *len, char *err, size_t errlen)
{
    return textfile_read_max(path, SIZE_MAX - 1, len, err, errlen);
}

char *textfile_read_max(const char *path, size_t max, size_t *len, char *err, size_t errlen)
{
    FILE *f = regular_fopen(path, err, errlen);
    if (!f)
        return NULL;
    /* fstat, not fseek/ftell: the size regular_fopen() checked is a regular file's. */
    struct stat st;
    char *s = NULL;
    size_t n = 0;
    /* not xalloc: the file's size: refused in err */
    if (fstat(fileno(f), &st) != 0) {
        snprintf(err, errlen, "cannot read (%s)", strerror(errno));
    } else if ((unsigned long long)st.st_size > max) {
        snprintf(err, errlen, "%lld bytes, more than the %zu a file of its kind may hold",
                 (long long)st.st_size, max);
    } else if (!(s = malloc((n = (size_t)st.st_size) + 1))) {
        snprintf(err, errlen, "out of memory for %zu bytes", n);
    } else if (fread(s, 1, n, f) != n) {
        snprintf(err, errlen, "cannot read (%s)", ferror(f) ? strerror(errno) : "file shrank");
        free(s);
        s = NULL;
    }
    fclose(f);
    if (s) {
        s[n] = '\0';
        if (len)
            *len = n;
    }
    return s;
}
