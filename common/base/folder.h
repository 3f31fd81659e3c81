/* folder: output folders, created with their parents (as mkdir -p does).
 *
 * Every program that writes files under a folder the user names (--out, --overview,
 * --report, recordings) creates it here, so that "out/a/b" works on a fresh clone. */
#ifndef CAVELIGHT_FOLDER_H
#define CAVELIGHT_FOLDER_H

#include <stddef.h>

/* Creates the folder path and its missing parents. Returns 0 (also when it exists), or
 * -1 with "cannot create folder P: reason" in err. */
int folder_create(const char *path, char *err, size_t errlen);
/* Creates the folder a file path lies in ("out/x/report.json" -> "out/x"). */
int folder_create_for(const char *file_path, char *err, size_t errlen);

#endif
