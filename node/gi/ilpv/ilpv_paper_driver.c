/* ilpv_paper_driver: see ilpv_paper_driver.h. */
#include "gi/ilpv/ilpv_paper_driver.h"

#include <stdio.h>

#include "gi/ilpv/lpv_paper.h"

int ilpv_paper_driver_init(ilpv_paper_driver *d, const gl_functions *gl, const lattice_desc *lat,
                           const lpv_blockers *blockers, workpool *pool, char *err, size_t errlen)
{
    *d = (ilpv_paper_driver){.blockers = blockers, .pool = pool};
    if (lpv_paper_init(&d->lpv, lat) != 0) {
        snprintf(err, errlen, "renderer: out of memory for a %dx%dx%d lattice", lat->n[0],
                 lat->n[1], lat->n[2]);
        return -1;
    }
    if (gl) {
        ilpv_gl_variant v = {.transport = LPV_TRANSPORT_PAPER};
        if (!(d->gl = ilpv_gl_create(gl, lat, blockers, &v, err, errlen)))
            return -1;
    }
    return 0;
}

void ilpv_paper_driver_free(ilpv_paper_driver *d)
{
    if (d->gl)
        ilpv_gl_destroy(d->gl);
    lpv_paper_free(&d->lpv);
    *d = (ilpv_paper_driver){0};
}

void ilpv_paper_driver_reset(ilpv_paper_driver *d)
{
    lpv_paper_reset(&d->lpv);
}

lpv_volume *ilpv_paper_driver_injection(ilpv_paper_driver *d)
{
    lpv_paper_begin_frame(&d->lpv);
    return lpv_paper_injection(&d->lpv);
}

void ilpv_paper_driver_run(ilpv_paper_driver *d, const ilpv_paper_driver_frame *f)
{
    float cell = d->lpv.lattice.cell;
    float la = lpv_paper_step_probability(f->absorption, cell);
    float ls = lpv_paper_step_probability(f->scattering, cell);
    if (!d->gl) {
        lpv_paper_frame(&d->lpv, &(lpv_paper_frame_desc){
            .steps = f->steps, .lambda_incr = f->lambda_incr, .emitted_energy = f->emitted_energy,
            .propagate = {.transport = LPV_TRANSPORT_PAPER, .blockers = d->blockers,
                          .absorption = la, .scattering = ls, .pool = d->pool}});
        return;
    }
    lpv_paper_history *h = &d->lpv.history;
    lpv_paper_merge m = lpv_paper_merge_factors(h, f->lambda_incr, f->emitted_energy);
    d->lpv.current = 0;
    ilpv_gl_paper_frame(d->gl, &d->lpv.injected, m, f->steps, la, ls, &d->lpv.volume[0]);
    lpv_paper_history_advance(h, f->emitted_energy);
}

const lpv_volume *ilpv_paper_driver_result(const ilpv_paper_driver *d)
{
    return lpv_paper_result(&d->lpv);
}

void ilpv_paper_driver_steps(ilpv_paper_driver *d, int steps)
{
    lpv_paper_reset(&d->lpv);
    if (d->gl) {
        ilpv_gl_paper_steps(d->gl, steps, 1, 0.0f, 0.0f);
        return;
    }
    lpv_propagate_desc pd = {.transport = LPV_TRANSPORT_PAPER, .blockers = d->blockers, .pool = d->pool};
    for (int s = 0; s < steps; s++) {
        lpv_propagate_step(&pd, &d->lpv.volume[d->lpv.current], &d->lpv.volume[1 - d->lpv.current]);
        d->lpv.current = 1 - d->lpv.current;
    }
}
