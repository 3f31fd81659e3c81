/* regular_file: opens an input (scene, config, key, projector file, cache) for reading only
 * when it is a regular file. The open() is non-blocking, so a FIFO or a device named as an
 * input never hangs the program, and fstat() then refuses anything but a regular file.
 *
 * regular_fopen() returns a blocking "rb" stream, or NULL with errno kept (ENOENT stays
 * ENOENT) and a one-line reason WITHOUT the path in err, e.g. "not a regular file (a
 * FIFO)", for the caller to put its own context and the path in front. */
#ifndef CAVELIGHT_REGULAR_FILE_H
#define CAVELIGHT_REGULAR_FILE_H

#include <stddef.h>
#include <stdio.h>

FILE *regular_fopen(const char *path, char *err, size_t errlen);

#endif
