/* standalone: cavelight-node --standalone (see standalone.h). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/folder.h"
#include "frame/frame_params.h"
#include "glctx.h"
#include "image/image.h"
#include "lpv/lattice.h"
#include "lpv/lpv_budget.h"
#include "base/vec3.h"
#include "base/xalloc.h"
#include "frame/frame_view.h"
#include "frame/offaxis.h"
#include "reference_cli.h"
#include "renderer.h"
#include "renderer_hud.h"
#include "scene/scene_load.h"
#include "standalone.h"

void standalone_frame_params(const node_options *o, const scene *s, const renderer_view *first_eye,
                             frame_params *out)
{
    *out = o->frame;
    frame_params_lights_from_scene(out, s);
    /* No tracker: the HUD, when shown, hangs in front of the first eye. */
    if (o->have_wand)
        memcpy(out->wand + 12, o->wand, sizeof o->wand);
    else if (out->hud_layout >= 0)
        renderer_hud_wand_in_front(first_eye->view, out->wand);
}

typedef struct eye_setup {
    const char *name;
    renderer_view view;
} eye_setup;

/* Mono: one view; stereo: left and right eyes offset along the screen's (or camera's)
 * right vector, with off-axis frusta for screens and parallel axes for cameras. */
static int make_views(const node_options *o, const scene *s, const scene_camera *cam,
                      eye_setup eyes[2], int *count)
{
    float right[3], head[3];
    if (o->have_screen) {
        vec3_sub(o->screen + 3, o->screen, right);
        vec3_normalize(right);
        memcpy(head, o->eye, sizeof head);
    } else {
        memcpy(head, cam->position, sizeof head);
        float view[16];
        if (offaxis_view(cam->position, cam->target, cam->up, view) == 0)
            for (int i = 0; i < 3; i++)
                right[i] = view[4 * i]; /* the view's first row */
        else
            memcpy(right, (const float[3]){1, 0, 0}, sizeof right);
    }
    static const char *const names[3] = {"left", "mono", "right"};
    *count = o->stereo ? 2 : 1;
    float far_plane = scene_far_plane(s);
    for (int e = 0; e < *count; e++) {
        int side = o->stereo ? 2 * e - 1 : 0;
        float eye[3];
        frame_view_eye(head, right, o->eye_separation, side, eye);
        eyes[e].name = names[side + 1];
        int rc;
        if (o->have_screen) {
            float distance;
            rc = frame_view_screen(o->screen, o->screen + 3, o->screen + 6, eye, far_plane,
                                   o->width, o->height, &eyes[e].view, &distance);
            if (rc == 1)
                fprintf(stderr, "cavelight-node: the %s eye is %.3g m %s the screen's plane: "
                        "rendered from %g m in front\n", eyes[e].name, fabsf(distance),
                        distance < 0 ? "behind" : "in front of", FRAME_VIEW_NEAR_PLANE);
            rc = rc == 1 ? 0 : rc;
        } else {
            rc = frame_view_scene_camera(cam, eye, far_plane, o->width, o->height,
                                         &eyes[e].view);
        }
        if (rc != 0) {
            fprintf(stderr, "cavelight-node: degenerate camera (screen corners collinear, or "
                    "position equal to target)\n");
            return -1;
        }
    }
    return 0;
}

static double median(double *v, int n)
{
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && v[j - 1] > v[j]; j--) {
            double t = v[j];
            v[j] = v[j - 1];
            v[j - 1] = t;
        }
    return n ? (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2])) : 0;
}

static int write_images(const node_options *o, int frame, const char *eye,
                        const renderer_image *img)
{
    char path[4096], err[256];
    snprintf(path, sizeof path, "%s/frame%04d_%s.png", o->out, frame, eye);
    if (image_write_png(path, img->width, img->height, img->rgb, err, sizeof err))
        return fprintf(stderr, "cavelight-node: %s\n", err), -1;
    if (!o->pfm)
        return 0;
    const char *kind[3] = {"final", "direct", "indirect"};
    const float *data[3] = {img->final, img->direct, img->indirect};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/frame%04d_%s_%s.pfm", o->out, frame, eye, kind[k]);
        if (image_write_pfm(path, img->width, img->height, data[k], err, sizeof err))
            return fprintf(stderr, "cavelight-node: %s\n", err), -1;
    }
    return 0;
}

/* Measures every candidate lattice with this context and backend: one propagation step
 * and the LPV's other work per frame (injection, merge, upload, checksum, residual: a
 * frame with 0 steps), each the median of three tries (what a frame meets on a shared
 * machine, not its luckiest moment); then picks by lpv_budget_choose(). */
static int choose_budget(const node_options *o, const renderer_desc *base,
                         const frame_params *fp, lpv_budget_choice *choice, cJSON *report)
{
    static const int axis[] = {16, 24, 32, 48, 64};
    enum { N = sizeof axis / sizeof axis[0] };
    lpv_budget_candidate cand[N];
    char err[512];
    for (int k = 0; k < N; k++) {
        renderer_desc rd = *base;
        rd.lattice_cells = axis[k];
        rd.converge_threshold = -1;
        renderer *r = renderer_create(&rd, err, sizeof err);
        if (!r) {
            fprintf(stderr, "cavelight-node: --budget-ms: %s\n", err);
            return -1;
        }
        double step_try[3], fixed_try[3];
        frame_params none = *fp;
        none.lpv_steps = 0;
        renderer_frame_pass(r, &none); /* the first frame pays for first touches */
        for (int i = 0; i < 3; i++) {
            step_try[i] = renderer_measure_step_ms(r, 3);
            renderer_frame_pass(r, &none);
            renderer_timings t;
            renderer_get_timings(r, &t);
            fixed_try[i] = t.inject_ms + t.propagate_ms;
        }
        cand[k] = (lpv_budget_candidate){
            .axis_cells = axis[k],
            .cells = lattice_cell_count(renderer_get_lattice(r)),
            .step_ms = fmax(median(step_try, 3), 1e-6), /* a step is never free */
            .fixed_ms = median(fixed_try, 3),
        };
        renderer_destroy(r);
    }
    int classic = o->mode == RENDERER_LPV_CLASSIC;
    lpv_budget_desc bd = {.budget_ms = o->budget_ms, .candidates = cand, .count = N,
                          .min_steps = classic ? 8 : 4, .max_steps = classic ? 16 : 8};
    if (lpv_budget_choose(&bd, choice) != 0) {
        fprintf(stderr, "cavelight-node: --budget-ms: no choice from the measured costs\n");
        return -1;
    }
    const lpv_budget_candidate *c = &cand[choice->index];
    printf("cavelight-node: budget %.3g ms: lattice %d, %d step%s, predicted %.3g ms per frame%s "
           "(measured %.3g ms per step, %.3g ms per frame besides the steps)\n", o->budget_ms,
           choice->axis_cells, choice->steps, choice->steps == 1 ? "" : "s", choice->predicted_ms,
           choice->fits ? "" : ", over budget even at the coarsest lattice", c->step_ms,
           c->fixed_ms);
    cJSON *jb = cJSON_AddObjectToObject(report, "budget");
    cJSON_AddNumberToObject(jb, "budget_ms", o->budget_ms);
    cJSON_AddNumberToObject(jb, "lattice_cells", choice->axis_cells);
    cJSON_AddNumberToObject(jb, "steps", choice->steps);
    cJSON_AddNumberToObject(jb, "predicted_ms", choice->predicted_ms);
    cJSON_AddBoolToObject(jb, "fits", choice->fits);
    cJSON *jc = cJSON_AddArrayToObject(jb, "candidates");
    for (int i = 0; i < N; i++) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddNumberToObject(e, "axis_cells", cand[i].axis_cells);
        cJSON_AddNumberToObject(e, "cells", (double)cand[i].cells);
        cJSON_AddNumberToObject(e, "step_ms", cand[i].step_ms);
        cJSON_AddNumberToObject(e, "fixed_ms", cand[i].fixed_ms);
        cJSON_AddItemToArray(jc, e);
    }
    return 0;
}

/* Per-stage milliseconds of every frame run, for the report's medians. */
enum { M_RSM, M_INJECT, M_PROP, M_FRAME, M_GBUF, M_SHADE, M_FINAL, M_EYE, M_COUNT };
static const char *const stage_names[M_COUNT] = {
    "rsm_ms", "inject_ms", "propagate_ms", "frame_host_ms",
    "gbuffer_ms", "shade_ms", "final_ms", "eye_host_ms",
};

/* What the run is: context, scene, GI method and, for ILPV, its lattice, for vpl its VPLs. */
static void report_setup(cJSON *report, const node_options *o, glctx *ctx, renderer *r,
                         const scene *sc, const frame_params *fp)
{
    const lattice_desc *lat = renderer_get_lattice(r);
    const char *gi = frame_gi_name(renderer_get_gi(r));
    const char *backend = renderer_get_lpv_backend(r) == RENDERER_LPV_GL ? "gl" : "cpu";
    if (lat)
        printf("cavelight-node: %s, %s, scene %s (%zu triangles), lattice %dx%dx%d, LPV on %s\n",
               glctx_describe(ctx), glctx_renderer(ctx), o->scene, sc->triangle_count, lat->n[0],
               lat->n[1], lat->n[2], backend);
    else
        printf("cavelight-node: %s, %s, scene %s (%zu triangles), GI %s\n", glctx_describe(ctx),
               glctx_renderer(ctx), o->scene, sc->triangle_count, gi);
    cJSON_AddStringToObject(report, "scene", o->scene);
    cJSON_AddStringToObject(report, "gl", glctx_describe(ctx));
    cJSON_AddStringToObject(report, "gl_renderer", glctx_renderer(ctx));
    cJSON_AddStringToObject(report, "gi", gi);
    if (lat) {
        cJSON_AddStringToObject(report, "lpv_backend", backend);
        cJSON_AddItemToObject(report, "lattice", cJSON_CreateIntArray(lat->n, 3));
        /* The lattice follows the scene's shape: what that saves against a cube. */
        int longest = lat->n[0] > lat->n[1] ? lat->n[0] : lat->n[1];
        longest = longest > lat->n[2] ? longest : lat->n[2];
        cJSON_AddNumberToObject(report, "cells", (double)lattice_cell_count(lat));
        cJSON_AddNumberToObject(report, "cube_cells", (double)longest * longest * longest);
        cJSON_AddStringToObject(report, "lpv_mode",
                                renderer_get_lpv_mode(r) == RENDERER_LPV_CLASSIC ? "classic"
                                                                                 : "incremental");
    }
    if (renderer_get_gi(r) == FRAME_GI_VPL) {
        frame_params sane = *fp; /* the count the renderer uses */
        frame_params_sanitize(&sane);
        cJSON_AddNumberToObject(report, "vpl_count", sane.vpl_count);
        cJSON_AddNumberToObject(report, "vpl_seed", sane.vpl_seed);
        cJSON_AddStringToObject(report, "vpl_selection", vpl_selection_names[sane.vpl_selection]);
    }
    cJSON_AddNumberToObject(report, "triangles", (double)sc->triangle_count);
    cJSON_AddNumberToObject(report, "width", o->width);
    cJSON_AddNumberToObject(report, "height", o->height);
    cJSON_AddNumberToObject(report, "rsm", o->rsm > 0 ? o->rsm : RENDERER_DEFAULT_RSM_SIZE);
    cJSON_AddNumberToObject(report, "steps", fp->lpv_steps);
}

/* The eye passes of one frame: images written, stage times summed over the eyes. */
static int render_eyes(const node_options *o, renderer *r, const eye_setup *eyes, int eye_count,
                       int f, double eye_sum[4])
{
    renderer_view views[2];
    for (int e = 0; e < eye_count; e++)
        views[e] = eyes[e].view;
    renderer_screen(r, views, eye_count); /* one light assignment for both eyes */
    for (int e = 0; e < eye_count; e++) {
        renderer_image img;
        if (renderer_eye_pass(r, &eyes[e].view, o->pfm, &img) != 0) {
            fprintf(stderr, "cavelight-node: frame %d, eye %s: %s\n", f, eyes[e].name,
                    renderer_last_error(r));
            return -1;
        }
        if (o->out && write_images(o, f, eyes[e].name, &img) != 0)
            return -1;
        renderer_timings te;
        renderer_get_timings(r, &te);
        eye_sum[0] += te.gbuffer_ms;
        eye_sum[1] += te.shade_ms;
        eye_sum[2] += te.final_ms;
        eye_sum[3] += te.eye_host_ms;
    }
    return 0;
}

/* Frame f: the frame pass, every eye, the window; its line on stdout and its entry in the
 * report. Returns 0, 1 when the window was closed, -1 on an error. */
static int render_frame(const node_options *o, glctx *ctx, renderer *r, const eye_setup *eyes,
                        int eye_count, frame_params *fp, int f, cJSON *frames,
                        double stage_ms[M_COUNT])
{
    fp->version = (uint64_t)f;
    fp->time = f / 60.0;
    uint64_t checksum = renderer_frame_pass(r, fp);
    renderer_timings t;
    renderer_get_timings(r, &t);
    renderer_lpv_stats ls;
    renderer_get_lpv_stats(r, &ls);
    double eye_sum[4] = {0, 0, 0, 0};
    if (render_eyes(o, r, eyes, eye_count, f, eye_sum) != 0)
        return -1;
    int closed = 0;
    if (o->gl == GLCTX_GLFW) { /* a window shows the first eye; closing it ends the run */
        renderer_present(r, o->width, o->height);
        closed = !glctx_swap(ctx);
    }
    char hex[17];
    snprintf(hex, sizeof hex, "%016llx", (unsigned long long)checksum);
    cJSON *jf = cJSON_CreateObject();
    cJSON_AddNumberToObject(jf, "frame", f);
    cJSON_AddStringToObject(jf, "lpv_checksum", hex); /* the GI method's checksum */
    cJSON_AddBoolToObject(jf, "skipped", ls.skipped_this_frame);
    if (isfinite(ls.last_residual)) /* +Inf before two computed frames: JSON null */
        cJSON_AddNumberToObject(jf, "residual", ls.last_residual);
    else
        cJSON_AddNullToObject(jf, "residual");
    double vals[M_COUNT] = {t.rsm_ms, t.inject_ms, t.propagate_ms, t.frame_host_ms,
                            eye_sum[0], eye_sum[1], eye_sum[2], eye_sum[3]};
    for (int m = 0; m < M_COUNT; m++) {
        cJSON_AddNumberToObject(jf, stage_names[m], vals[m]);
        stage_ms[m] = vals[m];
    }
    cJSON_AddItemToArray(frames, jf);
    /* renderer_timings' inject and propagate are the vpl method's selection and maps. */
    int vpl = renderer_get_gi(r) == FRAME_GI_VPL;
    printf("frame %d: %s %s%s, frame pass %.2f ms (rsm %.2f gpu, %s %.2f, %s %.2f), "
           "eyes %.2f ms\n", f, frame_gi_name(renderer_get_gi(r)), hex,
           ls.skipped_this_frame ? " (skipped, converged)" : "", t.frame_host_ms, t.rsm_ms,
           vpl ? "select" : "inject", t.inject_ms, vpl ? "shadow maps" : "propagate",
           t.propagate_ms, eye_sum[3]);
    return closed;
}

/* Medians over the frames run (GPU timer results arrive a few frames late: the first
 * frames report 0 there), then report.json when --out is given. */
static int report_finish(const node_options *o, renderer *r, cJSON *report, double *samples,
                         int frames_run)
{
    cJSON *med = cJSON_AddObjectToObject(report, "median");
    double m[M_COUNT];
    for (int k = 0; k < M_COUNT; k++) {
        m[k] = median(samples + (size_t)k * o->frames, frames_run);
        cJSON_AddNumberToObject(med, stage_names[k], m[k]);
    }
    renderer_lpv_stats ls;
    renderer_get_lpv_stats(r, &ls);
    cJSON_AddNumberToObject(report, "frames_skipped", (double)ls.frames_skipped);
    double total = m[M_FRAME] + m[M_EYE];
    cJSON_AddNumberToObject(report, "lpv_share", total > 0 ? (m[M_INJECT] + m[M_PROP]) / total : 0);
    if (!o->out)
        return 0;
    char path[4096];
    snprintf(path, sizeof path, "%s/report.json", o->out);
    char *text = cJSON_Print(report);
    FILE *f = fopen(path, "w");
    int rc = 0;
    if (!text || !f || fputs(text, f) < 0) {
        fprintf(stderr, "cavelight-node: cannot write %s\n", path);
        rc = 1;
    }
    if (f)
        fclose(f);
    free(text);
    return rc;
}

/* The GL path: context, renderer (its lattice and steps from --budget-ms if given), the
 * frames, the report. */
static int run_gl(const node_options *o, const scene *sc, const eye_setup *eyes, int eye_count,
                  frame_params *fp)
{
    char err[512];
    glctx_desc gd = {.backend = o->gl, .width = o->width, .height = o->height,
                     .title = "cavelight-node", .visible = o->gl == GLCTX_GLFW};
    glctx *ctx = glctx_create(&gd, err, sizeof err);
    if (!ctx) {
        /* The context's own message names no option: the one to try is this mode's. */
        fprintf(stderr, "cavelight-node: %s%s\n", err,
                o->gl == GLCTX_GLFW ? "; or render without a window: --gl egl" : "");
        return 1;
    }
    renderer_desc rd = {
        .gl = glctx_gl(ctx), .scene = sc, .lpv_backend = o->lpv, .rsm_size = o->rsm,
        .lattice_cells = o->lattice, .lattice_cell_budget = o->lattice_total,
        .threads = o->threads, .vpl_point = o->vpl_point, .vpl_visibility = o->vpl_visibility,
        .ism_size = o->ism_size, .ism_points = o->ism_points, .vpl_interleave = o->vpl_interleave,
        .lpv_gl_tiles = o->tiles, .lpv_mode = o->mode, .converge_threshold = o->converge_threshold,
        .gi = fp->gi,
    };
    cJSON *report = cJSON_CreateObject();
    renderer *r = NULL;
    double *samples = xcalloc((size_t)o->frames * M_COUNT, sizeof *samples);
    int rc = 1, frames_run = 0;
    lpv_budget_choice budget;
    if (o->budget_ms > 0) {
        if (choose_budget(o, &rd, fp, &budget, report) != 0)
            goto out;
        rd.lattice_cells = budget.axis_cells;
        fp->lpv_steps = budget.steps;
    }
    if (!(r = renderer_create(&rd, err, sizeof err))) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        goto out;
    }
    report_setup(report, o, ctx, r, sc, fp);
    cJSON *frames = cJSON_AddArrayToObject(report, "frames");
    int step = 0;
    for (int f = 0; f < o->frames && step == 0; f++) {
        double stage_ms[M_COUNT];
        if ((step = render_frame(o, ctx, r, eyes, eye_count, fp, f, frames, stage_ms)) < 0)
            goto out;
        for (int m = 0; m < M_COUNT; m++)
            samples[(size_t)m * o->frames + f] = stage_ms[m];
        frames_run++;
    }
    rc = report_finish(o, r, report, samples, frames_run);
out:
    free(samples);
    cJSON_Delete(report);
    renderer_destroy(r);
    glctx_destroy(ctx);
    return rc;
}

int standalone_run(const node_options *o)
{
    char err[512];
    if (o->out && folder_create(o->out, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        return 1;
    }
    scene sc;
    scene_load_desc sd = {.allow_outside_paths = o->allow_outside_paths};
    if (scene_load_with(o->scene, &sd, &sc, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        return 1;
    }
    if (sc.warning[0])
        fprintf(stderr, "cavelight-node: warning: scene %s: %s\n", o->scene, sc.warning);
    if (o->camera && scene_pick_camera(&sc, o->camera, err, sizeof err) != 0) {
        fprintf(stderr, "cavelight-node: --camera: %s\n", err);
        scene_free(&sc);
        return 1;
    }
    if (sc.light_added) {
        char note[400];
        scene_light_added_note(&sc, o->scene, note, sizeof note);
        fprintf(stderr, "cavelight-node: warning: %s\n", note);
    }
    node_options opt = *o;
    /* The scene's camera (the file's first, or --camera's), else the default view; the
     * command line's position, target and field of view win. */
    scene_camera cam;
    scene_default_camera(&sc, &cam);
    if (opt.have_position)
        memcpy(cam.position, opt.position, sizeof opt.position);
    if (opt.have_target)
        memcpy(cam.target, opt.target, sizeof opt.target);
    if (opt.have_position || opt.have_target)
        memset(cam.up, 0, sizeof cam.up);
    if (opt.yfov > 0) {
        cam.yfov = opt.yfov;
        cam.orthographic = 0;
    }
    if (!opt.have_height && cam.aspect > 0 && !opt.have_screen)
        opt.height = (int)fmin(fmax(lround(opt.width / cam.aspect), 1), 16384);
    eye_setup eyes[2];
    int eye_count, rc = 1;
    if (make_views(&opt, &sc, &cam, eyes, &eye_count) == 0) {
        frame_params fp;
        standalone_frame_params(o, &sc, &eyes[0].view, &fp);
        /* No tracker: the head stands between the eyes, where the vpl method's view rule
         * casts its rays from (vpl_view.h). */
        for (int i = 0; i < 3; i++)
            fp.head[12 + i] = 0.5f * (eyes[0].view.eye_position[i] +
                                      eyes[eye_count - 1].view.eye_position[i]);
        if (o->reference) {
            reference_cli_desc rd = {.scene = &sc, .scene_name = o->scene, .params = &fp,
                                     .view = &eyes[0].view, .threads = o->threads,
                                     .samples = o->samples, .bounces = o->bounces,
                                     .seed = o->seed, .out = o->out};
            rc = reference_cli_run(&rd);
        } else {
            rc = run_gl(&opt, &sc, eyes, eye_count, &fp);
        }
    }
    scene_free(&sc);
    return rc;
}
