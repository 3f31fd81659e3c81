/* setting: one named, typed, ranged value a user may set, described once.
 *
 * A table of settings is the one place that says a value's name (the command-line option
 * without "--", the cluster config's key and the parameter store's key), its type, its
 * range, its default and its help line. From the row come the parser every program uses
 * (the same reason text everywhere: "a whole number in 64..4096"), the clamp every node
 * applies to what it receives, the text --help shows and the field it is read into.
 *
 * Values are 32-bit: a whole number, a float or the index of a choice. A row's offset says
 * where its value lives in its owner's struct (an int32_t, an int-sized enum or a float).
 * Nothing here knows any program's settings. */
#ifndef CAVELIGHT_SETTING_H
#define CAVELIGHT_SETTING_H

#include <stddef.h>
#include <stdint.h>

typedef enum setting_kind {
    SETTING_INT = 0,
    SETTING_FLOAT,
    SETTING_CHOICE,
} setting_kind;

enum {
    SETTING_POW2 = 1u << 0,    /* INT: a power of two as well */
    SETTING_REBUILD = 1u << 1, /* a change rebuilds its owner's state (a lattice, a map size);
                                  the others may change every frame at no extra cost */
};

typedef union setting_value {
    int32_t i; /* INT, CHOICE (the index) */
    float f;   /* FLOAT */
} setting_value;

typedef struct setting {
    const char *name;            /* "vpl-count" */
    const char *arg;             /* --help's placeholder ("N"); CHOICE: NULL, names shown */
    setting_kind kind;
    double min, max;             /* INT, FLOAT: the accepted range, both ends included */
    double def;                  /* the default; CHOICE: its index */
    const char *const *choices;  /* CHOICE: the names, in index order */
    int choice_count;
    unsigned flags;
    size_t offset;               /* of the value's field in its owner's struct */
    const char *help;            /* one line; "\n" starts a continuation line */
} setting;

setting_value setting_default(const setting *s);
/* The text as a value of s: NULL, or the reason it is refused ("a whole number in
 * 64..4096", "one of exact, ism or ism-splat", "a power of two in 8..256"). */
const char *setting_parse(const setting *s, const char *text, setting_value *out);
/* What a receiver does with a value it did not check itself: a NaN, an unknown choice, or
 * zero or less where the range is positive (a value that means nothing there, as a size or
 * a gamma of 0) becomes the default; another number outside the range its nearest end; a
 * whole number that is no power of two where one is wanted the power of two below it.
 * Returns 1 if changed. */
int setting_clamp(const setting *s, setting_value *v);
/* "256", "0.8", "ism". */
void setting_format(const setting *s, setting_value v, char *buf, size_t cap);
/* --help's argument: arg, or the choices joined by '|'. */
void setting_arg(const setting *s, char *buf, size_t cap);
/* The field at s->offset of owner. */
setting_value setting_load(const setting *s, const void *owner);
void setting_store(const setting *s, setting_value v, void *owner);
/* The index of the row named name among n rows, or -1. */
int setting_find(const setting *rows, int n, const char *name);

#endif
