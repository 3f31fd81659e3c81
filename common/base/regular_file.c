#include "base/regular_file.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *kind_of(mode_t m)
{
    if (S_ISDIR(m))
        return "a folder";
    if (S_ISFIFO(m))
        return "a FIFO";
    if (S_ISSOCK(m))
        return "a socket";
    if (S_ISCHR(m) || S_ISBLK(m))
        return "a device";
    return "not a plain file";
}

FILE *regular_fopen(const char *path, char *err, size_t errlen)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
    if (fd < 0) {
        int e = errno;
        snprintf(err, errlen, "cannot open (%s)", strerror(e));
        errno = e;
        return NULL;
    }
    struct stat st;
    int flags;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        int e = errno;
        if (fstat(fd, &st) != 0)
            snprintf(err, errlen, "cannot read (%s)", strerror(e));
        else
            snprintf(err, errlen, "not a regular file (%s)", kind_of(st.st_mode)), e = EINVAL;
        close(fd);
        errno = e;
        return NULL;
    }
    /* a regular file never blocks; the stream is an ordinary one from here */
    if ((flags = fcntl(fd, F_GETFL)) != -1)
        fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        int e = errno;
        snprintf(err, errlen, "cannot open (%s)", strerror(e));
        close(fd);
        errno = e;
    }
    return f;
}
