#include "base/ratelog.h"

int ratelog_event(ratelog *r, double now_ms, uint64_t *skipped)
{
    r->count++;
    if (r->count > RATELOG_BURST && now_ms < r->next_ms) {
        r->skipped++;
        return 0;
    }
    if (skipped)
        *skipped = r->skipped;
    r->skipped = 0;
    if (r->count >= RATELOG_BURST)
        r->next_ms = now_ms + RATELOG_INTERVAL_MS;
    return 1;
}
