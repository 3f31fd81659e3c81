#include "cluster/cluster_keys.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

int cluster_key_path(const cluster_config *c, const char *who, cluster_key_kind kind, char *out,
                     size_t cap)
{
    int n = snprintf(out, cap, "%s/%s.%s", c->keys_dir, who, kind == CLUSTER_KEY_SECRET ? "key" : "pub");
    return n < 0 || (size_t)n >= cap ? -1 : 0;
}

/* The Z85 alphabet (ZeroMQ RFC 32). */
static int z85_char(char ch)
{
    return ch && strchr("0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.-:+=^!/*?&<>()[]{}@%$#", ch);
}

int cluster_key_read(const cluster_config *c, const char *who, cluster_key_kind kind,
                     char z85[CLUSTER_KEY_Z85 + 1], char *err, size_t errlen)
{
    char path[CLUSTER_TEXT_MAX + 64];
    if (cluster_key_path(c, who, kind, path, sizeof path) != 0) {
        snprintf(err, errlen, "cluster keys %s: path too long", c->keys_dir);
        return -1;
    }
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "cluster keys %s: %s: run cavelight-master --config %s --keygen "
                 "(or set security in the config)", path, strerror(errno), c->path);
        return -1;
    }
    struct stat st;
    if (kind == CLUSTER_KEY_SECRET && fstat(fileno(f), &st) == 0 && (st.st_mode & 077)) {
        fclose(f);
        snprintf(err, errlen, "cluster keys %s: a secret key readable by others: chmod 600 it", path);
        return -1;
    }
    char line[128] = "";
    int ok = fgets(line, sizeof line, f) != NULL;
    fclose(f);
    size_t n = strcspn(line, "\r\n");
    for (size_t i = 0; ok && i < n; i++)
        ok = z85_char(line[i]);
    if (!ok || n != CLUSTER_KEY_Z85) {
        snprintf(err, errlen, "cluster keys %s: not a key (40 Z85 characters); make new ones with "
                 "cavelight-master --config %s --keygen", path, c->path);
        return -1;
    }
    memcpy(z85, line, CLUSTER_KEY_Z85);
    z85[CLUSTER_KEY_Z85] = 0;
    return 0;
}
