#define _XOPEN_SOURCE 700 /* S_ISVTX, the sticky bit */
#include "gi/caches/cache_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/byteorder.h"
#include "base/clock.h"
#include "base/fnv1a.h"
#include "base/folder.h"
#include "base/regular_file.h"
#include "gi/caches/val_select.h"

/* Layout, little-endian: magic, version u32, edge and angle (float bits) u32, 0 u32, scene
 * hash u64, count u64, count records of 7 floats (position, normal, area), FNV-1a u64 of
 * everything before it. */
static const char MAGIC[8] = {'C', 'V', 'L', 'C', 'A', 'C', 'H', 'E'};
enum { HEADER = 40, RECORD = 4 * CACHE_RECORD_FLOATS, TRAILER = 8 };
/* More caches than this is a damaged count, not a scene. */
#define MAX_COUNT ((uint64_t)1 << 26)

uint64_t cache_scene_hash(const scene *s)
{
    uint8_t b[8];
    le_put(b, s->triangle_count, 8);
    uint64_t h = fnv1a64(FNV1A64_OFFSET, b, 8);
    h = val_hash_words(h, s->positions, 9 * s->triangle_count);
    h = val_hash_words(h, s->normals, 9 * s->triangle_count);
    for (size_t t = 0; t < s->triangle_count; t++) /* the caches' roughness */
        h = val_hash_words(h, &s->materials[s->triangle_material[t]].roughness, 1);
    return h;
}

cache_key cache_key_of(const scene *s, const cache_place_desc *d)
{
    return (cache_key){CACHE_FILE_VERSION, cache_scene_hash(s), d->edge, d->angle};
}

int cache_file_dir(char *out, size_t cap)
{
    const char *dir = getenv("CAVELIGHT_CACHE_DIR"), *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    if (dir && *dir)
        snprintf(out, cap, "%s", dir);
    else if (xdg && xdg[0] == '/') /* the spec: a relative path is to be ignored */
        snprintf(out, cap, "%s/cavelight", xdg);
    else if (home && *home)
        snprintf(out, cap, "%s/.cache/cavelight", home);
    else
        return -1;
    return 0;
}

static void put_header(uint8_t *h, const cache_key *key, uint64_t count)
{
    uint32_t edge, angle;
    memcpy(&edge, &key->edge, 4);
    memcpy(&angle, &key->angle, 4);
    memcpy(h, MAGIC, 8);
    le_put(h + 8, key->version, 4);
    le_put(h + 12, edge, 4);
    le_put(h + 16, angle, 4);
    le_put(h + 20, 0, 4);
    le_put(h + 24, key->scene_hash, 8);
    le_put(h + 32, count, 8);
}

void cache_file_path(const char *dir, const cache_key *key, char *out, size_t cap)
{
    uint8_t h[HEADER];
    put_header(h, key, 0);
    snprintf(out, cap, "%s/caches-%016llx.bin", dir,
             (unsigned long long)fnv1a64(FNV1A64_OFFSET, h, HEADER));
}

/* The records of buf (count of them) into a new set. */
static int decode(const uint8_t *buf, uint64_t count, const cache_key *key, cache_set *out)
{
    memset(out, 0, sizeof *out);
    /* not xalloc: a cache file's count: -1, and the caller rebuilds */
    out->caches = malloc((count ? count : 1) * sizeof *out->caches);
    if (!out->caches)
        return -1;
    for (uint64_t i = 0; i < count; i++) {
        float f[CACHE_RECORD_FLOATS];
        for (int k = 0; k < CACHE_RECORD_FLOATS; k++) {
            uint32_t bits = (uint32_t)le_get(buf + HEADER + RECORD * i + 4 * k, 4);
            memcpy(&f[k], &bits, 4);
        }
        light_cache *c = &out->caches[i];
        memcpy(c->position, f, sizeof c->position);
        memcpy(c->normal, f + 3, sizeof c->normal);
        c->area = f[6];
        c->roughness = f[7];
    }
    out->count = count;
    out->edge = key->edge;
    out->angle = key->angle;
    return 0;
}

int cache_file_read(const char *path, const cache_key *key, cache_set *out, char *why,
                    size_t cap)
{
    /* Only a regular file: a FIFO of that name would block, a folder's "size" is LONG_MAX. */
    FILE *f = regular_fopen(path, why, cap);
    if (!f) {
        if (errno == ENOENT)
            snprintf(why, cap, "absent");
        return -1;
    }
    uint8_t *buf = NULL;
    long size = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
    int rc = -1;
    /* not xalloc: the file's size: a failure is "cannot be read" and a rebuild */
    if (size < 0) {
        snprintf(why, cap, "cannot be read");
    } else if ((uint64_t)size > HEADER + RECORD * MAX_COUNT + TRAILER) {
        snprintf(why, cap, "%ld bytes, more than any light cache file", size);
    } else if (!(buf = malloc(size ? (size_t)size : 1)) || fseek(f, 0, SEEK_SET) != 0 ||
               fread(buf, 1, (size_t)size, f) != (size_t)size) {
        snprintf(why, cap, "cannot be read");
    } else {
        rc = cache_file_parse(buf, (size_t)size, key, out, why, cap);
    }
    free(buf);
    fclose(f);
    return rc;
}

int cache_file_parse(const uint8_t *buf, size_t size, const cache_key *key, cache_set *out,
                     char *why, size_t cap)
{
    if (size < HEADER + TRAILER) {
        snprintf(why, cap, "truncated: %zu bytes, less than a header", size);
        return -1;
    }
    uint8_t want[HEADER];
    uint64_t count = le_get(buf + 32, 8);
    put_header(want, key, count);
    uint64_t expect = count <= MAX_COUNT ? HEADER + RECORD * count + TRAILER : 0;
    if (memcmp(buf, MAGIC, 8) != 0)
        snprintf(why, cap, "not a light cache file");
    else if (memcmp(buf, want, HEADER) != 0)
        snprintf(why, cap, "made for another scene, settings or format version");
    else if ((uint64_t)size != expect)
        snprintf(why, cap, "truncated or padded: %zu bytes where %llu caches take %llu",
                 size, (unsigned long long)count, (unsigned long long)expect);
    else if (le_get(buf + size - TRAILER, 8) != fnv1a64(FNV1A64_OFFSET, buf, size - TRAILER))
        snprintf(why, cap, "checksum mismatch (damaged)");
    else if (decode(buf, count, key, out) != 0)
        snprintf(why, cap, "out of memory for %llu caches", (unsigned long long)count);
    else
        return 0;
    return -1;
}

int cache_file_write(const char *path, const cache_key *key, const cache_set *set, char *why,
                     size_t cap)
{
    if (folder_create_for(path, why, cap) != 0)
        return -1;
    size_t size = HEADER + RECORD * set->count + TRAILER;
    /* not xalloc: the scene's cache count: not saved, said in why */
    uint8_t *buf = malloc(size);
    if (!buf) {
        snprintf(why, cap, "out of memory");
        return -1;
    }
    put_header(buf, key, set->count);
    for (size_t i = 0; i < set->count; i++) {
        const light_cache *c = &set->caches[i];
        const float f[CACHE_RECORD_FLOATS] = {c->position[0], c->position[1], c->position[2],
                                              c->normal[0], c->normal[1], c->normal[2],
                                              c->area, c->roughness};
        for (int k = 0; k < CACHE_RECORD_FLOATS; k++) {
            uint32_t bits;
            memcpy(&bits, &f[k], 4);
            le_put(buf + HEADER + RECORD * i + 4 * k, bits, 4);
        }
    }
    le_put(buf + size - TRAILER, fnv1a64(FNV1A64_OFFSET, buf, size - TRAILER), 8);
    char tmp[600];
    snprintf(tmp, sizeof tmp, "%s.XXXXXX", path);
    int fd = mkstemp(tmp); /* O_CREAT | O_EXCL: never a planted name or symlink */
    FILE *f = fd >= 0 && fchmod(fd, 0644) == 0 ? fdopen(fd, "wb") : NULL;
    int ok = f && fwrite(buf, 1, size, f) == size;
    if (f && fclose(f) != 0)
        ok = 0;
    else if (!f && fd >= 0)
        close(fd);
    if (!ok || rename(tmp, path) != 0) {
        snprintf(why, cap, "cannot write %s: %s", f ? path : tmp, strerror(errno));
        if (fd >= 0)
            remove(tmp);
        free(buf);
        return -1;
    }
    free(buf);
    return 0;
}

int cache_folder_check(const char *dir, char *why, size_t cap)
{
    struct stat st;
    if (lstat(dir, &st) != 0)
        return 0; /* made by cache_file_write(), as this user's */
    if (S_ISLNK(st.st_mode) && stat(dir, &st) != 0)
        return 0;
    uid_t me = geteuid();
    if (!S_ISDIR(st.st_mode))
        snprintf(why, cap, "%s is not a folder", dir);
    else if (st.st_uid != me && st.st_uid != 0)
        snprintf(why, cap, "folder %s belongs to user %ld, not to this one (%ld): another "
                 "user could replace its files", dir, (long)st.st_uid, (long)me);
    else if ((st.st_mode & S_IWOTH) && !(st.st_mode & S_ISVTX))
        snprintf(why, cap, "folder %s is writable by all without the sticky bit: anyone "
                 "could replace its files (chmod o-w or +t it)", dir);
    else
        return 0;
    return -1;
}

int cache_store_get(const scene *s, const cache_place_desc *d, const char *dir, cache_set *out,
                    cache_store_report *rep, char *err, size_t errlen)
{
    double t0 = clock_now_ms();
    memset(rep, 0, sizeof *rep);
    cache_key key = cache_key_of(s, d);
    char why[700];
    if (dir && cache_folder_check(dir, why, sizeof why) != 0) {
        snprintf(rep->note, sizeof rep->note, "light caches: not stored (%s): placed at every "
                 "start", why);
        dir = NULL;
    }
    if (dir) {
        cache_file_path(dir, &key, rep->path, sizeof rep->path);
        if (cache_file_read(rep->path, &key, out, why, sizeof why) == 0) {
            rep->from_file = 1;
            rep->ms = clock_now_ms() - t0;
            return 0;
        }
        if (strcmp(why, "absent") != 0)
            snprintf(rep->note, sizeof rep->note, "light caches: %s: %s; placed again",
                     rep->path, why);
    }
    if (cache_place(s, d, out, err, errlen) != 0)
        return -1;
    if (dir && cache_file_write(rep->path, &key, out, why, sizeof why) != 0)
        snprintf(rep->note, sizeof rep->note, "light caches: not stored (%s): placed at every "
                 "start", why);
    rep->ms = clock_now_ms() - t0;
    return 0;
}
