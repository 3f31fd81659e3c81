/* Benchmark subcommands of cavelight-bench. Each prints one JSON object on one line. */
#ifndef CAVELIGHT_BENCH_H
#define CAVELIGHT_BENCH_H

int bench_lpv(int argc, char **argv);
int bench_cluster(int argc, char **argv);
int bench_frame(int argc, char **argv);
int bench_input(int argc, char **argv);
int bench_accuracy(int argc, char **argv);
int bench_reference(int argc, char **argv);

#endif
