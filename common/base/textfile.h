/* textfile: read a whole file into one malloc'd, NUL-terminated buffer.
 *
 * textfile_read() returns the buffer (free() it) and stores its length without the NUL
 * in *len when len is not NULL; the file may itself contain NUL bytes. On failure it
 * returns NULL and writes a one-line reason WITHOUT the path to err, e.g. "cannot open
 * (No such file or directory)", so each caller can put its own context and the path in
 * front ("shader %s: %s"). */
#ifndef CAVELIGHT_TEXTFILE_H
#define CAVELIGHT_TEXTFILE_H

#include <stddef.h>

char *textfile_read(const char *path, size_t *len, char *err, size_t errlen);
/* The same, refusing a file of more than max bytes before anything is read or allocated
 * ("N bytes, more than the MAX a file of its kind may hold"). */
char *textfile_read_max(const char *path, size_t max, size_t *len, char *err, size_t errlen);

#endif
