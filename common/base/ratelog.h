/* ratelog: the rate limit for log lines that peers can trigger (bad messages, strangers,
 * lost trackers), so that a flood cannot fill a disk or a terminal.
 *
 * One ratelog per kind of event, zero-initialised. The first RATELOG_BURST events are
 * printed; after that at most one per RATELOG_INTERVAL_MS, and that line says how many
 * were left out since the previous one. Every event is counted either way. The module
 * decides only whether to print; the caller prints. Not thread-safe: one owner each. */
#ifndef CAVELIGHT_RATELOG_H
#define CAVELIGHT_RATELOG_H

#include <stdint.h>

enum { RATELOG_BURST = 5, RATELOG_INTERVAL_MS = 10000 };

typedef struct ratelog {
    uint64_t count;       /* events so far */
    uint64_t skipped;     /* events not printed since the last printed one */
    double next_ms;       /* clock_now_ms() from which the next line may print */
} ratelog;

/* Counts one event at now_ms. Returns 1 when the caller should print it; *skipped (if not
 * NULL) then holds how many events were left out just before this one. */
int ratelog_event(ratelog *r, double now_ms, uint64_t *skipped);

#endif
