/* json_depth: how deep a JSON text nests, counted before any parser sees it.
 *
 * The parsers the programs use recurse once per level of [ and { (cJSON for configs,
 * nlohmann's and tinygltf's for glTF), so a small file of 200,000 nested arrays overflows the
 * stack. Every reader of JSON calls json_depth_check() on the whole text first: a pre-scan
 * that counts [ and { outside strings, far below what any thread's stack holds. */
#ifndef CAVELIGHT_JSON_DEPTH_H
#define CAVELIGHT_JSON_DEPTH_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Deeper than any glTF or config the programs read needs (glTF's own structure nests 6;
 * "extras" may hold more), and a few hundred kB of stack at most in any parser. */
enum { JSON_DEPTH_MAX = 128 };

/* 0 when text (n bytes, NUL not needed) nests at most JSON_DEPTH_MAX deep; else -1 and one
 * line in err without the file's name: "JSON nested deeper than 128 levels (at byte B)". */
int json_depth_check(const char *text, size_t n, char *err, size_t errlen);

#ifdef __cplusplus
}
#endif

#endif
