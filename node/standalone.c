/* standalone: cavelight-node --standalone (see standalone.h). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/folder.h"
#include "frame/frame_params.h"
#include "gl/glctx.h"
#include "image/image.h"
#include "frame/exposure.h"
#include "gi/gi_settings.h"
#include "gi/gi_budget.h"
#include "base/vec3.h"
#include "base/xalloc.h"
#include "frame/frame_view.h"
#include "frame/offaxis.h"
#include "present/present.h"
#include "reference/reference_cli.h"
#include "renderer.h"
#include "renderer_hud.h"
#include "scene/scene_load.h"
#include "standalone.h"
#include "standalone_app.h"

void standalone_frame_params(const node_options *o, const scene *s, const renderer_view *first_eye,
                             frame_params *out)
{
    *out = o->frame;
    frame_params_lights_from_scene(out, s);
    if (o->exposure_auto)
        out->exposure = exposure_from_light(out, s);
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
    const char *kind[4] = {"final", "direct", "indirect", "ao"};
    const float *data[4] = {img->final, img->direct, img->indirect, img->ao};
    for (int k = 0; k < 4 && data[k]; k++) { /* the AO only when the frame asks for it */
        snprintf(path, sizeof path, "%s/frame%04d_%s_%s.pfm", o->out, frame, eye, kind[k]);
        if (image_write_pfm(path, img->width, img->height, data[k], err, sizeof err))
            return fprintf(stderr, "cavelight-node: %s\n", err), -1;
    }
    return 0;
}

/* The budget plan's frames on a renderer of their own (gi_budget.h): what the method's
 * candidate settings cost on this machine. */
static int measure_budget(const renderer_desc *base, gi_budget_plan *plan)
{
    char err[512];
    frame_params f;
    gi_budget_plan_frame(plan, 0, &f);
    renderer_desc rd = *base;
    rd.first = &f;
    renderer *r = renderer_create(&rd, err, sizeof err);
    if (!r)
        return fprintf(stderr, "cavelight-node: --budget-ms: %s\n", err), -1;
    for (int i = 0; i < gi_budget_plan_frames(plan); i++) {
        gi_budget_plan_frame(plan, i, &f);
        renderer_frame_pass(r, &f);
        renderer_timings t;
        renderer_get_timings(r, &t);
        gi_budget_plan_record(plan, i, t.frame_host_ms);
    }
    renderer_destroy(r);
    return 0;
}

/* --budget-ms: the method's settings from this machine's measured costs (gi_budget.h),
 * into fp and the report. */
static int choose_budget(const node_options *o, const renderer_desc *base, frame_params *fp,
                         cJSON *report)
{
    char err[512];
    gi_budget_choice choice;
    gi_budget_plan *plan =
        gi_budget_plan_create(fp, base->scene->bounds_min, base->scene->bounds_max);
    int rc = measure_budget(base, plan);
    if (rc == 0 && (rc = gi_budget_plan_choose(plan, o->budget_ms, fp, &choice, err, sizeof err)))
        fprintf(stderr, "cavelight-node: --budget-ms: %s\n", err);
    gi_budget_plan_destroy(plan);
    if (rc != 0)
        return -1;
    printf("cavelight-node: budget %.3g ms: %s, predicted %.3g ms per frame%s (%s)\n",
           o->budget_ms, choice.summary, choice.predicted_ms,
           choice.fits ? "" : ", over budget even at the cheapest choice", choice.detail);
    cJSON *jb = cJSON_AddObjectToObject(report, "budget");
    cJSON_AddNumberToObject(jb, "budget_ms", o->budget_ms);
    for (int i = 0; i < choice.figure_count; i++)
        cJSON_AddNumberToObject(jb, choice.figure[i].name, choice.figure[i].value);
    cJSON_AddNumberToObject(jb, "predicted_ms", choice.predicted_ms);
    cJSON_AddBoolToObject(jb, "fits", choice.fits);
    return 0;
}

/* Per-stage milliseconds of every frame run, for the report's medians: the renderer's,
 * the GI method's own (gi_stats), the eyes'. */
enum { M_RSM, M_GI, M_FRAME, M_GBUF, M_SHADE, M_FINAL, M_EYE, M_COUNT };
static const char *const stage_names[M_COUNT] = {
    "rsm_ms", "gi_ms", "frame_host_ms", "gbuffer_ms", "shade_ms", "final_ms", "eye_host_ms",
};

/* What the run is: context, scene, the GI method and every setting of it and of the
 * frame, as the renderer uses them. */
static void report_setup(cJSON *report, const node_options *o, glctx *ctx, renderer *r,
                         const scene *sc, const frame_params *fp)
{
    frame_params sane = *fp;
    gi_frame_sanitize(&sane);
    int method = gi_active(renderer_gi(r));
    const char *name = gi_method_at(method)->name;
    printf("cavelight-node: %s, %s, scene %s (%zu triangles), GI %s\n", glctx_describe(ctx),
           glctx_renderer(ctx), o->scene, sc->triangle_count, name);
    cJSON_AddStringToObject(report, "scene", o->scene);
    cJSON_AddStringToObject(report, "gl", glctx_describe(ctx));
    cJSON_AddStringToObject(report, "gl_renderer", glctx_renderer(ctx));
    cJSON_AddStringToObject(report, "gi", name);
    cJSON *js = cJSON_AddObjectToObject(report, "settings");
    for (int i = 0; i < gi_option_count(); i++) {
        const gi_option *g = gi_option_at(i);
        if (g->method >= 0 && g->method != method)
            continue;
        char text[64];
        setting_value v = gi_option_get(g, &sane);
        setting_format(g->row, v, text, sizeof text);
        if (g->row->kind == SETTING_CHOICE)
            cJSON_AddStringToObject(js, g->row->name, text);
        else
            cJSON_AddNumberToObject(js, g->row->name, g->row->kind == SETTING_FLOAT ? v.f : v.i);
    }
    cJSON_AddNumberToObject(report, "triangles", (double)sc->triangle_count);
    cJSON_AddNumberToObject(report, "width", o->width);
    cJSON_AddNumberToObject(report, "height", o->height);
    cJSON_AddNumberToObject(report, "rsm", sane.rsm_size);
    cJSON_AddNumberToObject(report, "steps", sane.lpv_steps);
}

/* The GI method's stages and figures (gi_stats) as name: value, into obj. */
static void add_stats(cJSON *obj, const gi_stats *g)
{
    for (int i = 0; i < g->stage_count; i++) {
        char key[64];
        snprintf(key, sizeof key, "%s_ms", g->stage[i].name);
        cJSON_AddNumberToObject(obj, key, g->stage[i].value);
    }
    for (int i = 0; i < g->figure_count; i++) {
        if (isfinite(g->figure[i].value)) /* +Inf (no residual yet): JSON null */
            cJSON_AddNumberToObject(obj, g->figure[i].name, g->figure[i].value);
        else
            cJSON_AddNullToObject(obj, g->figure[i].name);
    }
}

/* The eye passes of one frame: images written, the first eye handed to the window, stage
 * times summed over the eyes. */
static int render_eyes(const node_options *o, renderer *r, present *out, const eye_setup *eyes,
                       int eye_count, int f, double eye_sum[4], standalone_app *app)
{
    renderer_view views[2];
    for (int e = 0; e < eye_count; e++)
        views[e] = eyes[e].view;
    renderer_screen(r, views, eye_count); /* one light assignment for both eyes */
    for (int e = 0; e < eye_count; e++) {
        renderer_image img;
        if (app)
            standalone_app_eye(app, eye_count == 1 ? 0 : 2 * e - 1);
        if (renderer_eye_pass(r, &eyes[e].view, o->pfm, &img) != 0) {
            fprintf(stderr, "cavelight-node: frame %d, eye %s: %s\n", f, eyes[e].name,
                    renderer_last_error(r));
            return -1;
        }
        if (o->out && write_images(o, f, eyes[e].name, &img) != 0)
            return -1;
        if (e == 0)
            memcpy(present_source(out, 0), img.rgb, (size_t)img.width * img.height * 3);
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
static int render_frame(const node_options *o, present *out, renderer *r, const eye_setup *eyes,
                        int eye_count, frame_params *fp, int f, cJSON *frames,
                        double stage_ms[M_COUNT], standalone_app *app)
{
    fp->version = (uint64_t)f;
    fp->time = f / 60.0;
    if (app)
        standalone_app_step(app, r, fp, f);
    if (f > 0 && fp->light_count > 0)
        fp->lights[0].position[0] += o->light_drift;
    uint64_t checksum = renderer_frame_pass(r, fp);
    renderer_timings t;
    renderer_get_timings(r, &t);
    double eye_sum[4] = {0, 0, 0, 0};
    if (render_eyes(o, r, out, eyes, eye_count, f, eye_sum, app) != 0)
        return -1;
    /* A window (--gl glfw) shows the first eye; closing it ends the run. */
    char err[512];
    present_frame_desc pf = {.version = (uint64_t)f, .display_gamma = fp->display_gamma};
    int h = gpu_timer_begin(renderer_gpu_timer(r), "present"); /* its context is the renderer's */
    int closed = present_frame(out, &pf, err, sizeof err);
    gpu_timer_end(renderer_gpu_timer(r), h);
    if (closed < 0) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        return -1;
    }
    char hex[17];
    snprintf(hex, sizeof hex, "%016llx", (unsigned long long)checksum);
    cJSON *jf = cJSON_CreateObject();
    cJSON_AddNumberToObject(jf, "frame", f);
    cJSON_AddStringToObject(jf, "checksum", hex); /* the GI method's, as READY carries it */
    add_stats(jf, &t.gi);
    renderer_timings late; /* the GPU's stages as far as they arrived (a frame or more late) */
    renderer_get_timings(r, &late);
    cJSON *gpu = cJSON_AddObjectToObject(jf, "gpu_ms");
    for (int i = 0; i < late.gpu.count; i++)
        cJSON_AddNumberToObject(gpu, late.gpu.stage[i].name, late.gpu.stage[i].ms);
    double vals[M_COUNT] = {t.rsm_ms, gi_stats_total_ms(&t.gi), t.frame_host_ms,
                            eye_sum[0], eye_sum[1], eye_sum[2], eye_sum[3]};
    for (int m = 0; m < M_COUNT; m++) {
        cJSON_AddNumberToObject(jf, stage_names[m], vals[m]);
        stage_ms[m] = vals[m];
    }
    cJSON_AddItemToArray(frames, jf);
    char stages[256] = "";
    for (int i = 0; i < t.gi.stage_count; i++)
        snprintf(stages + strlen(stages), sizeof stages - strlen(stages), ", %s %.2f",
                 t.gi.stage[i].name, t.gi.stage[i].value);
    printf("frame %d: %s %s, frame pass %.2f ms (rsm %.2f gpu%s), eyes %.2f ms\n", f,
           gi_method_at(gi_active(renderer_gi(r)))->name, hex, t.frame_host_ms, t.rsm_ms, stages,
           eye_sum[3]);
    return closed;
}

/* Medians over the frames run (GPU timer results arrive a few frames late: the first
 * frames report 0 there), the last frame's GI figures, then report.json when --out is
 * given. */
static int report_finish(const node_options *o, renderer *r, cJSON *report, double *samples,
                         int frames_run)
{
    cJSON *med = cJSON_AddObjectToObject(report, "median");
    double m[M_COUNT];
    for (int k = 0; k < M_COUNT; k++) {
        m[k] = median(samples + (size_t)k * o->frames, frames_run);
        cJSON_AddNumberToObject(med, stage_names[k], m[k]);
    }
    renderer_timings t;
    renderer_get_timings(r, &t);
    add_stats(report, &t.gi);
    double total = m[M_FRAME] + m[M_EYE];
    cJSON_AddNumberToObject(report, "gi_share", total > 0 ? m[M_GI] / total : 0);
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

/* The GL path: context, renderer (its method's settings from --budget-ms if given), the
 * frames, the report. */
static int run_gl(const node_options *o, const scene *sc, const eye_setup *eyes, int eye_count,
                  frame_params *fp)
{
    char err[512];
    present_viewport vp = {.name = "window", .width = o->width, .height = o->height};
    present_desc pd = {.output = o->gl == GLCTX_GLFW ? PRESENT_WINDOW : PRESENT_HEADLESS, .backend = o->gl,
                       .log_name = "cavelight-node", .viewport_count = 1, .viewports = &vp,
                       .title = "cavelight-node", .quiet = 1};
    present *out = present_create(&pd, err, sizeof err);
    if (!out) {
        /* The context's own message names no option: the one to try is this mode's. */
        fprintf(stderr, "cavelight-node: %s%s\n", err,
                o->gl == GLCTX_GLFW ? "; or render without a window: --gl egl" : "");
        return 1;
    }
    glctx *ctx = present_context(out);
    renderer_desc rd = {.gl = glctx_gl(ctx), .scene = sc, .first = fp, .threads = o->threads};
    cJSON *report = cJSON_CreateObject();
    renderer *r = NULL;
    standalone_app *app = NULL;
    double *samples = xcalloc((size_t)o->frames * M_COUNT, sizeof *samples);
    int rc = 1, frames_run = 0;
    if (o->budget_ms > 0 && choose_budget(o, &rd, fp, report) != 0)
        goto out;
    if (!(r = renderer_create(&rd, err, sizeof err))) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        goto out;
    }
    if (o->app && !(app = standalone_app_open(o->app, sc, ctx, err, sizeof err))) {
        fprintf(stderr, "cavelight-node: %s\n", err);
        goto out;
    }
    if (app)
        standalone_app_attach(app, r);
    report_setup(report, o, ctx, r, sc, fp);
    cJSON *frames = cJSON_AddArrayToObject(report, "frames");
    int step = 0;
    for (int f = 0; f < o->frames && step == 0; f++) {
        double stage_ms[M_COUNT];
        if ((step = render_frame(o, out, r, eyes, eye_count, fp, f, frames, stage_ms, app)) < 0)
            goto out;
        for (int m = 0; m < M_COUNT; m++)
            samples[(size_t)m * o->frames + f] = stage_ms[m];
        frames_run++;
    }
    rc = report_finish(o, r, report, samples, frames_run);
out:
    free(samples);
    cJSON_Delete(report);
    standalone_app_close(app);
    renderer_destroy(r);
    present_destroy(out);
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
    char note[400];
    if (scene_light_note(&sc, o->scene, note, sizeof note))
        fprintf(stderr, "cavelight-node: warning: %s\n", note);
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
         * casts its rays from (view_samples.h). */
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
