#include "lpv/lpv_classic.h"

#include "base/fpmode.h"

#include <string.h>

int lpv_classic_init(lpv_classic *c, const lattice_desc *lat)
{
    memset(c, 0, sizeof *c);
    lpv_volume *all[] = {&c->near, &c->shell, &c->work[0], &c->work[1], &c->accum};
    for (size_t i = 0; lat && i < sizeof all / sizeof all[0]; i++)
        if (lpv_volume_init(all[i], lat->n, LPV_LIGHT_CHANNELS) != 0) {
            lpv_classic_free(c);
            return -1;
        }
    return lat ? 0 : -1;
}

void lpv_classic_free(lpv_classic *c)
{
    lpv_volume *all[] = {&c->near, &c->shell, &c->work[0], &c->work[1], &c->accum};
    for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
        lpv_volume_free(all[i]);
    lpv_splat_free(&c->splat);
    memset(c, 0, sizeof *c);
}

int lpv_classic_frame(lpv_classic *c, const lpv_volume *injected, const lpv_volume *origin,
                      int steps, const lpv_propagate_desc *propagate)
{
    lpv_splat_desc sd = {injected, origin, propagate->blockers, propagate->absorption,
                         propagate->pool};
    int rc = lpv_splat_run(&c->splat, &sd, &c->near, &c->shell);
    fpmode mode = fpmode_enter();
    lpv_volume_copy(&c->accum, &c->near);
    lpv_volume_add(&c->accum, &c->shell);
    fpmode_leave(mode);
    lpv_propagate_desc pd = *propagate;
    pd.accum = &c->accum;
    const lpv_volume *src = &c->shell;
    for (int step = 0; step < steps; step++) {
        lpv_volume *dst = &c->work[step & 1];
        pd.step = (unsigned)step;
        lpv_propagate_step(&pd, src, dst);
        src = dst;
    }
    return rc;
}

const lpv_volume *lpv_classic_result(const lpv_classic *c)
{
    return &c->accum;
}
