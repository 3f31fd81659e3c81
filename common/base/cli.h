/* cli: a program's command line from one table of options, through getopt_long.
 *
 * Each program describes every option once (cli_option: long name, argument, default as
 * --help shows it, group, the modes it works in, help). The same table builds getopt_long's
 * option array and the grouped --help text, so the two cannot drift apart. cli_parse()
 * hands each option to the program's set() in order; it refuses, in one line each:
 *   an unknown option, naming the closest valid one ("did you mean --frames?");
 *   a missing argument, naming the argument the option wants;
 *   a value set() rejects, with set()'s reason ("a whole number in 1..16384");
 *   an option that does not work in the mode the command line chose, naming the mode where
 *   it does (cli_check_modes(), after the program has decided its mode).
 * --help and -h print the help on stdout. Long options are matched whole (no abbreviations,
 * so that an option added later cannot change what a script meant). Nothing here knows any
 * program's options. */
#ifndef CAVELIGHT_CLI_H
#define CAVELIGHT_CLI_H

#include <stdio.h>

#include "base/setting.h"

enum { CLI_MAX_OPTIONS = 128 };

typedef struct cli_option {
    int id;              /* the program's own code for the option, passed to set() */
    const char *name;    /* long name without "--" */
    const char *arg;     /* argument placeholder ("N", "FILE"); NULL: a flag */
    const char *def;     /* the default as --help shows it; NULL: none to show */
    int group;           /* index into cli_program.groups */
    unsigned modes;      /* bit i: works in cli_program.modes[i]; 0 = in every mode */
    const char *help;    /* one line; "\n" starts an indented continuation line */
} cli_option;

typedef struct cli_program {
    const char *name;           /* "cavelight-node", for messages */
    const char *usage;          /* the usage lines printed first by --help */
    const char *const *groups;  /* group titles, in the order --help prints them */
    int group_count;
    const char *const *modes;   /* mode names ("standalone (--standalone)"); may be NULL */
    int mode_count;
    const cli_option *options;
    int count;
    const char *epilogue;       /* printed after the options, or NULL */
    /* The default of an option whose def is NULL, written into buf (the program's own
     * default values, so that --help cannot disagree with them); NULL: none to show. */
    const char *(*show_default)(void *user, int id, char *buf, size_t cap);
    /* Applies one option (value NULL for a flag). Returns NULL, or the reason the value is
     * refused ("a whole number in 1..16384"). */
    const char *(*set)(void *user, int id, const char *value);
    void *user;
} cli_program;

/* The result of one parse: which options were given. */
typedef struct cli_given {
    unsigned char given[CLI_MAX_OPTIONS]; /* by index into cli_program.options */
} cli_given;

typedef enum cli_result {
    CLI_OK = 0,
    CLI_HELP = 1,   /* --help was printed: exit 0 */
    CLI_ERROR = -1, /* one line was printed to stderr: exit 2 */
} cli_result;

/* An option row for a setting (setting.h): its name, its argument (the choices joined by
 * '|'), its default and its help; the texts live in text, which must outlive the row. */
typedef struct cli_setting_text {
    char arg[160];
    char def[32];
} cli_setting_text;
void cli_option_from_setting(const setting *s, int id, int group, unsigned modes,
                             cli_setting_text *text, cli_option *out);

/* Parses argv[1..]. Arguments that are not options (wherever they stand, and all after
 * "--") go to positional[0..max_positional); one more is refused. */
cli_result cli_parse(const cli_program *p, int argc, char **argv, const char **positional,
                     int max_positional, int *npositional, cli_given *given);
/* Refuses (one line, CLI_ERROR) the first given option that does not work in `mode`. */
cli_result cli_check_modes(const cli_program *p, const cli_given *given, int mode);
/* The option with this id, or NULL. */
const cli_option *cli_find(const cli_program *p, int id);
/* 1 when the option with this id was given. */
int cli_was_given(const cli_program *p, const cli_given *given, int id);
/* The grouped help text. */
void cli_help(const cli_program *p, FILE *f);
/* The valid option closest to `name` (without "--"), or NULL when none is close. */
const char *cli_closest(const cli_program *p, const char *name);
/* The candidate closest to word (edit distance), or NULL when none is close. */
const char *cli_nearest(const char *word, const char *const *candidates, int n);

/* Value parsers for set(): each returns NULL or the reason the text is refused. */
const char *cli_int(const char *s, int lo, int hi, int *out);
const char *cli_float(const char *s, float lo, float hi, float *out);
const char *cli_floats(const char *s, int n, float *out); /* "x,y,z" */
/* The index of s in names[0..n), or -1; cli_choice_reason() says "one of a, b, c". */
int cli_choice(const char *s, const char *const *names, int n);
const char *cli_choice_reason(const char *const *names, int n);

#endif
