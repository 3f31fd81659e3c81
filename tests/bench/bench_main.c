/* cavelight-bench: benchmarks that print one JSON line each. One subcommand per file;
 * each subcommand's options are its own table (bench_parse(), base/cli.h). */
#include <stdio.h>
#include <string.h>

#include "bench.h"

static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
} benches[] = {
    {"lpv", bench_lpv}, {"cluster", bench_cluster}, {"frame", bench_frame},
    {"input", bench_input}, {"accuracy", bench_accuracy}, {"reference", bench_reference},
    {"move", bench_move},
};
enum { BENCH_COUNT = sizeof benches / sizeof benches[0] };

/* Every subcommand's own --help, one after the other. */
static int help(void)
{
    printf("usage: cavelight-bench BENCHMARK [options]   (each prints one JSON line)\n"
           "benchmarks:");
    for (int i = 0; i < BENCH_COUNT; i++)
        printf(" %s", benches[i].name);
    printf("\n");
    for (int i = 0; i < BENCH_COUNT; i++) {
        char *argv[] = {(char *)benches[i].name, "--help", NULL};
        printf("\n");
        fflush(stdout);
        if (benches[i].run(2, argv) != 0)
            return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0))
        return help();
    if (argc >= 2)
        for (int i = 0; i < BENCH_COUNT; i++)
            if (strcmp(argv[1], benches[i].name) == 0)
                return benches[i].run(argc - 1, argv + 1);
    if (argc < 2) {
        fprintf(stderr, "cavelight-bench: name a benchmark: lpv, cluster, frame, input, accuracy, "
                "reference or move (see --help)\n");
        return 2;
    }
    const char *names[BENCH_COUNT];
    for (int i = 0; i < BENCH_COUNT; i++)
        names[i] = benches[i].name;
    const char *close = cli_nearest(argv[1], names, BENCH_COUNT);
    fprintf(stderr, "cavelight-bench: unknown benchmark '%s'%s%s%s (see --help)\n", argv[1],
            close ? ": did you mean " : "", close ? close : "", close ? "?" : "");
    return 2;
}
