/* cache_file: the light caches of a scene (cache_place.h) kept on disk, so that a node
 * places them once per scene and settings, not on every start, and a CAVE's nodes that
 * share a folder place them once between them.
 *
 * A file holds one placement and says what it was made from: its key (the format version,
 * a hash of the scene's triangles, normals and their materials' roughness, the cube edge
 * and angle tolerance) and a checksum of every byte before it. Its name is the key's hash, so another scene or other
 * settings never meet it; a file whose key, size or checksum does not match (damaged,
 * truncated, another build's format) is never trusted: the caches are placed again and the
 * file rewritten. Files are written to a temporary name in the same folder and renamed, so
 * a reader sees a whole file or none. A folder that cannot be created or written (read-only,
 * full) costs only the placement's time: the caches are used, and the note says why they
 * were not stored. The temporary is made by mkstemp() (O_EXCL: a name planted in the folder,
 * a symlink to a file elsewhere, is never opened) and a folder that others could plant or
 * swap files in (writable by all without the sticky bit, or owned by another user than this
 * one or root) is not used at all: neither read nor written, with a note saying why.
 *
 * Where: CAVELIGHT_CACHE_DIR when set, else $XDG_CACHE_HOME/cavelight, else
 * $HOME/.cache/cavelight (the XDG base directory rules); no folder (none of them set): no
 * file, placed every time. No GL. */
#ifndef CAVELIGHT_CACHE_FILE_H
#define CAVELIGHT_CACHE_FILE_H

#include <stddef.h>
#include <stdint.h>

#include "gi/caches/cache_place.h"
#include "scene/scene.h"

/* Raised whenever the placement or the file's layout changes: older files are then stale. */
enum { CACHE_FILE_VERSION = 2 };
/* Floats per cache in a file: position, normal, area, roughness (light_cache). */
enum { CACHE_RECORD_FLOATS = 8 };

typedef struct cache_key {
    uint32_t version;
    uint64_t scene_hash;   /* cache_scene_hash() */
    float edge, angle;     /* cache_place_desc */
} cache_key;

/* FNV-1a over the triangle count and every position and normal's float bits. */
uint64_t cache_scene_hash(const scene *s);
cache_key cache_key_of(const scene *s, const cache_place_desc *d);
/* The folder (rules above) into out; 0, or -1 when there is none. */
int cache_file_dir(char *out, size_t cap);
/* DIR/caches-HASH.bin for key. */
void cache_file_path(const char *dir, const cache_key *key, char *out, size_t cap);
/* 0 with the caches, or -1 with why it is not usable ("absent", "truncated: 100 of 140
 * bytes", "checksum mismatch", "made for another scene or settings", ...). */
int cache_file_read(const char *path, const cache_key *key, cache_set *out, char *why,
                    size_t cap);
/* cache_file_read()'s checks and decoding of a whole file's bytes (the fuzz target's way in). */
int cache_file_parse(const uint8_t *buf, size_t size, const cache_key *key, cache_set *out,
                     char *why, size_t cap);
/* 0 when the folder dir is safe to keep caches in (above), or when it does not exist yet;
 * else -1 with why. */
int cache_folder_check(const char *dir, char *why, size_t cap);
/* 0, or -1 with why (the folder or file could not be written); the folder is created. */
int cache_file_write(const char *path, const cache_key *key, const cache_set *set, char *why,
                     size_t cap);

/* How cache_store_get() got them. */
typedef struct cache_store_report {
    int from_file;         /* 1: read from the file; 0: placed now */
    double ms;             /* time taken */
    char path[512];        /* the file ("" without a folder) */
    char note[1400];        /* "" or one line: a file not trusted, or not written, and why */
} cache_store_report;

/* The caches of s for d: from the file in dir (NULL: no file) when it is valid, else placed
 * and written there. 0, or -1 with one line in err (cache_place()'s). */
int cache_store_get(const scene *s, const cache_place_desc *d, const char *dir, cache_set *out,
                    cache_store_report *rep, char *err, size_t errlen);

#endif
