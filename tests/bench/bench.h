/* Benchmark subcommands of cavelight-bench. Each prints one JSON object on one line. */
#ifndef CAVELIGHT_BENCH_H
#define CAVELIGHT_BENCH_H

#include "base/cli.h"

/* One option of a benchmark: a whole number in [lo, hi] (value), a text (text), or one
 * of choices (its index into value); or every GI and display setting of the node
 * (gi_settings.h) into a frame (frame). The variable's value before parsing is the default
 * --help shows. */
struct frame_params;
typedef struct bench_option {
    const char *name, *arg, *help;
    int *value;
    int lo, hi;
    const char **text;
    const char *const *choices;
    int choice_count;
    struct frame_params *frame;
} bench_option;

/* Parses a benchmark's options (argv[0] is its name). Returns 0, 1 when --help was
 * printed (exit 0), -1 after one line on stderr (exit 2). */
int bench_parse(const char *bench, const char *summary, const bench_option *opts, int count,
                int argc, char **argv);
#define BENCH_INT(name_, arg_, help_, ptr, lo_, hi_)                                           \
    {.name = name_, .arg = arg_, .help = help_, .value = ptr, .lo = lo_, .hi = hi_}
#define BENCH_TEXT(name_, arg_, help_, ptr) {.name = name_, .arg = arg_, .help = help_, .text = ptr}
#define BENCH_CHOICE(name_, arg_, help_, ptr, names)                                           \
    {.name = name_, .arg = arg_, .help = help_, .value = ptr, .choices = names,                 \
     .choice_count = (int)(sizeof names / sizeof *names)}
#define BENCH_SETTINGS(frame_) {.name = "", .frame = frame_}
#define BENCH_PARSE(bench, summary, opts, argc, argv)                                          \
    bench_parse(bench, summary, opts, (int)(sizeof opts / sizeof *opts), argc, argv)

int bench_lpv(int argc, char **argv);
int bench_cluster(int argc, char **argv);
int bench_frame(int argc, char **argv);
int bench_input(int argc, char **argv);
int bench_accuracy(int argc, char **argv);
int bench_reference(int argc, char **argv);
int bench_move(int argc, char **argv);

#endif
