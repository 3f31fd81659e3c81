/* workpool: a fixed set of worker threads that run one parallel-for at a time.
 *
 * workpool_run(pool, n, fn, ctx) calls fn(ctx, i) for i in [0, n) and returns when all
 * are done. Item i always means the same piece of work (callers split by fixed ranges,
 * never by who is free), which keeps results independent of the thread count.
 * The calling thread takes part, so a pool of T threads starts T - 1 workers. */
#ifndef CAVELIGHT_WORKPOOL_H
#define CAVELIGHT_WORKPOOL_H

typedef struct workpool workpool;
typedef void (*workpool_fn)(void *ctx, int item);

/* threads <= 0 means the number of online CPUs. Returns NULL on failure. */
workpool *workpool_create(int threads);
void workpool_destroy(workpool *pool);
int workpool_threads(const workpool *pool);
void workpool_run(workpool *pool, int items, workpool_fn fn, void *ctx);

#endif
