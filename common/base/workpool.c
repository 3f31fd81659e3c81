#include "base/workpool.h"

#include <pthread.h>
#include <stdlib.h>
#include <unistd.h>

#include "base/xalloc.h"

enum { MAX_THREADS = 256 };

struct workpool {
    int threads;
    pthread_t workers[MAX_THREADS];
    pthread_mutex_t lock;
    pthread_cond_t wake, done;
    /* The current job: items are handed out by a counter under the lock. Which thread
     * runs an item never changes what the item computes. */
    workpool_fn fn;
    void *ctx;
    int items, next, finished;
    unsigned long generation;
    int busy_workers;
    int stop;
};

/* A worker that woke late for a finished job must not take items of the next one. */
static int take_item(workpool *p, unsigned long generation)
{
    int i = -1;
    if (p->generation == generation && p->next < p->items)
        i = p->next++;
    return i;
}

static void run_items(workpool *p, workpool_fn fn, void *ctx, unsigned long generation)
{
    for (;;) {
        pthread_mutex_lock(&p->lock);
        int i = take_item(p, generation);
        pthread_mutex_unlock(&p->lock);
        if (i < 0)
            return;
        fn(ctx, i);
        pthread_mutex_lock(&p->lock);
        p->finished++;
        pthread_mutex_unlock(&p->lock);
    }
}

static void *worker_main(void *arg)
{
    workpool *p = arg;
    unsigned long seen = 0;
    pthread_mutex_lock(&p->lock);
    for (;;) {
        while (!p->stop && p->generation == seen)
            pthread_cond_wait(&p->wake, &p->lock);
        if (p->stop)
            break;
        seen = p->generation;
        workpool_fn fn = p->fn;
        void *ctx = p->ctx;
        p->busy_workers++;
        pthread_mutex_unlock(&p->lock);
        run_items(p, fn, ctx, seen);
        pthread_mutex_lock(&p->lock);
        p->busy_workers--;
        pthread_cond_broadcast(&p->done);
    }
    pthread_mutex_unlock(&p->lock);
    return NULL;
}

workpool *workpool_create(int threads)
{
    if (threads <= 0) {
        long n = sysconf(_SC_NPROCESSORS_ONLN);
        threads = n > 0 ? (int)n : 1;
    }
    if (threads > MAX_THREADS)
        threads = MAX_THREADS;
    workpool *p = xcalloc(1, sizeof *p);
    p->threads = threads;
    if (pthread_mutex_init(&p->lock, NULL) != 0) {
        free(p);
        return NULL;
    }
    pthread_cond_init(&p->wake, NULL);
    pthread_cond_init(&p->done, NULL);
    for (int t = 0; t < threads - 1; t++) {
        if (pthread_create(&p->workers[t], NULL, worker_main, p) != 0) {
            p->threads = t + 1;
            workpool_destroy(p);
            return NULL;
        }
    }
    return p;
}

void workpool_destroy(workpool *p)
{
    if (!p)
        return;
    pthread_mutex_lock(&p->lock);
    p->stop = 1;
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);
    for (int t = 0; t < p->threads - 1; t++)
        pthread_join(p->workers[t], NULL);
    pthread_cond_destroy(&p->wake);
    pthread_cond_destroy(&p->done);
    pthread_mutex_destroy(&p->lock);
    free(p);
}

int workpool_threads(const workpool *p)
{
    return p ? p->threads : 1;
}

void workpool_run(workpool *p, int items, workpool_fn fn, void *ctx)
{
    if (items <= 0)
        return;
    if (!p || p->threads == 1 || items == 1) {
        for (int i = 0; i < items; i++)
            fn(ctx, i);
        return;
    }
    pthread_mutex_lock(&p->lock);
    p->fn = fn;
    p->ctx = ctx;
    p->items = items;
    p->next = 0;
    p->finished = 0;
    unsigned long generation = ++p->generation;
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->lock);
    run_items(p, fn, ctx, generation);
    /* Wait until every item is done and no worker still holds this job. */
    pthread_mutex_lock(&p->lock);
    while (p->finished < p->items || p->busy_workers > 0)
        pthread_cond_wait(&p->done, &p->lock);
    pthread_mutex_unlock(&p->lock);
}
