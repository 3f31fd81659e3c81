#include "cluster/cluster_keys.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "base/regular_file.h"

int cluster_key_path(const cluster_config *c, const char *who, cluster_key_kind kind, char *out,
                     size_t cap)
{
    int n = snprintf(out, cap, "%s/%s.%s", c->keys_dir, who, kind == CLUSTER_KEY_SECRET ? "key" : "pub");
    return n < 0 || (size_t)n >= cap ? -1 : 0;
}

int cluster_keys_bundle_dir(const cluster_config *c, const char *host, char *out, size_t cap)
{
    int n = snprintf(out, cap, "%s/hosts/%s", c->keys_dir, host);
    if (n < 0 || (size_t)n >= cap)
        return -1;
    for (char *p = out + strlen(c->keys_dir) + 7; *p; p++)
        if (*p == '/')
            *p = '_';
    return 0;
}

int cluster_keys_dir_for(const cluster_config *c, const char *config_there, char *out, size_t cap)
{
    const char *slash = strrchr(c->path, '/');
    size_t folder = slash ? (size_t)(slash - c->path) + 1 : 0;
    const char *rel = strncmp(c->keys_dir, c->path, folder) == 0 ? c->keys_dir + folder : NULL;
    int n;
    if (!config_there || !config_there[0] || !rel) {
        n = snprintf(out, cap, "%s", c->keys_dir);
    } else {
        const char *there = strrchr(config_there, '/');
        n = snprintf(out, cap, "%.*s%s", there ? (int)(there - config_there) + 1 : 0, config_there, rel);
    }
    return n < 0 || (size_t)n >= cap ? -1 : 0;
}

/* What the one who reads a key should do about a missing or bad file. */
static void advice(const cluster_config *c, const char *reader, char *out, size_t cap)
{
    if (!reader) {
        snprintf(out, cap, "the master needs master.key, master.pub and every node's .pub there as "
                 "cavelight-master --config %s --keygen wrote them (a new keygen wants the old folder removed; "
                 "or set security in the config)", c->path);
        return;
    }
    int node = cluster_config_find_node(c, reader);
    char bundle[CLUSTER_TEXT_MAX + 80];
    if (node < 0 || cluster_keys_bundle_dir(c, c->nodes[node].host, bundle, sizeof bundle) != 0)
        snprintf(bundle, sizeof bundle, "%s/hosts/HOST", c->keys_dir);
    snprintf(out, cap, "node %s needs %s.key, %s.pub and master.pub in %s (security.keys of %s): copy them "
             "from %s on the master's host, where cavelight-master --keygen wrote them (not a keygen here: "
             "that makes keys the master does not know)", reader, reader, reader, c->keys_dir, c->path, bundle);
}

/* The Z85 alphabet (ZeroMQ RFC 32). */
static int z85_char(char ch)
{
    return ch && strchr("0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ.-:+=^!/*?&<>()[]{}@%$#", ch);
}

int cluster_key_read(const cluster_config *c, const char *reader, const char *who, cluster_key_kind kind,
                     char z85[CLUSTER_KEY_Z85 + 1], char *err, size_t errlen)
{
    char path[CLUSTER_TEXT_MAX + 64], what[CLUSTER_TEXT_MAX * 2 + 300];
    if (cluster_key_path(c, who, kind, path, sizeof path) != 0) {
        snprintf(err, errlen, "cluster keys %s: path too long", c->keys_dir);
        return -1;
    }
    advice(c, reader, what, sizeof what);
    char why[128];
    FILE *f = regular_fopen(path, why, sizeof why);
    if (!f) {
        snprintf(err, errlen, "cluster keys %s: %s: %s", path, errno == EINVAL ? why : strerror(errno), what);
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
        snprintf(err, errlen, "cluster keys %s: not a key (40 Z85 characters): %s", path, what);
        return -1;
    }
    memcpy(z85, line, CLUSTER_KEY_Z85);
    z85[CLUSTER_KEY_Z85] = 0;
    return 0;
}

int cluster_key_read_pair(const cluster_config *c, const char *reader, const char *who,
                          cluster_key_derive_fn derive, char pub[CLUSTER_KEY_Z85 + 1],
                          char secret[CLUSTER_KEY_Z85 + 1], char *err, size_t errlen)
{
    if (cluster_key_read(c, reader, who, CLUSTER_KEY_SECRET, secret, err, errlen) != 0 ||
        cluster_key_read(c, reader, who, CLUSTER_KEY_PUBLIC, pub, err, errlen) != 0)
        return -1;
    char derived[CLUSTER_KEY_Z85 + 1] = "";
    if (derive(derived, secret) == 0 && strcmp(derived, pub) == 0)
        return 0;
    char spath[CLUSTER_TEXT_MAX + 64], ppath[CLUSTER_TEXT_MAX + 64], what[CLUSTER_TEXT_MAX * 2 + 300];
    cluster_key_path(c, who, CLUSTER_KEY_SECRET, spath, sizeof spath);
    cluster_key_path(c, who, CLUSTER_KEY_PUBLIC, ppath, sizeof ppath);
    advice(c, reader, what, sizeof what);
    snprintf(err, errlen, "cluster keys %s: this secret key's public key is not the one in %s (two nodes' "
             "files swapped, files of two keygen runs mixed, or a damaged key; every handshake would fail): %s",
             spath, ppath, what);
    return -1;
}
