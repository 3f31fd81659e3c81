#include "gi/ao_cost.h"

#include "gi/ldm/ldm_map.h"

const char *ao_check(const frame_params *p)
{
    static _Thread_local char why[256];
    if (p->ao != FRAME_AO_LDM)
        return NULL;
    return ldm_memory_check(p->ao_directions, p->ao_resolution, p->ldm_layers,
                            p->ldm_memory_mb, "ao", why, sizeof why);
}
