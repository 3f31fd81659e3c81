/* cavelight-bench: benchmarks that print one JSON line each. One subcommand per file. */
#include <stdio.h>
#include <string.h>

#include "bench.h"

static const struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *usage;
} benches[] = {
    {"lpv", bench_lpv, "lpv --res N --steps S [--threads T]"},
    {"cluster", bench_cluster, "cluster --nodes N [--frames F] [--transport tcp|ipc]"},
    {"frame", bench_frame, "frame [--scene default|bunny|FILE] [--width W --height H --frames N "
                           "--rsm N --lattice N --gl egl|osmesa --lpv auto|cpu|gl --tiles auto|on|off]"},
    {"input", bench_input, "input [--iterations N]"},
    {"accuracy", bench_accuracy, "accuracy sweep|move|path|savings [--scene S --out DIR --width W "
                                 "--height H --ref-samples N ...] (scripts/chart.sh)"},
    {"reference", bench_reference, "reference [--width W --height H --samples N --bounces B --runs R]"},
};

int main(int argc, char **argv)
{
    if (argc >= 2) {
        for (size_t i = 0; i < sizeof benches / sizeof benches[0]; i++)
            if (strcmp(argv[1], benches[i].name) == 0)
                return benches[i].run(argc - 1, argv + 1);
    }
    fprintf(stderr, "usage: cavelight-bench <benchmark> [options]\n");
    for (size_t i = 0; i < sizeof benches / sizeof benches[0]; i++)
        fprintf(stderr, "  %s\n", benches[i].usage);
    return 2;
}
