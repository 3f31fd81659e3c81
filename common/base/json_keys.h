/* json_keys: which keys of a JSON document its parser reads, so that the keys it never
 * reads (misspelt, or put in the wrong section) can be named, each with the nearest key
 * that is read in the same object.
 *
 * A parser looks up every object member through json_keys_get() instead of
 * cJSON_GetObjectItemCaseSensitive(). The reads form the table of valid keys, object by
 * object: each section's valid keys are exactly those that the code parsing that section
 * asks for, so a section gains a key where its parser reads it and no list elsewhere has
 * to follow. After a successful parse, json_keys_unknown() walks the document from the
 * root through the members that were read (objects, and arrays of objects) and reports
 * every member whose key was not asked for in its object.
 *
 * It does not judge values (the parser does) and says nothing about objects the parser
 * never looked into: a member whose own key is unknown is reported once, not its insides. */
#ifndef CAVELIGHT_JSON_KEYS_H
#define CAVELIGHT_JSON_KEYS_H

#include <stddef.h>
#include <cjson/cJSON.h>

typedef struct json_keys json_keys;

json_keys *json_keys_create(void); /* never NULL (xalloc) */
void json_keys_destroy(json_keys *k);

/* cJSON_GetObjectItemCaseSensitive(object, key), recording that object reads key (also
 * when the member is absent). object may be NULL (returns NULL, records nothing). */
const cJSON *json_keys_get(json_keys *k, const cJSON *object, const char *key);

/* One unknown member: field is its path ("nodes[0].resolutoin"), key its key, nearest the
 * closest key read in the same object or NULL when none is close, valid those keys
 * comma-separated ("" when the object read none). */
typedef void (*json_keys_report)(void *user, const char *field, const char *key, const char *nearest,
                                 const char *valid);
/* Reports every unknown member under root, in document order; returns their count. */
int json_keys_unknown(const json_keys *k, const cJSON *root, json_keys_report report, void *user);

/* For a required key that object lacks: the member of object that looks like it misspelt
 * ("nmae" for "name", by cli_nearest()'s rule), or NULL. */
const char *json_keys_misspelt(const cJSON *object, const char *key);

/* The usual words for one unknown member, into out: 'unknown key "resolutoin" (did you
 * mean "resolution"?)' or 'unknown key "x" (keys here: a, b)'. */
void json_keys_describe(const char *key, const char *nearest, const char *valid, char *out, size_t cap);

#endif
