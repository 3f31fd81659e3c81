/* json_keys: the keys a parser reads, and the ones it never does (json_keys.h). */
#include "base/json_keys.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/cli.h"
#include "base/xalloc.h"

enum { KEY_MAX = 64, VALID_MAX = 512, FIELD_MAX = 256 };

typedef struct key_read {
    const cJSON *object;
    char key[KEY_MAX];
} key_read;

struct json_keys {
    key_read *reads;
    size_t count, cap;
};

json_keys *json_keys_create(void)
{
    return xcalloc(1, sizeof(json_keys));
}

void json_keys_destroy(json_keys *k)
{
    if (!k)
        return;
    free(k->reads);
    free(k);
}

static int was_read(const json_keys *k, const cJSON *object, const char *key)
{
    for (size_t i = 0; i < k->count; i++)
        if (k->reads[i].object == object && strcmp(k->reads[i].key, key) == 0)
            return 1;
    return 0;
}

const cJSON *json_keys_get(json_keys *k, const cJSON *object, const char *key)
{
    if (!object)
        return NULL;
    if (!was_read(k, object, key) && strlen(key) < KEY_MAX) {
        if (k->count == k->cap) {
            k->cap = k->cap ? 2 * k->cap : 64;
            k->reads = xrealloc(k->reads, k->cap * sizeof *k->reads);
        }
        k->reads[k->count].object = object;
        snprintf(k->reads[k->count].key, KEY_MAX, "%s", key);
        k->count++;
    }
    return cJSON_GetObjectItemCaseSensitive(object, key);
}

typedef struct walk {
    const json_keys *k;
    json_keys_report report;
    void *user;
    int found;
} walk;

static void walk_value(walk *w, const cJSON *v, const char *path);

/* The keys object reads, as candidates and as one comma-separated list. */
static int keys_of(const json_keys *k, const cJSON *object, const char **keys, int max, char *valid)
{
    int n = 0;
    valid[0] = '\0';
    for (size_t i = 0; i < k->count && n < max; i++)
        if (k->reads[i].object == object) {
            keys[n++] = k->reads[i].key;
            size_t used = strlen(valid);
            snprintf(valid + used, VALID_MAX - used, "%s%s", used ? ", " : "", k->reads[i].key);
        }
    return n;
}

static void walk_object(walk *w, const cJSON *o, const char *path)
{
    const cJSON *m;
    cJSON_ArrayForEach(m, o) {
        char field[FIELD_MAX];
        snprintf(field, sizeof field, "%s%s%s", path, path[0] ? "." : "", m->string);
        if (was_read(w->k, o, m->string)) {
            walk_value(w, m, field);
            continue;
        }
        const char *keys[CLI_MAX_OPTIONS];
        char valid[VALID_MAX];
        int n = keys_of(w->k, o, keys, CLI_MAX_OPTIONS, valid);
        w->report(w->user, field, m->string, cli_nearest(m->string, keys, n), valid);
        w->found++;
    }
}

static void walk_value(walk *w, const cJSON *v, const char *path)
{
    if (cJSON_IsObject(v)) {
        walk_object(w, v, path);
    } else if (cJSON_IsArray(v)) {
        int i = 0;
        const cJSON *e;
        cJSON_ArrayForEach(e, v) {
            char field[FIELD_MAX];
            snprintf(field, sizeof field, "%.*s[%d]", FIELD_MAX - 16, path, i++);
            walk_value(w, e, field);
        }
    }
}

int json_keys_unknown(const json_keys *k, const cJSON *root, json_keys_report report, void *user)
{
    walk w = {.k = k, .report = report, .user = user};
    walk_value(&w, root, "");
    return w.found;
}

const char *json_keys_misspelt(const cJSON *object, const char *key)
{
    enum { MAX = 64 };
    const char *names[MAX];
    int n = 0;
    if (!cJSON_IsObject(object))
        return NULL;
    for (const cJSON *m = object->child; m && n < MAX; m = m->next)
        if (m->string && strcmp(m->string, key) != 0)
            names[n++] = m->string;
    return cli_nearest(key, names, n);
}

void json_keys_describe(const char *key, const char *nearest, const char *valid, char *out, size_t cap)
{
    if (nearest)
        snprintf(out, cap, "unknown key \"%s\" (did you mean \"%s\"?)", key, nearest);
    else if (valid[0])
        snprintf(out, cap, "unknown key \"%s\" (keys here: %s)", key, valid);
    else
        snprintf(out, cap, "unknown key \"%s\"", key);
}
