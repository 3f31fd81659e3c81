#include "base/folder.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

static int make_one(const char *path, char *err, size_t errlen)
{
    struct stat st;
    if (mkdir(path, 0777) == 0 || (errno == EEXIST && stat(path, &st) == 0 && S_ISDIR(st.st_mode)))
        return 0;
    snprintf(err, errlen, "cannot create folder %s: %s", path,
             errno == EEXIST ? "a file of that name is in the way" : strerror(errno));
    return -1;
}

int folder_create(const char *path, char *err, size_t errlen)
{
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf) {
        snprintf(err, errlen, "cannot create folder %.64s...: path too long", path);
        return -1;
    }
    for (char *p = buf + 1; *p; p++)
        if (*p == '/' && p[-1] != '/') {
            *p = 0;
            if (make_one(buf, err, errlen) != 0)
                return -1;
            *p = '/';
        }
    return make_one(buf, err, errlen);
}

int folder_create_for(const char *file_path, char *err, size_t errlen)
{
    const char *slash = strrchr(file_path, '/');
    if (!slash || slash == file_path)
        return 0;
    char dir[4096];
    snprintf(dir, sizeof dir, "%.*s", (int)(slash - file_path), file_path);
    return folder_create(dir, err, errlen);
}
