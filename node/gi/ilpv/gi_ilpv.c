/* gi_ilpv: the ILPV method (gi_ilpv.h). The VPLs of the RSMs every light type feeds
 * (collect_vpls(), in texel order, so the injection is deterministic) are injected
 * on the host, then the ILPV driver (gi/ilpv/ilpv.h) runs the frame on the CPU or GL backend.
 *
 * Units: an RSM texel holds the flux Phi it reflects (W). A Lambertian VPL of flux Phi
 * has radiant intensity Phi/pi cos(theta); lpv_inject adds flux * SH_cos(n), so we pass
 * Phi/pi and the lattice holds radiant intensity (W/sr) per cell, whose energy <L|1> is
 * Phi. The shading divides by the cell area to get radiance (docs/node.md).
 *
 * A frame whose inputs are unchanged and whose result has converged is skipped
 * (lpv_converge.h); the residual is computed on the host from the result the checksum is
 * taken of, so every node decides alike. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/workpool.h"
#include "base/xalloc.h"
#include "frame/light_view.h"
#include "gi/ilpv/gi_ilpv.h"
#include "gi/ilpv/ilpv_gl.h"
#include "gi/ilpv/ilpv_paper_driver.h"
#include "gl/gltools.h"
#include "frame/hud.h"
#include "gi/ilpv/ilpv.h"
#include "gi/ilpv/lattice.h"
#include "gi/ilpv/lpv_converge.h"
#include "gi/ilpv/lpv_geometry.h"
#include "gi/ilpv/lpv_inject.h"
#include "gi/ilpv/lpv_objects.h"
#include "gi/ilpv/lpv_receive.h"
#include "gi/ilpv/lpv_transfer.h"
#include "gi/vpl_source.h"

_Static_assert((int)HUD_DEFAULT_LATTICE_CELLS == (int)LATTICE_DEFAULT_AXIS_CELLS,
               "the HUD's steps bar assumes the default lattice without one");

struct gi_ilpv {
    const gl_functions *gl;
    const scene *scene;
    ilpv_settings settings;  /* backend resolved */
    lattice_desc lattice;
    lpv_blockers blockers;   /* from the scene, following its objects (lpv_objects.h) */
    lpv_objects objects;
    ilpv_gl *gl_backend;     /* the GL backend's, to upload moved blockers; NULL: CPU */
    lpv_objects_stats moved; /* the last objects() call's */
    double objects_ms;
    ilpv driver;             /* beams: the frame's sequence, on its backend */
    ilpv_paper_driver paper; /* paper: the thesis's frame (ilpv_paper_driver.h) */
    lpv_converge converge;
    uint64_t checksum;       /* of the last computed result */
    workpool *pool;
    gi_rsm_reader reader;    /* one RSM layer read back */
    lpv_vpl *vpls;           /* what the LPV injects: RSM VPLs (flux / pi) and emitters */
    size_t vpl_capacity;
    lpv_vpl *emitters;       /* one VPL per emissive triangle, built at load */
    size_t emitter_count;
    double emitter_energy;
    float *scratch;          /* 4 floats per cell, one colour at a time */
    GLuint shown[3];         /* the result, what the shading samples */
    uint32_t reset_epoch;
    int frames;
    double inject_ms, propagate_ms; /* the last frame's stages */
    gpu_timer *timer;        /* the renderer's: the stages' GPU time */
};

static const double PI = 3.14159265358979323846;

/* One VPL per emissive triangle (paper 3.3.5, gi/vpl_source.h), flux pi * L_e * area
 * passed as L_e * area (see the units above). */
static int build_emitters(gi_ilpv *r)
{
    size_t n = vpl_emitters(r->scene, NULL);
    /* not xalloc: the scene's emitters: -1 to the caller */
    vpl_emitter *e = n ? malloc(n * sizeof *e) : NULL;
    r->emitters = n ? malloc(n * sizeof *r->emitters) : NULL;
    if (n && (!e || !r->emitters)) {
        free(e);
        return -1;
    }
    vpl_emitters(r->scene, e);
    r->emitter_count = n;
    r->emitter_energy = 0;
    for (size_t i = 0; i < n; i++) {
        lpv_vpl *v = &r->emitters[i];
        for (int k = 0; k < 3; k++) {
            v->position[k] = e[i].position[k];
            v->normal[k] = e[i].normal[k];
            v->flux[k] = e[i].radiance[k] * e[i].area;
        }
        r->emitter_energy +=
            PI * e[i].area * (e[i].radiance[0] + e[i].radiance[1] + e[i].radiance[2]) / 3.0;
    }
    free(e);
    return 0;
}

/* The backend the settings ask for, with the blockers and pool the method owns. */
static int make_driver(gi_ilpv *r, const gi_desc *d, char *err, size_t errlen)
{
    int on_gl = r->settings.backend == ILPV_BACKEND_GL;
    if (r->settings.transport == LPV_TRANSPORT_PAPER) {
        int bad = ilpv_paper_driver_init(&r->paper, on_gl ? r->gl : NULL, &r->lattice, &r->blockers,
                                         r->pool, err, errlen);
        r->gl_backend = bad ? NULL : r->paper.gl;
        return bad;
    }
    ilpv_backend b;
    if (on_gl) {
        ilpv_gl_variant v = {
            .transport = LPV_TRANSPORT_BEAMS,
            .tiles = r->settings.gl_tiles == ILPV_TILES_AUTO ? !d->software
                                                             : r->settings.gl_tiles == ILPV_TILES_ON};
        ilpv_gl *g = ilpv_gl_create(r->gl, &r->lattice, &r->blockers, &v, err, errlen);
        if (!g)
            return -1;
        r->gl_backend = g;
        b = ilpv_gl_backend(g);
    } else {
        ilpv_cpu *c = ilpv_cpu_create(&r->lattice, &r->blockers, r->pool);
        if (!c)
            goto oom;
        b = ilpv_cpu_backend(c);
    }
    ilpv_desc id = {.lattice = &r->lattice, .blockers = &r->blockers, .pool = r->pool, .backend = &b};
    if (ilpv_init(&r->driver, &id) != 0)
        goto oom;
    return 0;
oom:
    snprintf(err, errlen, "renderer: out of memory for a %dx%dx%d lattice", r->lattice.n[0],
             r->lattice.n[1], r->lattice.n[2]);
    return -1;
}

static int init(gi_ilpv *r, const gi_desc *d, char *err, size_t errlen)
{
    const scene *s = r->scene;
    if (r->settings.backend == ILPV_BACKEND_AUTO)
        r->settings.backend = d->software ? ILPV_BACKEND_CPU : ILPV_BACKEND_GL;
    if (ilpv_settings_lattice(&r->settings, r->scene->bounds_min, r->scene->bounds_max, &r->lattice, err,
                              errlen) != 0)
        return -1;
    double threshold = d->no_reuse ? -1.0 : r->settings.converge_threshold;
    /* The blockers of the scene as loaded; objects() follows what moves. */
    /* not xalloc: scratch is the lattice's size (a setting): refused in err */
    if (lpv_blockers_init(&r->blockers, r->lattice.n) != 0 || build_emitters(r) != 0 ||
        lpv_objects_init(&r->objects, &r->blockers, &r->lattice, s) != 0 ||
        lpv_converge_init(&r->converge, r->lattice.n, threshold) != 0 ||
        !(r->pool = workpool_create(d->threads)) ||
        !(r->scratch = malloc(lattice_cell_count(&r->lattice) * 4 * sizeof(float)))) {
        snprintf(err, errlen, "renderer: out of memory for a %dx%dx%d lattice",
                 r->lattice.n[0], r->lattice.n[1], r->lattice.n[2]);
        return -1;
    }
    if (make_driver(r, d, err, errlen) != 0)
        return -1;
    for (int c = 0; c < 3; c++)
        r->shown[c] = gltools_texture3d(r->gl, r->lattice.n);
    return 0;
}

static void release(gi_ilpv *r)
{
    for (int c = 0; c < 3; c++)
        if (r->shown[c])
            r->gl->DeleteTextures(1, &r->shown[c]);
    if (r->driver.injected.cells)
        ilpv_free(&r->driver);
    if (r->paper.lpv.injected.cells)
        ilpv_paper_driver_free(&r->paper);
    if (r->pool)
        workpool_destroy(r->pool);
    if (r->converge.previous.cells)
        lpv_converge_free(&r->converge);
    lpv_blockers_free(&r->blockers);
    lpv_objects_free(&r->objects);
    free(r->emitters);
    free(r->vpls);
    gi_rsm_reader_free(&r->reader);
    free(r->scratch);
}

/* Every RSM texel a light reaches (gi_rsm_read_layer(), in layer then texel order) as the
 * lattice wants it, Phi / pi (the units above), then the emitters. NULL when out of
 * memory (the frame injects nothing). */
static const lpv_vpl *collect_vpls(gi_ilpv *r, const gi_rsm *rsm, size_t *count)
{
    size_t texels = (size_t)rsm->size * rsm->size, n = 0;
    size_t need = (size_t)rsm->layers * texels + r->emitter_count;
    if (need > r->vpl_capacity) {
        /* not xalloc: the RSM size (a setting) and the scene's emitters: no VPLs this frame */
        lpv_vpl *v = realloc(r->vpls, need * sizeof *v);
        if (!v) {
            *count = 0;
            return NULL;
        }
        r->vpls = v;
        r->vpl_capacity = need;
    }
    for (int layer = 0; layer < rsm->layers; layer++) {
        const float *pos, *nrm, *flux;
        if (gi_rsm_read_layer(&r->reader, r->gl, rsm, layer, &pos, &nrm, &flux) != 0)
            break;
        for (size_t i = 0; i < texels; i++) {
            const float *f = flux + 4 * i;
            if (pos[4 * i + 3] == 0.0f || !(f[0] > 0 || f[1] > 0 || f[2] > 0))
                continue;
            lpv_vpl *v = &r->vpls[n++];
            memcpy(v->position, pos + 4 * i, sizeof v->position);
            memcpy(v->normal, nrm + 4 * i, sizeof v->normal);
            for (int k = 0; k < 3; k++)
                v->flux[k] = f[k] * (float)(1.0 / PI);
        }
    }
    if (r->emitter_count) /* a scene without emitters has no emitter array */
        memcpy(r->vpls + n, r->emitters, r->emitter_count * sizeof *r->emitters);
    *count = n + r->emitter_count;
    return r->vpls;
}

/* Emitted energy for the incremental merge, from the lights' parameters (paper 3.4). */
static double emitted_energy(const gi_ilpv *r, const frame_params *p)
{
    double e = r->emitter_energy;
    for (int i = 0; i < p->light_count && i < FRAME_MAX_LIGHTS; i++)
        e += light_power(&p->lights[i], r->scene);
    return e;
}

/* The clocks between the stages inject and propagate: host ms and the GPU timer. */
typedef struct stage_clock {
    double t1;               /* host: when propagate began */
    int h;                   /* the running GPU stage */
} stage_clock;

static void next_stage(gi_ilpv *r, stage_clock *c)
{
    c->t1 = clock_now_ms();
    gpu_timer_end(r->timer, c->h);
    c->h = gpu_timer_begin(r->timer, "propagate");
}

static int is_paper(const gi_ilpv *r)
{
    return r->settings.transport == LPV_TRANSPORT_PAPER;
}

/* The thesis's frame: its injection without origins or splat, classic as lambda 0. */
static void frame_paper(gi_ilpv *r, const frame_params *p, const lpv_vpl *vpls, size_t count,
                        stage_clock *c)
{
    lpv_inject_vpls(ilpv_paper_driver_injection(&r->paper), NULL, &r->lattice, vpls, count, NULL);
    next_stage(r, c);
    int classic = r->settings.mode == ILPV_MODE_CLASSIC;
    ilpv_paper_driver_run(&r->paper, &(ilpv_paper_driver_frame){
        .steps = p->lpv_steps, .lambda_incr = classic ? 0.0f : p->lambda_incr,
        .emitted_energy = emitted_energy(r, p), .absorption = p->absorption,
        .scattering = p->scattering});
}

static void frame_beams(gi_ilpv *r, const frame_params *p, const lpv_vpl *vpls, size_t count,
                        stage_clock *c)
{
    ilpv_begin_frame(&r->driver);
    lpv_inject_vpls(ilpv_injection(&r->driver), ilpv_origin(&r->driver), &r->lattice, vpls,
                    count, NULL);
    next_stage(r, c);
    ilpv_frame(&r->driver, &(ilpv_frame_desc){
        .steps = p->lpv_steps, .lambda_incr = p->lambda_incr,
        .emitted_energy = emitted_energy(r, p), .classic = r->settings.mode == ILPV_MODE_CLASSIC,
        .absorption = lpv_transfer_step_probability(p->absorption, r->lattice.cell),
        .scattering = lpv_transfer_step_probability(p->scattering, r->lattice.cell)});
}

static void reset(gi_ilpv *r)
{
    if (is_paper(r))
        ilpv_paper_driver_reset(&r->paper);
    else
        ilpv_reset(&r->driver);
}

static uint64_t frame(void *state, const frame_params *p, const gi_rsm *rsm)
{
    gi_ilpv *r = state;
    if (r->frames == 0 || p->reset_epoch != r->reset_epoch) {
        reset(r);
        r->reset_epoch = p->reset_epoch;
    }
    double t0 = clock_now_ms();
    stage_clock c = {.h = gpu_timer_begin(r->timer, "inject")};
    size_t count;
    const lpv_vpl *vpls = collect_vpls(r, rsm, &count);
    (is_paper(r) ? frame_paper : frame_beams)(r, p, vpls, count, &c);
    const lpv_volume *result = gi_ilpv_volume(r);
    r->checksum = lpv_volume_checksum(result);
    ilpv_gl_upload(r->gl, result, r->shown, r->scratch);
    lpv_converge_end(&r->converge, result, is_paper(r) ? 0 : ilpv_pending(&r->driver), r->pool);
    gpu_timer_end(r->timer, c.h);
    r->inject_ms = c.t1 - t0;
    r->propagate_ms = clock_now_ms() - c.t1;
    r->frames++;
    return r->checksum;
}

/* Moved objects block light where they are now: their cells are redone (lpv_objects.h),
 * the GL backend gets the blockers again, and the next frame is computed. */
static void objects(void *state, const gi_objects *o)
{
    gi_ilpv *r = state;
    double t0 = clock_now_ms();
    lpv_objects_update(&r->objects, &r->blockers, &r->lattice, r->scene, o->model, o->shown, o->moved,
                       &r->moved);
    if (r->gl_backend && r->moved.cells_redone)
        ilpv_gl_update_blockers(r->gl_backend, &r->blockers);
    lpv_converge_forget(&r->converge);
    r->objects_ms = clock_now_ms() - t0;
}

static int reuse(void *state, const frame_params *p)
{
    gi_ilpv *r = state;
    int same = lpv_converge_begin(&r->converge, p);
    if (same)
        r->inject_ms = r->propagate_ms = 0;
    return same;
}

gi_ilpv *gi_ilpv_of(gi *g)
{
    return g && gi_active(g) == GI_METHOD_ID(ilpv) ? gi_state(g) : NULL;
}

const lpv_volume *gi_ilpv_volume(const gi_ilpv *r)
{
    return is_paper(r) ? ilpv_paper_driver_result(&r->paper) : ilpv_result(&r->driver);
}

lpv_transport gi_ilpv_transport(const gi_ilpv *r) { return r->settings.transport; }
ilpv_mode gi_ilpv_mode(const gi_ilpv *r) { return r->settings.mode; }
ilpv_backend_choice gi_ilpv_backend(const gi_ilpv *r) { return r->settings.backend; }
const lattice_desc *gi_ilpv_lattice(const gi_ilpv *r) { return &r->lattice; }

void gi_ilpv_stats_get(const gi_ilpv *r, gi_ilpv_stats *out)
{
    out->frames_skipped = r->converge.frames_skipped;
    out->last_residual = r->converge.residual;
    out->skipped_this_frame = r->converge.skipped;
    lpv_volume_energy(is_paper(r) ? &r->paper.lpv.injected : &r->driver.injected,
                      out->injected_energy);
}

double gi_ilpv_measure_step_ms(gi_ilpv *r, int steps)
{
    ilpv_backend *b = &r->driver.backend;
    double t0 = 0;
    for (int timed = 0; timed < 2; timed++) { /* one untimed step, then `steps` */
        int n = timed ? steps : 1;
        if (is_paper(r))
            ilpv_paper_driver_steps(&r->paper, n);
        else
            b->steps(b->state, n, (unsigned)timed, 0.0f, 0.0f);
        r->gl->Finish();
        if (!timed)
            t0 = clock_now_ms();
    }
    double ms = steps > 0 ? (clock_now_ms() - t0) / steps : 0.0;
    reset(r);
    lpv_converge_forget(&r->converge);
    return ms;
}

/* ---- the method --------------------------------------------------------------------- */

static void *create(const gi_desc *d, char *err, size_t errlen)
{
    gi_ilpv *r = xcalloc(1, sizeof *r);
    r->gl = d->gl;
    r->scene = d->scene;
    r->timer = d->timer;
    ilpv_settings_get(d->frame, &r->settings);
    if (init(r, d, err, errlen) != 0) {
        release(r);
        free(r);
        return NULL;
    }
    return r;
}

static void destroy(void *state)
{
    release(state);
    free(state);
}

static void eye_bind(void *state, const gi_eye *e)
{
    const gi_ilpv *r = state;
    const gl_functions *gl = r->gl;
    GLuint prog = e->program;
    const char *lname[3] = {"u_lpv_r", "u_lpv_g", "u_lpv_b"};
    for (int c = 0; c < 3; c++) {
        gl->ActiveTexture((GLenum)(GL_TEXTURE0 + e->first_unit + c));
        gl->BindTexture(GL_TEXTURE_3D, r->shown[c]);
        gl->Uniform1i(gl->GetUniformLocation(prog, lname[c]), e->first_unit + c);
    }
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_lpv_enabled"), r->frames > 0);
    gl->Uniform3fv(gl->GetUniformLocation(prog, "u_lpv_origin"), 1, r->lattice.origin);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_lpv_cell"), r->lattice.cell);
    gl->Uniform1f(gl->GetUniformLocation(prog, "u_lpv_behind"), LPV_RECEIVE_BEHIND);
    gl->Uniform1i(gl->GetUniformLocation(prog, "u_lpv_paper"), is_paper(r));
    gl->Uniform3i(gl->GetUniformLocation(prog, "u_lpv_size"), r->lattice.n[0], r->lattice.n[1],
                  r->lattice.n[2]);
}

/* Stages: injection, propagation; figures: the fitted lattice against the cube of its
 * longest axis, the backend, and the convergence (residual +Inf before two computed
 * frames). */
static void stats(const void *state, gi_stats *out)
{
    const gi_ilpv *r = state;
    out->stage_count = 2;
    out->stage[0] = (gi_stat){"inject", r->inject_ms};
    out->stage[1] = (gi_stat){"propagate", r->propagate_ms};
    const int *n = r->lattice.n;
    int longest = n[0] > n[1] ? (n[0] > n[2] ? n[0] : n[2]) : (n[1] > n[2] ? n[1] : n[2]);
    out->hud_cells = longest;
    const gi_stat figures[] = {
        {"lattice_x", n[0]}, {"lattice_y", n[1]}, {"lattice_z", n[2]},
        {"cells", (double)lattice_cell_count(&r->lattice)},
        {"cube_cells", (double)longest * longest * longest},
        {"gl_backend", r->settings.backend == ILPV_BACKEND_GL},
        {"skipped", r->converge.skipped},
        {"frames_skipped", (double)r->converge.frames_skipped},
        {"residual", r->converge.residual},
        {"objects_ms", r->objects_ms},
        {"objects_cells", (double)r->moved.cells_redone},
    };
    out->figure_count = (int)(sizeof figures / sizeof figures[0]);
    memcpy(out->figure, figures, sizeof figures);
}

const gi_method gi_ilpv_method = {
    .name = "ilpv",
    .shade = {"ilpv/ilpv_shade.glsl"},
    .create = create,
    .destroy = destroy,
    .reuse = reuse,
    .frame = frame,
    .eye_bind = eye_bind,
    .stats = stats,
    .objects = objects,
};
