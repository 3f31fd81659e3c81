#include "lpv/lpv_classic.h"

#include "base/fpmode.h"

#include <string.h>

int lpv_classic_init(lpv_classic *c, const lattice_desc *lat)
{
    memset(c, 0, sizeof *c);
    if (!lat || lpv_volume_init(&c->work[0], lat->n, LPV_LIGHT_CHANNELS) != 0 ||
        lpv_volume_init(&c->work[1], lat->n, LPV_LIGHT_CHANNELS) != 0 ||
        lpv_volume_init(&c->accum, lat->n, LPV_LIGHT_CHANNELS) != 0) {
        lpv_classic_free(c);
        return -1;
    }
    return 0;
}

void lpv_classic_free(lpv_classic *c)
{
    lpv_volume_free(&c->work[0]);
    lpv_volume_free(&c->work[1]);
    lpv_volume_free(&c->accum);
    memset(c, 0, sizeof *c);
}

typedef struct add_job {
    lpv_volume *accum;
    const lpv_volume *step;
} add_job;

/* One z slice of accum += step. */
static void add_slice(void *ctx, int z)
{
    const add_job *j = ctx;
    fpmode mode = fpmode_enter();
    size_t plane = (size_t)j->accum->n[0] * j->accum->n[1], lo = (size_t)z * plane;
    for (int c = 0; c < LPV_LIGHT_CHANNELS; c++) {
        float *a = j->accum->ch[c] + lo;
        const float *s = j->step->ch[c] + lo;
        for (size_t i = 0; i < plane; i++)
            a[i] += s[i];
    }
    fpmode_leave(mode);
}

void lpv_classic_frame(lpv_classic *c, const lpv_volume *injected, int steps,
                       const lpv_propagate_desc *propagate)
{
    lpv_volume_clear(&c->accum);
    lpv_propagate_desc pd = *propagate;
    const lpv_volume *src = injected;
    for (int step = 0; step < steps; step++) {
        lpv_volume *dst = &c->work[step & 1];
        pd.use_blocking = step > 0 && propagate->use_blocking;
        lpv_propagate_step(&pd, src, dst);
        add_job j = {&c->accum, dst};
        workpool_run(pd.pool, c->accum.n[2], add_slice, &j);
        src = dst;
    }
}

const lpv_volume *lpv_classic_result(const lpv_classic *c)
{
    return &c->accum;
}
